// f24_sqrt: pipelined fp24 square root, docs/fp24.md semantics bit for bit (hls/fp24/f24_sqrt.c),
// for the RGS's shading (Sec. 4; hls/units/rgs.c: vector lengths for the cosines, the refraction
// term; shade_rec.c: the decoded normal's 1/length).
// Restoring digit-by-digit root unrolled: K = M + 5 combinational segments with STAGES pipeline
// registers spread evenly over the cuts after them (PULP FPnew style; the last cut always gets
// one, so the output is registered):
//   1       specials, exponent halved (the radicand's significand doubled for an odd exponent)
//   2..M+4  one root bit per row: row i brings down two radicand bits and subtracts
//           4 x root + 1 from the partial remainder, an (i+4)-bit subtract-and-select (the
//           remainder is at most 2 x root, so it grows one bit per row, M+5 bits in the last row)
//   M+5     sticky (remainder != 0), shared rounder (f24_round_pack), result or special
// The C model subtracts on the whole (2M+6)-bit radicand; its root and its final remainder are
// the same integers as this narrow form's (both are the integer root and radicand - root^2).
// sqrt(+-0) = +-0 (and subnormal encodings), sqrt(+Inf) = +Inf, NaN and negative nonzero
// operands (including -Inf) give the default NaN; the result never overflows or underflows.
// Latency STAGES cycles (default 9: about 2.3 rows per stage, >= 60 MHz on iCE40 HX8K at e7m16;
// 8 missed it, docs/synth.md), one root per cycle (II = 1). Resources: M+3 rows of 4..M+6-bit
// subtractors and muxes (about (M+3)(M+10)/2 adder bits, on average a little more than half the
// divider's), the rounder, at most STAGES x (4M + 2E + 14) pipeline FFs (the state's full width;
// synthesis drops the radicand bits already brought down and the early rows' zero bits: 360 at
// e7m16).
module f24_sqrt #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int STAGES = 9
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  output logic         valid_o,
  output logic [E+M:0] res_o
);
  localparam int W = 1 + E + M;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam int STEPS = M + 3;              // root bits, the leading one at bit M+2
  localparam int K = STEPS + 2;              // segments
  localparam int RW = STEPS + 1;             // the final remainder (<= 2 x root) fits M+4 bits
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] DEFAULT_NAN = {1'b0, EMAX, 1'b1, {(M-1){1'b0}}};
  // the recurrence's state: special?, special result, exponent, radicand, remainder, root so far
  localparam int B = 1 + W + (E + 3) + (M + 2) + RW + STEPS;

  // ---- segment 1: specials, even exponent, radicand significand
  logic sign, nan, spec1;
  logic [E-1:0] ea;
  logic signed [E+2:0] e1, exp1;
  logic [M+1:0] rad1;              // the significand, doubled for an odd exponent
  logic [W-1:0] spec_res1;
  always_comb begin
    sign = a_i[W-1];
    ea = a_i[W-2:M];
    nan = ea == EMAX && a_i[M-1:0] != 0;
    e1 = (E+3)'(ea) - (E+3)'(BIAS);
    rad1 = e1[0] ? {1'b1, a_i[M-1:0], 1'b0} : {2'b01, a_i[M-1:0]};
    exp1 = (e1 >>> 1) + (E+3)'(BIAS);  // floor(e / 2): the odd exponent's bit went into rad1
    spec1 = 1'b1;
    if (nan || (sign && ea != 0))
      spec_res1 = DEFAULT_NAN;                 // NaN, negative nonzero, -Inf
    else if (ea == 0 || ea == EMAX)
      spec_res1 = {a_i[W-1:M], {M{1'b0}}};     // +-0 (subnormal encodings too) and +Inf
    else begin
      spec1 = 1'b0;
      spec_res1 = '0;
    end
  end

  logic [B-1:0] d [0:STEPS] /* verilator split_var */; // the state after segment 1 and each row
  logic v [0:STEPS] /* verilator split_var */;
  f24_pipe #(.W(B), .STAGES(1 * STAGES / K)) u_c1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i),
    .data_i({spec1, spec_res1, exp1, rad1, RW'(0), STEPS'(0)}), .valid_o(v[0]), .data_o(d[0])
  );

  // ---- segments 2 .. M+4: one root bit per row
  for (genvar i = 0; i < STEPS; i++) begin : g_row
    // the radicand is rad x 2^(M+4), 2 x STEPS bits; row i brings down its pair i from the top
    localparam int P = 2 * (STEPS - 1 - i);
    logic [1+W+E+2:0] side;
    /* verilator lint_off UNUSEDSIGNAL */
    logic [M+1:0] rad;           // pairs above and below this row's are not read here
    logic [RW-1:0] rem;          // at most 2 x root < 2^(i+1) before this row
    logic [STEPS-1:0] root;      // its low i bits hold the root so far
    logic [2*STEPS-1:0] radicand;
    logic [i+3:0] diff;          // cur - trial with its borrow: one carry chain, then a mux; bit i+2
                                 // is 0 whenever the difference is taken (remainder <= 2 x root)
    /* verilator lint_on UNUSEDSIGNAL */
    logic [i+2:0] cur;           // remainder x 4 + the pair
    logic [i+1:0] trial;         // root x 4 + 1
    logic [i+1:0] rem_n;
    logic take;
    always_comb begin
      {side, rad, rem, root} = d[i];
      radicand = {rad, (M+4)'(0)};
      cur = (i+3)'({rem, radicand[P+1:P]});
      trial = (i+2)'({root, 2'b01});
      diff = {1'b0, cur} - (i+4)'(trial);
      take = !diff[i+3];
      rem_n = take ? diff[i+1:0] : cur[i+1:0];
    end
    f24_pipe #(.W(B), .STAGES((i + 2) * STAGES / K - (i + 1) * STAGES / K)) u_row (
      .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v[i]),
      .data_i({side, rad, RW'(rem_n), root[STEPS-2:0], take}), .valid_o(v[i+1]), .data_o(d[i+1])
    );
  end

  // ---- segment M+5: sticky, round, or the special result
  logic specl;
  logic [W-1:0] spec_resl;
  logic signed [E+2:0] expl;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [M+1:0] radl;             // the radicand is no longer needed
  /* verilator lint_on UNUSEDSIGNAL */
  logic [RW-1:0] reml;
  logic [STEPS-1:0] rootl;
  logic [30:0] sig;
  always_comb begin
    {specl, spec_resl, expl, radl, reml, rootl} = d[STEPS];
    sig = 31'({rootl[STEPS-1:1], rootl[0] | (reml != 0)}) << (30 - (STEPS - 1));
  end
  f24_round_stage #(.E(E), .M(M), .STAGES(STAGES - (K - 1) * STAGES / K)) u_cl (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v[STEPS]), .spec_i(specl), .spec_res_i(spec_resl),
    .sign_i(1'b0), .exp_i(expl), .sig_i(sig), .valid_o(valid_o), .res_o(res_o)
  );
endmodule
