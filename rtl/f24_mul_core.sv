// f24_mul_core: fp24 multiplication, combinational (docs/fp24.md, hls/fp24/f24_mul.c).
// (M+1) x (M+1) significand multiplier, exponent adder, 1-bit normalize with sticky, shared
// rounder. NaN in or 0 x Inf gives the default NaN; the sign is the xor also for zeros.
module f24_mul_core #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  output logic [E+M:0] res_o
);
  localparam int W = 1 + E + M;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] DEFAULT_NAN = {1'b0, EMAX, 1'b1, {(M-1){1'b0}}};

  logic sign, carry, a_nan, b_nan;
  logic [E-1:0] ea, eb;
  logic [2*M+1:0] prod;
  logic [63:0] wide;
  logic [5:0] lead;
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
    prod = {1'b1, a_i[M-1:0]} * {1'b1, b_i[M-1:0]};   // in [2^2M, 2^(2M+2))
    carry = prod[2*M+1];
    lead = 6'(2 * M) + 6'(carry);                      // position of the leading one
    wide = 64'(prod);
    if (lead >= 30)
      sig = 31'((wide >> (lead - 30)) | 64'((wide & ((64'd1 << (lead - 30)) - 1)) != 0));
    else
      sig = 31'(wide << (30 - lead));
    exp = (E+3)'(ea) + (E+3)'(eb) - (E+3)'(BIAS) + (E+3)'(carry);
  end

  always_comb begin // specials, in the order of the C model, else the rounded result
    if (a_nan || b_nan)
      res_o = DEFAULT_NAN;
    else if (ea == EMAX || eb == EMAX)
      res_o = (ea == 0 || eb == 0) ? DEFAULT_NAN : {sign, EMAX, {M{1'b0}}};
    else if (ea == 0 || eb == 0)
      res_o = {sign, {(E+M){1'b0}}};
    else
      res_o = rounded;
  end
endmodule
