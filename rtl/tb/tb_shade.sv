// tb_shade: test wrapper (not synthesized) around the RGS's shading datapath, each unit with its own
// input stream and handshake: the decoding of the compact shading record's vertex normals
// (shade_rec_decode, ports n_*), the bilinear texture sample (tex_bilinear, ports t_*, whose
// memory port the bench serves) and the frame of a hit (rgs_frame, ports f_*). The C++ bench (tb_shade.cpp) drives valid_i and ready_i with gaps
// and back pressure and checks every result against the C model.
module tb_shade #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 n_valid_i,
  output logic                 n_ready_o,
  input  logic [5:0]           n_tid_i,
  input  logic [41:0]          n_code_i,
  output logic                 n_valid_o,
  input  logic                 n_ready_i,
  output logic [5:0]           n_tid_o,
  output logic [3*(E+M+1)-1:0] n_o,
  input  logic                 t_valid_i,
  output logic                 t_ready_o,
  input  logic [5:0]           t_tid_i,
  input  logic [E+M:0]         t_s_i,
  input  logic [E+M:0]         t_t_i,
  input  logic [31:0]          t_width_i,
  input  logic [31:0]          t_height_i,
  input  logic [31:0]          t_addr_i,
  output logic                 t_req_valid_o,
  input  logic                 t_req_ready_i,
  output logic [31:0]          t_req_addr_o,
  input  logic                 t_rsp_valid_i,
  output logic                 t_rsp_ready_o,
  input  logic [31:0]          t_rsp_data_i,
  output logic                 t_valid_o,
  input  logic                 t_ready_i,
  output logic [5:0]           t_tid_o,
  output logic [47:0]          t_rgb_o,
  input  logic                 f_valid_i,
  output logic                 f_ready_o,
  input  logic [5:0]           f_tid_i,
  input  logic [3*(E+M+1)-1:0] f_o_i,
  input  logic [3*(E+M+1)-1:0] f_d_i,
  input  logic [E+M:0]         f_t_i,
  input  logic [E+M:0]         f_cos_n_i,
  input  logic [3*(E+M+1)-1:0] f_n_i,
  input  logic [9*(E+M+1)-1:0] f_w2o_i,
  output logic                 f_valid_o,
  input  logic                 f_ready_i,
  output logic [5:0]           f_tid_o,
  output logic [3*(E+M+1)-1:0] f_d_o,
  output logic [3*(E+M+1)-1:0] f_n_o,
  output logic                 f_entering_o,
  output logic [E+M:0]         f_t_hat_o,
  output logic [3*(E+M+1)-1:0] f_p_o
);
  shade_rec_decode #(.E(E), .M(M), .TID_BITS(6)) u_dec (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(n_valid_i),
    .ready_o(n_ready_o), .tid_i(n_tid_i), .code_i(n_code_i), .valid_o(n_valid_o), .ready_i(n_ready_i),
    .tid_o(n_tid_o), .n_o(n_o));
  tex_bilinear #(.E(E), .M(M), .TID_BITS(6)) u_tex (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(t_valid_i),
    .ready_o(t_ready_o), .tid_i(t_tid_i), .s_i(t_s_i), .t_i(t_t_i), .width_i(t_width_i), .height_i(t_height_i),
    .addr_i(t_addr_i), .req_valid_o(t_req_valid_o), .req_ready_i(t_req_ready_i), .req_addr_o(t_req_addr_o),
    .rsp_valid_i(t_rsp_valid_i), .rsp_ready_o(t_rsp_ready_o), .rsp_data_i(t_rsp_data_i), .valid_o(t_valid_o),
    .ready_i(t_ready_i), .tid_o(t_tid_o), .rgb_o(t_rgb_o));
  rgs_frame #(.E(E), .M(M), .TID_BITS(6)) u_frame (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(f_valid_i),
    .ready_o(f_ready_o), .tid_i(f_tid_i), .o_i(f_o_i), .d_i(f_d_i), .t_i(f_t_i), .cos_n_i(f_cos_n_i), .n_i(f_n_i),
    .w2o_i(f_w2o_i), .valid_o(f_valid_o), .ready_i(f_ready_i), .tid_o(f_tid_o), .d_o(f_d_o), .n_o(f_n_o),
    .entering_o(f_entering_o), .t_hat_o(f_t_hat_o), .p_o(f_p_o));
endmodule
