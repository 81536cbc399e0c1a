// f24_div: pipelined fp24 divider, docs/fp24.md semantics bit for bit (hls/fp24/f24_div.c).
// Restoring radix-2 digit recurrence unrolled: K = M + 5 combinational segments with STAGES
// pipeline registers spread evenly over the cuts after them (PULP FPnew style; the last cut always
// gets one, so the output is registered):
//   1       exponent difference, one more dividend bit when the quotient is below one, specials
//   2..M+4  one (M+3)-bit subtract-and-select row each: one quotient bit per row
//   M+5     sticky (remainder != 0), shared rounder (f24_round_pack), result or special
// x/0 = Inf, 0/0 and Inf/Inf = default NaN, x/Inf = signed zero.
// Latency STAGES cycles (default 11: about two rows per stage at e7m16, >= 60 MHz on iCE40 HX8K,
// docs/synth.md), one division per cycle (II = 1), as the traversal unit needs (4 dividers per
// 4-ray packet step, Table 2). Resources: M+3 rows of one (M+3)-bit subtractor and mux, the
// rounder, about STAGES x (2M + E + 35) pipeline FFs (remainder, divisor, quotient so far).
module f24_div #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int STAGES = 11
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
  localparam int W = 1 + E + M;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam int STEPS = M + 3;
  localparam int K = STEPS + 2;              // segments
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] DEFAULT_NAN = {1'b0, EMAX, 1'b1, {(M-1){1'b0}}};
  // the recurrence's state: special?, special result, sign, exponent, divisor, remainder, quotient
  localparam int B = 1 + W + 1 + (E + 3) + (M + 3) + (M + 3) + STEPS;

  // ---- segment 1: operands, exponent, specials
  logic sign, a_nan, b_nan, spec1;
  logic [E-1:0] ea, eb;
  logic [M+2:0] rem1, divisor;   // the remainder stays below 2 x divisor < 2^(M+2)
  logic signed [E+2:0] exp1;
  logic [W-1:0] spec_res1;
  always_comb begin
    sign = a_i[W-1] ^ b_i[W-1];
    ea = a_i[W-2:M];
    eb = b_i[W-2:M];
    a_nan = ea == EMAX && a_i[M-1:0] != 0;
    b_nan = eb == EMAX && b_i[M-1:0] != 0;
    rem1 = (M+3)'({1'b1, a_i[M-1:0]});
    divisor = (M+3)'({1'b1, b_i[M-1:0]});
    exp1 = (E+3)'(ea) - (E+3)'(eb) + (E+3)'(BIAS);
    if (rem1 < divisor) begin                     // quotient below one: one more dividend bit
      rem1 = rem1 << 1;
      exp1 = exp1 - 1;
    end
    spec1 = 1'b1;
    if (a_nan || b_nan)
      spec_res1 = DEFAULT_NAN;
    else if (ea == EMAX)
      spec_res1 = eb == EMAX ? DEFAULT_NAN : {sign, EMAX, {M{1'b0}}};
    else if (eb == EMAX)
      spec_res1 = {sign, {(E+M){1'b0}}};
    else if (eb == 0)
      spec_res1 = ea == 0 ? DEFAULT_NAN : {sign, EMAX, {M{1'b0}}};
    else if (ea == 0)
      spec_res1 = {sign, {(E+M){1'b0}}};
    else begin
      spec1 = 1'b0;
      spec_res1 = '0;
    end
  end

  logic [B-1:0] d [0:STEPS] /* verilator split_var */; // the state after segment 1 and each row
  logic v [0:STEPS] /* verilator split_var */;
  f24_pipe #(.W(B), .STAGES(1 * STAGES / K)) u_c1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i),
    .data_i({spec1, spec_res1, sign, exp1, divisor, rem1, STEPS'(0)}), .valid_o(v[0]), .data_o(d[0])
  );

  // ---- segments 2 .. M+4: one quotient bit per row
  for (genvar i = 0; i < STEPS; i++) begin : g_row
    logic [B-2*(M+3)-STEPS-1:0] side;
    logic [M+2:0] dv, rem, rem_n;
    /* verilator lint_off UNUSEDSIGNAL */
    logic [STEPS-1:0] quot;     // its top bit is shifted out
    /* verilator lint_on UNUSEDSIGNAL */
    logic [M+3:0] diff;         // rem - dv with its borrow: one carry chain, then a mux
    logic take;
    always_comb begin
      {side, dv, rem, quot} = d[i];
      diff = {1'b0, rem} - {1'b0, dv};
      take = !diff[M+3];
      rem_n = (take ? diff[M+2:0] : rem) << 1;
    end
    f24_pipe #(.W(B), .STAGES((i + 2) * STAGES / K - (i + 1) * STAGES / K)) u_row (
      .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v[i]),
      .data_i({side, dv, rem_n, quot[STEPS-2:0], take}), .valid_o(v[i+1]), .data_o(d[i+1])
    );
  end

  // ---- segment M+5: sticky, round, or the special result
  logic specl, signl;
  logic [W-1:0] spec_resl;
  logic signed [E+2:0] expl;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [M+2:0] dvl;              // the divisor is no longer needed
  /* verilator lint_on UNUSEDSIGNAL */
  logic [M+2:0] reml;
  logic [STEPS-1:0] quotl;
  logic [30:0] sig;
  always_comb begin
    {specl, spec_resl, signl, expl, dvl, reml, quotl} = d[STEPS];
    sig = 31'({quotl[STEPS-1:1], quotl[0] | (reml != 0)}) << (30 - (STEPS - 1));
  end
  f24_round_stage #(.E(E), .M(M), .STAGES(STAGES - (K - 1) * STAGES / K)) u_cl (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v[STEPS]), .spec_i(specl), .spec_res_i(spec_resl),
    .sign_i(signl), .exp_i(expl), .sig_i(sig), .valid_o(valid_o), .res_o(res_o)
  );
endmodule
