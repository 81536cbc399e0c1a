// f24_mul: pipelined fp24 multiplier (f24_mul_core + f24_pipe), docs/fp24.md semantics bit for bit.
// Latency STAGES (default 3) cycles, II = 1. Resources: one (M+1)x(M+1) multiplier (DSP blocks
// on Xilinx), an exponent adder, the rounder.
module f24_mul #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int STAGES = 3
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  output logic         valid_o,
  output logic [E+M:0] res_o
);
  logic [E+M:0] res;
  f24_mul_core #(.E(E), .M(M)) u_core (.a_i(a_i), .b_i(b_i), .res_o(res));
  f24_pipe #(.W(1 + E + M), .STAGES(STAGES)) u_pipe (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i), .data_i(res), .valid_o(valid_o), .data_o(res_o)
  );
endmodule
