// f24_sum_exact_core: exact dot product of N fp24 pairs with a double-word result, combinational
// (hls/fp24/f24_sum_exact.c, docs/numerics.md): hi = the exact sum rounded, lo = the exact
// remainder rounded. The N products are exact ((M+1)x(M+1) bits), aligned to the largest product
// exponent in a 128-bit two's-complement window with HEAD bits of headroom (bits below it ORed into
// its last bit), summed; then one leading-one detector, the shared rounder for hi, the remainder
// and the rounder again for lo. Specials as the C model: NaN in, Inf * 0 or Inf - Inf give the
// default NaN, an Inf product Inf; a sum of zero products is -0 only if every one is -0.
// Resources: N (M+1)x(M+1) multipliers, N 128-bit aligners, a 128-bit N-input adder, two
// 128-bit leading-one detectors and shifters, two rounders.
module f24_sum_exact_core #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int N = 4
) (
  input  logic [N*(E+M+1)-1:0] a_i,
  input  logic [N*(E+M+1)-1:0] b_i,
  output logic [E+M:0]         hi_o,
  output logic [E+M:0]         lo_o
);
  localparam int W = 1 + E + M;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam int HEAD = 5;
  localparam int TOP = 127 - HEAD - (2 * M + 1);  // where the largest product's last bit sits
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] DEFAULT_NAN = {1'b0, EMAX, 1'b1, {(M-1){1'b0}}};

  logic nan, inf, inf_sign, zero_sign, any, sign, rest_neg;
  int emax, scale, at;
  logic [127:0] acc, mag, rest, rmag;
  logic [W-1:0] hi, lo;
  logic [30:0] sig_hi, sig_lo;
  logic signed [E+2:0] exp_hi, exp_lo;

  // |a| * 2^scale with its leading one at p: the rounder's significand (sticky in bit 0) and exponent
  function automatic void window(input logic [127:0] a, input int scale_in, output logic [30:0] sig,
                                 output logic signed [E+2:0] exp);
    int p, e;
    p = 0;
    for (int i = 0; i < 128; i++)
      if (a[i]) p = i;
    if (p >= 30) begin
      sig = 31'(a >> (p - 30));
      sig[0] = sig[0] | ((a & ((128'd1 << (p - 30)) - 128'd1)) != 0);
    end else begin
      sig = 31'(a << (30 - p));
    end
    e = p + scale_in + BIAS;
    exp = (E+3)'(e < -2 ? -2 : e > int'(EMAX) ? int'(EMAX) : e); // the rounder's range: zero below, Inf above
  endfunction

  f24_round_pack #(.E(E), .M(M)) u_hi (.sign_i(sign), .exp_i(exp_hi), .sig_i(sig_hi), .res_o(hi));
  f24_round_pack #(.E(E), .M(M)) u_lo (.sign_i(sign ^ rest_neg), .exp_i(exp_lo), .sig_i(sig_lo), .res_o(lo));

  always_comb begin
    nan = 1'b0;
    inf = 1'b0;
    inf_sign = 1'b0;
    zero_sign = 1'b1;
    any = 1'b0;
    emax = 0;
    for (int k = 0; k < N; k++) begin
      logic [E-1:0] ea, eb;
      logic s;
      ea = a_i[k*W+M +: E];
      eb = b_i[k*W+M +: E];
      s = a_i[k*W+W-1] ^ b_i[k*W+W-1];
      zero_sign = zero_sign & s;
      if ((ea == EMAX && a_i[k*W +: M] != 0) || (eb == EMAX && b_i[k*W +: M] != 0))
        nan = 1'b1;
      else if (ea == EMAX || eb == EMAX) begin
        if (ea == 0 || eb == 0 || (inf && inf_sign != s)) nan = 1'b1;
        inf = 1'b1;
        inf_sign = s;
      end else if (ea != 0 && eb != 0 && (!any || int'(ea) + int'(eb) > emax)) begin
        emax = int'(ea) + int'(eb);
        any = 1'b1;
      end
    end
    acc = '0;
    for (int k = 0; k < N; k++) begin
      logic [E-1:0] ea, eb;
      logic [2*M+1:0] prod;
      logic [127:0] term;
      int down;
      ea = a_i[k*W+M +: E];
      eb = b_i[k*W+M +: E];
      prod = {1'b1, a_i[k*W +: M]} * {1'b1, b_i[k*W +: M]};
      down = emax - int'(ea) - int'(eb);
      if (down <= TOP)
        term = 128'(prod) << (TOP - down);
      else if (down - TOP >= 64)
        term = 128'(prod != 0);
      else
        term = {64'd0, (64'(prod) >> (down - TOP)) | 64'((64'(prod) & ((64'd1 << (down - TOP)) - 64'd1)) != 0)};
      if (ea != 0 && eb != 0 && ea != EMAX && eb != EMAX)
        acc = acc + ((a_i[k*W+W-1] ^ b_i[k*W+W-1]) ? -term : term);
    end
    sign = acc[127];
    mag = sign ? -acc : acc;
    scale = emax - 2 * BIAS - 2 * M - TOP;
    window(mag, scale, sig_hi, exp_hi);
  end

  always_comb begin // the remainder after the rounded hi, for lo
    at = int'(hi[W-2:M]) - BIAS - M - scale;       // hi's last bit in the window
    rest = mag - (at >= 0 ? (128'({1'b1, hi[M-1:0]}) << at) : mag);
    rest_neg = rest[127];
    rmag = rest_neg ? -rest : rest;
    window(rmag, scale, sig_lo, exp_lo);
  end

  always_comb begin // specials, then the rounded words
    if (nan) begin
      hi_o = DEFAULT_NAN;
      lo_o = '0;
    end else if (inf) begin
      hi_o = {inf_sign, EMAX, {M{1'b0}}};
      lo_o = '0;
    end else if (!any) begin
      hi_o = {zero_sign, {(E+M){1'b0}}};
      lo_o = '0;
    end else if (mag == 0) begin
      hi_o = '0;
      lo_o = '0;
    end else begin
      hi_o = hi;
      lo_o = (hi[W-2:M] == 0 || hi[W-2:M] == EMAX || at < 0 || rmag == 0) ? '0 : lo;
    end
  end
endmodule
