// tb_rgs_ctrl: test wrapper (not synthesized) around rgs_ctrl, the RGS's per-block control
// (rtl/rgs_ctrl.sv), with tags of 6 bits; the C++ bench (tb_rgs_ctrl.cpp) is its memory and its ray
// tracing core and checks every packet, pixel and primary hit against the C model.
module tb_rgs_ctrl #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  input  logic [3:0]                max_depth_i,
  input  logic                      shadows_i,
  input  logic                      blk_valid_i,
  output logic                      blk_ready_o,
  input  logic [5:0]                blk_tag_i,
  input  logic [31:0]               blk_x_i,
  input  logic [31:0]               blk_y_i,
  output logic                      tr_valid_o,
  input  logic                      tr_ready_i,
  output logic [5:0]                tr_tag_o,
  output logic [2:0]                tr_flags_o,
  output logic [3:0]                tr_active_o,
  output logic [4*3*(E+M+1)-1:0]    tr_o_o,
  output logic [4*3*(E+M+1)-1:0]    tr_d_o,
  output logic [4*(E+M+1)-1:0]      tr_tmin_o,
  output logic [4*(E+M+1)-1:0]      tr_tmax_o,
  input  logic                      hit_valid_i,
  output logic                      hit_ready_o,
  input  logic [4*32-1:0]           hit_inst_i,
  input  logic [4*32-1:0]           hit_tri_i,
  input  logic [4*(E+M+1)-1:0]      hit_t_i,
  input  logic [4*(E+M+1)-1:0]      hit_u_i,
  input  logic [4*(E+M+1)-1:0]      hit_v_i,
  input  logic [4*(E+M+1)-1:0]      hit_cos_i,
  output logic                      mem_req_valid_o,
  input  logic                      mem_req_ready_i,
  output logic [31:0]               mem_addr_o,
  input  logic                      mem_rsp_valid_i,
  input  logic [127:0]              mem_rdata_i,   // a line of 4 words
  output logic                      px_valid_o,
  input  logic                      px_ready_i,
  output logic [5:0]                px_tag_o,
  output logic [4*24-1:0]           px_rgb_o,
  output logic [4*32-1:0]           px_inst_o,
  output logic [4*32-1:0]           px_tri_o,
  output logic [4*(E+M+1)-1:0]      px_t_o,
  output logic [4*(E+M+1)-1:0]      px_u_o,
  output logic [4*(E+M+1)-1:0]      px_v_o,
  output logic [4*(E+M+1)-1:0]      px_cos_o,
  output logic [4:0]                st_o,       // the control's state: the bench's cycles per state
  output logic [4:0]                sst_o       // rgs_surface's state (its cycles per state in SURF)
);
  assign st_o = u_dut.st;
  assign sst_o = u_dut.u_surface.st;
  rgs_ctrl #(.E(E), .M(M), .TAG_BITS(6)) u_dut (
    .clk_i(clk_i), .rst_ni(rst_ni), .max_depth_i(max_depth_i), .shadows_i(shadows_i), .blk_valid_i(blk_valid_i),
    .blk_ready_o(blk_ready_o), .blk_tag_i(blk_tag_i), .blk_x_i(blk_x_i), .blk_y_i(blk_y_i), .tr_valid_o(tr_valid_o),
    .tr_ready_i(tr_ready_i), .tr_tag_o(tr_tag_o), .tr_flags_o(tr_flags_o), .tr_active_o(tr_active_o),
    .tr_o_o(tr_o_o), .tr_d_o(tr_d_o), .tr_tmin_o(tr_tmin_o), .tr_tmax_o(tr_tmax_o), .hit_valid_i(hit_valid_i),
    .hit_ready_o(hit_ready_o), .hit_inst_i(hit_inst_i), .hit_tri_i(hit_tri_i), .hit_t_i(hit_t_i), .hit_u_i(hit_u_i),
    .hit_v_i(hit_v_i), .hit_cos_i(hit_cos_i), .mem_req_valid_o(mem_req_valid_o), .mem_req_ready_i(mem_req_ready_i),
    .mem_addr_o(mem_addr_o), .mem_rsp_valid_i(mem_rsp_valid_i), .mem_rdata_i(mem_rdata_i), .px_valid_o(px_valid_o),
    .px_ready_i(px_ready_i), .px_tag_o(px_tag_o), .px_rgb_o(px_rgb_o), .px_inst_o(px_inst_o), .px_tri_o(px_tri_o),
    .px_t_o(px_t_o), .px_u_o(px_u_o), .px_v_o(px_v_o), .px_cos_o(px_cos_o));
endmodule
