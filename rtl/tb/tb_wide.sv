// tb_wide: test wrapper (not synthesized) around the accuracy datapath's units, each with its own
// input stream and handshake: the rebase unit and the transformation unit's wide mode. The C++
// bench (tb_wide.cpp) drives valid_i and ready_i with gaps and back pressure and checks every
// result against the C model.
module tb_wide #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  b_valid_i,
  output logic                  b_ready_o,
  input  logic [3*(E+M+1)-1:0]  b_o_hi_i,
  input  logic [3*(E+M+1)-1:0]  b_o_lo_i,
  input  logic [3*(E+M+1)-1:0]  b_d_hi_i,
  input  logic [3*(E+M+1)-1:0]  b_d_lo_i,
  input  logic [E+M:0]          b_t_i,
  output logic                  b_valid_o,
  input  logic                  b_ready_i,
  output logic [3*(E+M+1)-1:0]  b_p_hi_o,
  output logic [3*(E+M+1)-1:0]  b_p_lo_o,
  output logic [E+M:0]          b_te_o,
  input  logic                  w_valid_i,
  output logic                  w_ready_o,
  input  logic [12*(E+M+1)-1:0] w_m_i,
  input  logic [3*(E+M+1)-1:0]  w_tlo_i,
  input  logic [3*(E+M+1)-1:0]  w_p_hi_i,
  input  logic [3*(E+M+1)-1:0]  w_p_lo_i,
  input  logic                  w_point_i,
  output logic                  w_valid_o,
  input  logic                  w_ready_i,
  output logic [3*(E+M+1)-1:0]  w_r_hi_o,
  output logic [3*(E+M+1)-1:0]  w_r_lo_o
);
  rebase_unit #(.E(E), .M(M)) u_b (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(b_valid_i), .ready_o(b_ready_o),
    .o_hi_i(b_o_hi_i), .o_lo_i(b_o_lo_i), .d_hi_i(b_d_hi_i), .d_lo_i(b_d_lo_i), .t_i(b_t_i), .valid_o(b_valid_o),
    .ready_i(b_ready_i), .p_hi_o(b_p_hi_o), .p_lo_o(b_p_lo_o), .te_o(b_te_o));
  xform_wide #(.E(E), .M(M)) u_w (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(w_valid_i), .ready_o(w_ready_o),
    .m_i(w_m_i), .tlo_i(w_tlo_i), .p_hi_i(w_p_hi_i), .p_lo_i(w_p_lo_i), .point_i(w_point_i), .valid_o(w_valid_o),
    .ready_i(w_ready_i), .r_hi_o(w_r_hi_o), .r_lo_o(w_r_lo_o));
endmodule
