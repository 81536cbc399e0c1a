// tb_accum: test wrapper (not synthesized) around rgs_accum, an active ray's share of the RGS's
// accumulation (rtl/rgs_accum.sv), with thread ids of 6 bits; the C++ bench (tb_accum.cpp) drives
// it with gaps and back pressure and checks every result against the C model.
module tb_accum #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  input  logic                      valid_i,
  output logic                      ready_o,
  input  logic [5:0]                tid_i,
  input  logic [E+M:0]              eta_i,
  input  logic [12:0]               kd_i,
  input  logic [12:0]               kr_i,
  input  logic [12:0]               kt_i,
  input  logic [12:0]               ks_i,
  input  logic                      sf_valid_i,
  input  logic [3*(E+M+1)-1:0]      o_i,
  input  logic [3*(E+M+1)-1:0]      d_i,
  input  logic [3*(E+M+1)-1:0]      n_i,
  input  logic [E+M:0]              t_hat_i,
  input  logic                      entering_i,
  input  logic [3*16-1:0]           base_i,
  input  logic [3*16-1:0]           emission_i,
  input  logic [3*16-1:0]           tint_i,
  input  logic [3*16-1:0]           weight_i,
  input  logic [3*16-1:0]           diffuse_i,
  input  logic [3*16-1:0]           highlight_i,
  input  logic [3*16-1:0]           acc_i,
  input  logic [E+M:0]              eps_i,
  input  logic                      spawn_i,
  input  logic                      live_i,
  output logic                      valid_o,
  input  logic                      ready_i,
  output logic [5:0]                tid_o,
  output logic [3*16-1:0]           acc_o,
  output logic [3*(E+M+1)-1:0]      r_o_o,
  output logic [3*(E+M+1)-1:0]      r_d_o,
  output logic [3*16-1:0]           r_w_o,
  output logic                      r_active_o,
  output logic [3*(E+M+1)-1:0]      t_o_o,
  output logic [3*(E+M+1)-1:0]      t_d_o,
  output logic [3*16-1:0]           t_w_o,
  output logic                      t_active_o,
  output logic                      steps_o
);
  rgs_accum #(.E(E), .M(M), .TID_BITS(6)) u_dut (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(valid_i), .ready_o(ready_o), .tid_i(tid_i), .eta_i(eta_i), .kd_i(kd_i),
    .kr_i(kr_i), .kt_i(kt_i), .ks_i(ks_i), .sf_valid_i(sf_valid_i), .o_i(o_i), .d_i(d_i), .n_i(n_i),
    .t_hat_i(t_hat_i), .entering_i(entering_i), .base_i(base_i), .emission_i(emission_i), .tint_i(tint_i),
    .weight_i(weight_i), .diffuse_i(diffuse_i), .highlight_i(highlight_i), .acc_i(acc_i), .eps_i(eps_i),
    .spawn_i(spawn_i), .live_i(live_i), .valid_o(valid_o), .ready_i(ready_i), .tid_o(tid_o), .acc_o(acc_o),
    .r_o_o(r_o_o), .r_d_o(r_d_o), .r_w_o(r_w_o), .r_active_o(r_active_o), .t_o_o(t_o_o), .t_d_o(t_d_o),
    .t_w_o(t_w_o), .t_active_o(t_active_o), .steps_o(steps_o));
endmodule
