// tb_f24_ops: test wrapper (not synthesized) feeding one operand pair per cycle to every fp24
// operator in parallel: adder, adder in subtract mode, multiplier, divider, comparator, and the
// int-to-fp24 converter at SCALE 0 and -1 on the pair's bits {a, b} (the low 32 bits), and the
// unary square root and integer conversion on the first operand. Each result comes out with its operator's latency; the C++ bench (tb_f24_ops.cpp) checks each
// against the C model on every transaction.
module tb_f24_ops #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  output logic         add_valid_o,
  output logic [E+M:0] add_o,
  output logic         sub_valid_o,
  output logic [E+M:0] sub_o,
  output logic         mul_valid_o,
  output logic [E+M:0] mul_o,
  output logic         div_valid_o,
  output logic [E+M:0] div_o,
  output logic         cmp_valid_o,
  output logic [3:0]   cmp_flags_o,
  output logic [E+M:0] min_o,
  output logic [E+M:0] max_o,
  output logic         cvt_valid_o,
  output logic [E+M:0] cvt_o,
  output logic         half_valid_o,
  output logic [E+M:0] half_o,
  output logic         sqrt_valid_o,
  output logic [E+M:0] sqrt_o,
  output logic         to_i32_valid_o,
  output logic [31:0]  to_i32_o
);
  /* verilator lint_off UNUSEDSIGNAL */
  logic [2*(E+M+1)-1:0] ab;   // the converters take its low 32 bits
  /* verilator lint_on UNUSEDSIGNAL */
  assign ab = {a_i, b_i};
  f24_add #(.E(E), .M(M)) u_add (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i), .a_i(a_i),
                                 .b_i(b_i), .sub_i(1'b0), .valid_o(add_valid_o), .res_o(add_o));
  f24_add #(.E(E), .M(M)) u_sub (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i), .a_i(a_i),
                                 .b_i(b_i), .sub_i(1'b1), .valid_o(sub_valid_o), .res_o(sub_o));
  f24_mul #(.E(E), .M(M)) u_mul (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i), .a_i(a_i),
                                 .b_i(b_i), .valid_o(mul_valid_o), .res_o(mul_o));
  f24_div #(.E(E), .M(M)) u_div (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i), .a_i(a_i),
                                 .b_i(b_i), .valid_o(div_valid_o), .res_o(div_o));
  f24_cmp #(.E(E), .M(M)) u_cmp (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i), .a_i(a_i),
                                 .b_i(b_i), .valid_o(cmp_valid_o), .flags_o(cmp_flags_o), .min_o(min_o),
                                 .max_o(max_o));
  f24_from_i32 #(.E(E), .M(M)) u_cvt (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i), .a_i(ab[31:0]),
                                      .valid_o(cvt_valid_o), .res_o(cvt_o));
  f24_from_i32 #(.E(E), .M(M), .SCALE(-1)) u_half (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i),
                                                   .a_i(ab[31:0]), .valid_o(half_valid_o), .res_o(half_o));
  f24_sqrt #(.E(E), .M(M)) u_sqrt (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i), .a_i(a_i),
                                   .valid_o(sqrt_valid_o), .res_o(sqrt_o));
  f24_to_i32 #(.E(E), .M(M)) u_to_i32 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i), .a_i(a_i),
                                       .valid_o(to_i32_valid_o), .res_o(to_i32_o));
endmodule
