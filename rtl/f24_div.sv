// f24_div: pipelined fp24 divider (f24_div_core + f24_pipe), docs/fp24.md semantics bit for bit.
// Latency STAGES (default 6) cycles, II = 1: the M+3 rows of the restoring recurrence are
// unrolled (one (M+3)-bit subtract-and-select per row), so a divider accepts one division per
// cycle as the traversal unit needs (4 dividers per 4-ray packet step, Table 2).
module f24_div #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int STAGES = 6
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
  f24_div_core #(.E(E), .M(M)) u_core (.a_i(a_i), .b_i(b_i), .res_o(res));
  f24_pipe #(.W(1 + E + M), .STAGES(STAGES)) u_pipe (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i), .data_i(res), .valid_o(valid_o), .data_o(res_o)
  );
endmodule
