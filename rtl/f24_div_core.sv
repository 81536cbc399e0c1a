// f24_div_core: fp24 division, combinational (docs/fp24.md, hls/fp24/f24_div.c).
// Restoring radix-2 recurrence fully unrolled: M+3 subtract-and-select rows produce the
// quotient bits, the final remainder is the sticky bit; exponent subtractor; shared rounder.
// x/0 = Inf, 0/0 and Inf/Inf = default NaN, x/Inf = signed zero.
module f24_div_core #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  output logic [E+M:0] res_o
);
  localparam int W = 1 + E + M;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam int STEPS = M + 3;
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] DEFAULT_NAN = {1'b0, EMAX, 1'b1, {(M-1){1'b0}}};

  logic sign, a_nan, b_nan, take;
  logic [E-1:0] ea, eb;
  logic [M+2:0] rem, divisor;   // the remainder stays below 2 x divisor < 2^(M+2)
  logic [STEPS-1:0] quot;
  logic [30:0] sig;
  logic signed [E+2:0] exp;
  logic [W-1:0] rounded;

  f24_round_pack #(.E(E), .M(M)) u_round (.sign_i(sign), .exp_i(exp), .sig_i(sig), .res_o(rounded));

  always_comb begin
    sign = a_i[W-1] ^ b_i[W-1];
    ea = a_i[W-2:M];
    eb = b_i[W-2:M];
    a_nan = ea == EMAX && a_i[M-1:0] != 0;
    b_nan = eb == EMAX && b_i[M-1:0] != 0;
    rem = (M+3)'({1'b1, a_i[M-1:0]});
    divisor = (M+3)'({1'b1, b_i[M-1:0]});
    exp = (E+3)'(ea) - (E+3)'(eb) + (E+3)'(BIAS);
    if (rem < divisor) begin                     // quotient below one: one more dividend bit
      rem = rem << 1;
      exp = exp - 1;
    end
    quot = '0;
    for (int i = 0; i < STEPS; i++) begin
      take = rem >= divisor;
      quot = {quot[STEPS-2:0], take};
      rem = (rem - (take ? divisor : '0)) << 1;
    end
    sig = 31'({quot[STEPS-1:1], quot[0] | (rem != 0)}) << (30 - (STEPS - 1));
  end

  always_comb begin // specials, in the order of the C model, else the rounded result
    if (a_nan || b_nan)
      res_o = DEFAULT_NAN;
    else if (ea == EMAX)
      res_o = eb == EMAX ? DEFAULT_NAN : {sign, EMAX, {M{1'b0}}};
    else if (eb == EMAX)
      res_o = {sign, {(E+M){1'b0}}};
    else if (eb == 0)
      res_o = ea == 0 ? DEFAULT_NAN : {sign, EMAX, {M{1'b0}}};
    else if (ea == 0)
      res_o = {sign, {(E+M){1'b0}}};
    else
      res_o = rounded;
  end
endmodule
