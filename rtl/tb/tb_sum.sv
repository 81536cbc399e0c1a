// tb_sum: test wrapper (not synthesized) feeding one set of N operand pairs per cycle to the exact
// dot product f24_sum_exact; the C++ bench (tb_sum.cpp) checks hi and lo against the C model on
// every transaction.
module tb_sum #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int N = 9
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 valid_i,
  input  logic [N*(E+M+1)-1:0] a_i,
  input  logic [N*(E+M+1)-1:0] b_i,
  output logic                 valid_o,
  output logic [E+M:0]         hi_o,
  output logic [E+M:0]         lo_o
);
  f24_sum_exact #(.E(E), .M(M), .N(N)) u_sum (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i),
                                              .a_i(a_i), .b_i(b_i), .valid_o(valid_o), .hi_o(hi_o), .lo_o(lo_o));
endmodule
