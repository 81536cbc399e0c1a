// f24_sum_exact: pipelined exact dot product of N fp24 pairs into a double word
// (f24_sum_exact_core + f24_pipe; hls/fp24/f24_sum_exact.c bit for bit). Latency STAGES (default
// 4: multipliers, alignment, 128-bit sum, rounding), II = 1. The operator of the accuracy datapath
// (docs/numerics.md): N = 8 in the transformation unit's wide mode, 4 in the rebase unit, 9 for the
// intersection unit's plane distance.
module f24_sum_exact #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int N = 4,
  parameter int STAGES = 4
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 en_i,
  input  logic                 valid_i,
  input  logic [N*(E+M+1)-1:0] a_i,
  input  logic [N*(E+M+1)-1:0] b_i,
  output logic                 valid_o,
  output logic [E+M:0]         hi_o,
  output logic [E+M:0]         lo_o
);
  logic [E+M:0] hi, lo;
  f24_sum_exact_core #(.E(E), .M(M), .N(N)) u_core (.a_i(a_i), .b_i(b_i), .hi_o(hi), .lo_o(lo));
  f24_pipe #(.W(2 * (1 + E + M)), .STAGES(STAGES)) u_pipe (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i), .data_i({hi, lo}), .valid_o(valid_o),
    .data_o({hi_o, lo_o})
  );
endmodule
