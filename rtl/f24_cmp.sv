// f24_cmp: pipelined fp24 comparator with min/max (f24_cmp_core + f24_pipe), docs/fp24.md.
// Latency STAGES (default 1), II = 1. Resources: one (W+1)-bit key comparator, two W-bit muxes.
module f24_cmp #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int STAGES = 1
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  output logic         valid_o,
  output logic [3:0]   flags_o,  // {unordered, eq, le, lt}
  output logic [E+M:0] min_o,
  output logic [E+M:0] max_o
);
  localparam int W = 1 + E + M;
  logic lt, le, eq, unordered;
  logic [W-1:0] mn, mx;
  f24_cmp_core #(.E(E), .M(M)) u_core (
    .a_i(a_i), .b_i(b_i), .lt_o(lt), .le_o(le), .eq_o(eq), .unordered_o(unordered), .min_o(mn), .max_o(mx)
  );
  f24_pipe #(.W(4 + 2 * W), .STAGES(STAGES)) u_pipe (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i), .data_i({unordered, eq, le, lt, mn, mx}),
    .valid_o(valid_o), .data_o({flags_o, min_o, max_o})
  );
endmodule
