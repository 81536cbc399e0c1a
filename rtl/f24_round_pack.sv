// f24_round_pack: the shared rounder of every fp24 operator (docs/fp24.md, hls/fp24/f24_round_pack.c).
// Rounds an unrounded result (sign, exponent, significand with its leading one at bit 30 and the
// sticky bit ORed into bit 0) to nearest even, carries into the next binade, flushes tiny
// results to signed zero (tininess after rounding), overflows to Inf and packs.
// Combinational: one 31-bit incrementer, a tie detector, two exponent comparators.
module f24_round_pack #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic                sign_i,
  input  logic signed [E+2:0] exp_i,
  input  logic [30:0]         sig_i,
  output logic [E+M:0]        res_o
);
  localparam int RB = 30 - M;                  // round bits below the kept significand
  localparam logic signed [E+2:0] EXP_MAX = (E+3)'((1 << E) - 1);
  localparam logic [RB-1:0] HALF = RB'(1) << (RB - 1);

  logic [M+1:0] kept, kept_even;
  logic signed [E+2:0] exp_adj;
  logic tie;

  always_comb begin
    kept = {1'b0, sig_i[30:RB]} + (M+2)'(sig_i[RB-1]);  // (sig + half) >> RB
    tie = sig_i[RB-1:0] == HALF;
    kept_even = tie ? {kept[M+1:1], 1'b0} : kept;
    exp_adj = exp_i;
    if (kept_even[M+1]) begin                 // carried into the next binade
      kept_even = kept_even >> 1;
      exp_adj = exp_i + 1;
    end
    if (exp_adj <= 0)
      res_o = {sign_i, {(E+M){1'b0}}};        // tiny after rounding: signed zero
    else if (exp_adj >= EXP_MAX)
      res_o = {sign_i, {E{1'b1}}, {M{1'b0}}}; // overflow: Inf
    else
      res_o = {sign_i, exp_adj[E-1:0], kept_even[M-1:0]};
  end
endmodule
