// xform_wide: the transformation unit's wide mode (paper sections 2.1, 3, Figure 2 path d, with
// saarcor's accuracy datapath, docs/numerics.md; hls/units/xform_unit.c: xform_point_wide,
// xform_vector_wide). Maps a ray into an instance's object space in double words: per row r one
// exact dot product into (hi, lo), no rounding before it.
//   point_i = 1: m[r][0..2] * p.hi + m[r][0..2] * p.lo + m[r][3] * 1 + tlo_r * 1 (8 terms: the
//                origin in double words, the translation in two words, tlo the instance's low words)
//   point_i = 0: m[r][0..2] * p.hi (3 terms: a direction; p_lo_i, tlo_i and column 3 are ignored)
// A vector's five other terms become -0 * +0, which the exact sum ignores bit for bit: such a
// term is no NaN, no Inf, not live (no bits in the window), and its sign -0 is the identity of
// the rule that a sum of zero products is -0 only if every one is -0 (an AND of their signs). So
// one 8-term f24_sum_exact per row gives exactly the C's 3-term sum, signed zeros included.
// Datapath: three f24_sum_exact of 8 terms (all 24 products in one pass, each sum with its own
// multipliers, 6 a row: those of the terms times 1 are shifts; the C header's hardware note, the
// narrow unit's 9 multipliers used twice for a point, would halve them at half the rate), the
// vector mode's term muxes in front of them.
// Latency LATENCY = SUM_STAGES (default 25) cycles, one point or vector per cycle (II = 1).
// Resources: 3 x f24_sum_exact N = 8 (docs/synth.md).
// Handshake: valid/ready; the pipeline advances when the output is free or taken.
module xform_wide #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int SUM_STAGES = 25
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  valid_i,
  output logic                  ready_o,
  input  logic [12*(E+M+1)-1:0] m_i,     // rows m0 m1 m2 t, row 0 in the low words
  input  logic [3*(E+M+1)-1:0]  tlo_i,   // the translation's low words, x, y, z from the low word up
  input  logic [3*(E+M+1)-1:0]  p_hi_i,  // the point (or the vector) in double words
  input  logic [3*(E+M+1)-1:0]  p_lo_i,
  input  logic                  point_i, // 1: point (8 terms), 0: vector (3 terms)
  output logic                  valid_o,
  input  logic                  ready_i,
  output logic [3*(E+M+1)-1:0]  r_hi_o,
  output logic [3*(E+M+1)-1:0]  r_lo_o
);
  localparam int W = 1 + E + M;
  localparam int LATENCY = SUM_STAGES;
  localparam logic [W-1:0] NEG_ZERO = {1'b1, {(E+M){1'b0}}};
  logic en;
  logic [W-1:0] one;
  logic [5*W-1:0] b_point;
  assign en = ready_i || !valid_o;
  assign ready_o = en;
  // terms 3 .. 7's right operands: p.lo x, y, z, 1, 1 (a vector: +0); the 1 written with its
  // constant fraction, so that synthesis folds the multipliers of terms 6 and 7 (shifts)
  assign one = {2'b00, {(E-1){point_i}}, {M{1'b0}}};
  assign b_point = {one, one, point_i ? p_lo_i : '0};

  /* verilator lint_off PINCONNECTEMPTY */
  for (genvar r = 0; r < 3; r++) begin : g_row
    logic [3*W-1:0] m3;
    logic [5*W-1:0] a_point;
    assign m3 = m_i[4*r*W +: 3*W];
    // terms 3 .. 7's left operands: m0, m1, m2 (times p.lo), t, tlo_r (a vector: -0)
    assign a_point = point_i ? {tlo_i[r*W +: W], m_i[(4*r+3)*W +: W], m3} : {5{NEG_ZERO}};
    f24_sum_exact #(.E(E), .M(M), .N(8), .STAGES(SUM_STAGES)) u_sum (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .a_i({a_point, m3}), .b_i({b_point, p_hi_i}), .valid_o(), .hi_o(r_hi_o[r*W +: W]),
      .lo_o(r_lo_o[r*W +: W]));
  end

  // valid beside the sums
  f24_pipe #(.W(1), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
    .data_i(1'b0), .valid_o(valid_o), .data_o());
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
