// rebase_unit: the rebase unit (saarcor's accuracy datapath, docs/numerics.md; no section of the
// paper; hls/units/rebase_unit.c: rebase_origin, rebase_distance). Moves a ray's object-space
// origin to where it enters a leaf: te = rebase_distance(t) (t, or 0 when t is Inf or NaN: a ray
// without an entry distance moves nothing) and per component k one exact dot product of four
// terms into a double word, p_k = o.hi_k * 1 + o.lo_k * 1 + te * d.hi_k + te * d.lo_k, hi and lo
// (f24_sum_exact with N = 4, the C's f24q_sum_exact lane k). te leaves beside p: the intersection
// unit takes both (t = te + t').
// Datapath: three f24_sum_exact of 4 terms (each with its 4 (M+1)x(M+1) multipliers; the two
// terms o * 1 could skip theirs), the exponent test and mux of te in front of them, te delayed
// beside the sums in an f24_pipe.
// Latency LATENCY = SUM_STAGES (default 25) cycles, one ray per cycle (II = 1).
// Resources: 3 x f24_sum_exact N = 4 (docs/synth.md).
// Handshake: valid/ready; the pipeline advances when the output is free or taken.
module rebase_unit #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int SUM_STAGES = 25
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 valid_i,
  output logic                 ready_o,
  input  logic [3*(E+M+1)-1:0] o_hi_i,  // x, y, z from the low word up
  input  logic [3*(E+M+1)-1:0] o_lo_i,
  input  logic [3*(E+M+1)-1:0] d_hi_i,
  input  logic [3*(E+M+1)-1:0] d_lo_i,
  input  logic [E+M:0]         t_i,     // the entry distance (rebase_origin's t)
  output logic                 valid_o,
  input  logic                 ready_i,
  output logic [3*(E+M+1)-1:0] p_hi_o,
  output logic [3*(E+M+1)-1:0] p_lo_o,
  output logic [E+M:0]         te_o     // rebase_distance(t)
);
  localparam int W = 1 + E + M;
  localparam int LATENCY = SUM_STAGES;
  localparam logic [W-1:0] ONE = {2'b00, {(E-1){1'b1}}, {M{1'b0}}};
  logic en;
  logic [W-1:0] te;
  assign en = ready_i || !valid_o;
  assign ready_o = en;
  assign te = t_i[W-2:M] == '1 ? '0 : t_i;

  /* verilator lint_off PINCONNECTEMPTY */
  for (genvar k = 0; k < 3; k++) begin : g_comp
    // terms from the low word up: o.hi * 1, o.lo * 1, te * d.hi, te * d.lo (the C's order)
    f24_sum_exact #(.E(E), .M(M), .N(4), .STAGES(SUM_STAGES)) u_sum (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .a_i({te, te, o_lo_i[k*W +: W], o_hi_i[k*W +: W]}),
      .b_i({d_lo_i[k*W +: W], d_hi_i[k*W +: W], ONE, ONE}), .valid_o(), .hi_o(p_hi_o[k*W +: W]),
      .lo_o(p_lo_o[k*W +: W]));
  end

  // valid and te beside the sums
  f24_pipe #(.W(W), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
    .data_i(te), .valid_o(valid_o), .data_o(te_o));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
