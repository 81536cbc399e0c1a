// tb_surface: test wrapper (not synthesized) around rgs_surface, the surface the RGS shades at a
// hit (rtl/rgs_surface.sv), with thread ids of 6 bits; the C++ bench (tb_surface.cpp) is its memory
// and checks every surface and every read against the C model. The surface's frame (rgs_frame),
// vertex normals (rgs_normal) and texture samples' coordinates (tex_coords), which rgs_units shares
// among its surface units, are its own here: the frame's operand straight in, the normal's and the
// texture's through an rgs_arb of one requester each as in rgs_units.
module tb_surface #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  input  logic [31:0]               inst_base_i,
  input  logic [31:0]               obj_base_i,
  input  logic [31:0]               mat_base_i,
  input  logic [31:0]               tex_base_i,
  input  logic [31:0]               n_tex_i,
  input  logic                      valid_i,
  output logic                      ready_o,
  input  logic [5:0]                tid_i,
  input  logic                      active_i,
  input  logic [3*(E+M+1)-1:0]      o_i,
  input  logic [3*(E+M+1)-1:0]      d_i,
  input  logic [31:0]               inst_i,
  input  logic [31:0]               tri_i,
  input  logic [E+M:0]              t_i,
  input  logic [E+M:0]              u_i,
  input  logic [E+M:0]              v_i,
  input  logic [E+M:0]              cos_n_i,
  output logic                      mem_req_valid_o,
  input  logic                      mem_req_ready_i,
  output logic [31:0]               mem_addr_o,
  input  logic                      mem_rsp_valid_i,
  input  logic [127:0]              mem_rdata_i,   // a line of 4 words
  output logic                      valid_o,
  input  logic                      ready_i,
  output logic [5:0]                tid_o,
  output logic                      sf_valid_o,
  output logic [3*(E+M+1)-1:0]      p_o,
  output logic [3*(E+M+1)-1:0]      d_o,
  output logic [3*(E+M+1)-1:0]      n_o,
  output logic [E+M:0]              t_hat_o,
  output logic                      entering_o,
  output logic [31:0]               mat_o,
  output logic                      unlit_o,
  output logic [3:0]                k_o,
  output logic [E+M:0]              eta_o,
  output logic [12:0]               kd_o,
  output logic [12:0]               kr_o,
  output logic [12:0]               kt_o,
  output logic [12:0]               ks_o,
  output logic [3*16-1:0]           base_o,
  output logic [3*16-1:0]           emission_o,
  output logic [3*16-1:0]           tint_o
);
  localparam int W = 1 + E + M;
  logic fr_valid, fr_ready, fr_ovalid, fr_take, fr_entering;
  logic [3*W-1:0] fr_o, fr_d, fr_n, fr_dh, fr_nh, fr_p;
  logic [W-1:0] fr_t, fr_cos, fr_t_hat;
  logic [9*W-1:0] fr_w2o;
  /* verilator lint_off PINCONNECTEMPTY */
  rgs_frame #(.E(E), .M(M), .TID_BITS(1)) u_frame (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(fr_valid),
    .ready_o(fr_ready), .tid_i(1'b0), .o_i(fr_o), .d_i(fr_d), .t_i(fr_t), .cos_n_i(fr_cos), .n_i(fr_n), .w2o_i(fr_w2o),
    .valid_o(fr_ovalid), .ready_i(fr_take), .tid_o(), .d_o(fr_dh), .n_o(fr_nh), .entering_o(fr_entering),
    .t_hat_o(fr_t_hat), .p_o(fr_p));
  logic nv_req, nv_ack, nv_valid, nv_ready, nv_out, nv_zero;
  logic [125:0] nv_codes;
  logic [W-1:0] nv_u, nv_v;
  logic [126+2*W-1:0] nv_op;
  logic [3*W-1:0] nv_n;
  rgs_arb #(.N(1), .DW(126 + 2 * W)) u_nrm_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(nv_req),
    .data_i({nv_codes, nv_v, nv_u}), .ack_o(nv_ack), .valid_o(nv_valid), .ready_i(nv_ready), .index_o(), .data_o(nv_op));
  rgs_normal #(.E(E), .M(M), .TID_BITS(1), .DEPTH(2)) u_nrm (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(nv_valid),
    .ready_o(nv_ready), .tid_i(1'b0), .codes_i(nv_op[2*W +: 126]), .u_i(nv_op[0 +: W]), .v_i(nv_op[W +: W]),
    .valid_o(nv_out), .tid_o(), .n_o(nv_n), .zero_o(nv_zero));
  logic tx_req, tx_ack, tx_valid, tx_ready, tx_out;
  logic [W-1:0] tx_s, tx_t;
  logic [31:0] tx_width, tx_height, tx_addr, tx_row0, tx_row1, tx_x0, tx_x1;
  logic [2*W+95:0] tx_op;
  logic [8:0] tx_fx, tx_fy;
  rgs_arb #(.N(1), .DW(2 * W + 96)) u_tex_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(tx_req),
    .data_i({tx_s, tx_t, tx_width, tx_height, tx_addr}), .ack_o(tx_ack), .valid_o(tx_valid), .ready_i(tx_ready),
    .index_o(), .data_o(tx_op));
  tex_coords #(.E(E), .M(M), .TID_BITS(1)) u_tex (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(tx_valid),
    .ready_o(tx_ready), .tid_i(1'b0), .s_i(tx_op[W + 96 +: W]), .t_i(tx_op[96 +: W]), .width_i(tx_op[64 +: 32]),
    .height_i(tx_op[32 +: 32]), .addr_i(tx_op[0 +: 32]), .valid_o(tx_out), .ready_i(1'b1), .tid_o(),
    .row0_o(tx_row0), .row1_o(tx_row1), .x0_o(tx_x0), .x1_o(tx_x1), .fx_o(tx_fx), .fy_o(tx_fy));
  /* verilator lint_on PINCONNECTEMPTY */
  rgs_surface #(.E(E), .M(M), .TID_BITS(6)) u_dut (
    .clk_i(clk_i), .rst_ni(rst_ni), .inst_base_i(inst_base_i), .obj_base_i(obj_base_i), .mat_base_i(mat_base_i),
    .tex_base_i(tex_base_i), .n_tex_i(n_tex_i), .valid_i(valid_i), .ready_o(ready_o), .tid_i(tid_i),
    .active_i(active_i), .o_i(o_i), .d_i(d_i), .inst_i(inst_i), .tri_i(tri_i), .t_i(t_i), .u_i(u_i), .v_i(v_i),
    .cos_n_i(cos_n_i), .fr_valid_o(fr_valid), .fr_ready_i(fr_valid && fr_ready), .fr_o_o(fr_o), .fr_d_o(fr_d),
    .fr_t_o(fr_t), .fr_cos_n_o(fr_cos), .fr_n_o(fr_n), .fr_w2o_o(fr_w2o), .fr_valid_i(fr_ovalid), .fr_ready_o(fr_take),
    .fr_d_i(fr_dh), .fr_n_i(fr_nh), .fr_entering_i(fr_entering), .fr_t_hat_i(fr_t_hat), .fr_p_i(fr_p),
    .nrm_valid_o(nv_req), .nrm_ready_i(nv_ack), .nrm_codes_o(nv_codes), .nrm_u_o(nv_u), .nrm_v_o(nv_v),
    .nrm_valid_i(nv_out), .nrm_n_i(nv_n), .nrm_zero_i(nv_zero), .tx_valid_o(tx_req), .tx_ready_i(tx_ack),
    .tx_s_o(tx_s), .tx_t_o(tx_t), .tx_width_o(tx_width), .tx_height_o(tx_height), .tx_addr_o(tx_addr),
    .tx_valid_i(tx_out), .tx_row0_i(tx_row0), .tx_row1_i(tx_row1), .tx_x0_i(tx_x0), .tx_x1_i(tx_x1),
    .tx_fx_i(tx_fx), .tx_fy_i(tx_fy),
    .mem_req_valid_o(mem_req_valid_o), .mem_req_ready_i(mem_req_ready_i), .mem_addr_o(mem_addr_o),
    .mem_rsp_valid_i(mem_rsp_valid_i), .mem_rdata_i(mem_rdata_i), .valid_o(valid_o), .ready_i(ready_i),
    .tid_o(tid_o), .sf_valid_o(sf_valid_o), .p_o(p_o), .d_o(d_o), .n_o(n_o), .t_hat_o(t_hat_o),
    .entering_o(entering_o), .mat_o(mat_o), .unlit_o(unlit_o), .k_o(k_o), .eta_o(eta_o), .kd_o(kd_o), .kr_o(kr_o), .kt_o(kt_o), .ks_o(ks_o), .base_o(base_o), .emission_o(emission_o),
    .tint_o(tint_o));
endmodule
