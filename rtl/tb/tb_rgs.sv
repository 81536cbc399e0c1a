// tb_rgs: test wrapper (not synthesized) around the RGS's ray generation (rgs_raygen) and the
// tile controller (tile_ctrl). With chain_i the controller's blocks feed the ray generation (a
// frame as the pipe sees it); without, the C++ bench (tb_rgs.cpp) drives both inputs itself.
module tb_rgs #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  input  logic                   chain_i,
  input  logic                   cam_valid_i,
  output logic                   cam_ready_o,
  input  logic [3:0]             cam_idx_i,
  input  logic [31:0]            cam_word_i,
  input  logic                   blk_valid_i,
  output logic                   blk_ready_o,
  input  logic [31:0]            blk_x_i,
  input  logic [31:0]            blk_y_i,
  output logic                   pkt_valid_o,
  input  logic                   pkt_ready_i,
  output logic [3:0]             pkt_active_o,
  output logic [4*3*(E+M+1)-1:0] pkt_o_o,
  output logic [4*3*(E+M+1)-1:0] pkt_d_o,
  output logic [4*(E+M+1)-1:0]   pkt_tmin_o,
  output logic [4*(E+M+1)-1:0]   pkt_tmax_o,
  input  logic                   frame_valid_i,
  output logic                   frame_ready_o,
  input  logic [31:0]            x0_i,
  input  logic [31:0]            y0_i,
  input  logic [31:0]            x1_i,
  input  logic [31:0]            y1_i,
  input  logic [12:0]            tile_i,
  output logic                   tc_valid_o,
  input  logic                   tc_ready_i,
  output logic [31:0]            tc_x_o,
  output logic [31:0]            tc_y_o,
  output logic                   done_o
);
  logic rg_ready, rg_valid;
  logic [31:0] rg_x, rg_y;
  assign rg_valid = chain_i ? tc_valid_o : blk_valid_i;
  assign rg_x = chain_i ? tc_x_o : blk_x_i;
  assign rg_y = chain_i ? tc_y_o : blk_y_i;
  assign blk_ready_o = rg_ready;

  rgs_raygen #(.E(E), .M(M)) u_rg (.clk_i(clk_i), .rst_ni(rst_ni), .cam_valid_i(cam_valid_i),
    .cam_ready_o(cam_ready_o), .cam_idx_i(cam_idx_i), .cam_word_i(cam_word_i), .blk_valid_i(rg_valid),
    .blk_ready_o(rg_ready), .blk_x_i(rg_x), .blk_y_i(rg_y), .pkt_valid_o(pkt_valid_o), .pkt_ready_i(pkt_ready_i),
    .pkt_active_o(pkt_active_o), .pkt_o_o(pkt_o_o), .pkt_d_o(pkt_d_o), .pkt_tmin_o(pkt_tmin_o),
    .pkt_tmax_o(pkt_tmax_o));
  tile_ctrl u_tc (.clk_i(clk_i), .rst_ni(rst_ni), .frame_valid_i(frame_valid_i), .frame_ready_o(frame_ready_o),
    .x0_i(x0_i), .y0_i(y0_i), .x1_i(x1_i), .y1_i(y1_i), .tile_i(tile_i), .blk_valid_o(tc_valid_o),
    .blk_ready_i(chain_i ? rg_ready : tc_ready_i), .blk_x_o(tc_x_o), .blk_y_o(tc_y_o), .done_o(done_o));
endmodule
