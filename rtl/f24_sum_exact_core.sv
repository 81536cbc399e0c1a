// f24_sum_exact_core: exact dot product of N fp24 pairs with a double-word result, combinational
// (hls/fp24/f24_sum_exact.c, docs/numerics.md): hi = the exact sum rounded, lo = the exact
// remainder rounded. The N products are exact ((M+1)x(M+1) bits), aligned to the largest product
// exponent in a 128-bit two's-complement window with HEAD bits of headroom (bits below it ORed into
// its last bit), summed; then a normalizer (f24_norm128) and the shared rounder for hi, the
// remainder, and a normalizer and the rounder again for lo. Specials as the C model: NaN in,
// Inf * 0 or Inf - Inf give the default NaN, an Inf product Inf; a sum of zero products is -0
// only if every one is -0.
// Resources: N (M+1)x(M+1) multipliers, N 128-bit aligners, a 128-bit N-input adder, two
// normalizers, two rounders.
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

  // per term: exponents, sign, classes, the exact product
  logic [E-1:0] ea [N], eb [N];
  logic sgn [N], is_nan [N], is_inf [N], live [N];
  logic [2*M+1:0] prod [N];
  for (genvar k = 0; k < N; k++) begin : g_term
    assign ea[k] = a_i[k*W+M +: E];
    assign eb[k] = b_i[k*W+M +: E];
    assign sgn[k] = a_i[k*W+W-1] ^ b_i[k*W+W-1];
    assign is_nan[k] = (ea[k] == EMAX && a_i[k*W +: M] != 0) || (eb[k] == EMAX && b_i[k*W +: M] != 0);
    assign is_inf[k] = ea[k] == EMAX || eb[k] == EMAX;
    assign live[k] = !is_inf[k] && ea[k] != 0 && eb[k] != 0;
    assign prod[k] = {1'b1, a_i[k*W +: M]} * {1'b1, b_i[k*W +: M]};
  end

  logic nan, inf, inf_sign, zero_sign, any, sign, rest_neg;
  logic signed [31:0] emax, scale, at, down;
  logic [127:0] term, acc, mag, rest, rmag;
  logic [W-1:0] hi, lo;
  logic [30:0] sig_hi, sig_lo;
  logic signed [E+2:0] exp_hi, exp_lo;

  always_comb begin // specials and the largest product exponent
    nan = 1'b0;
    inf = 1'b0;
    inf_sign = 1'b0;
    zero_sign = 1'b1;
    any = 1'b0;
    emax = 0;
    for (int k = 0; k < N; k++) begin
      zero_sign = zero_sign & sgn[k];
      if (is_nan[k] || (is_inf[k] && (ea[k] == 0 || eb[k] == 0 || (inf && inf_sign != sgn[k]))))
        nan = 1'b1;
      if (is_inf[k]) begin
        inf = 1'b1;
        inf_sign = sgn[k];
      end
      if (live[k] && (!any || 32'(ea[k]) + 32'(eb[k]) > emax)) begin
        emax = 32'(ea[k]) + 32'(eb[k]);
        any = 1'b1;
      end
    end
  end

  always_comb begin // aligned, signed, summed
    acc = '0;
    for (int k = 0; k < N; k++) begin
      down = emax - 32'(ea[k]) - 32'(eb[k]);
      if (down <= TOP)
        term = 128'(prod[k]) << (TOP - down);
      else if (down - TOP >= 64)
        term = 128'(prod[k] != 0);
      else
        term = {64'd0, (64'(prod[k]) >> (down - TOP)) | 64'((64'(prod[k]) & ((64'd1 << (down - TOP)) - 64'd1)) != 0)};
      if (live[k])
        acc = acc + (sgn[k] ? -term : term);
    end
    sign = acc[127];
    mag = sign ? -acc : acc;
    scale = emax - 2 * BIAS - 2 * M - TOP;
  end

  f24_norm128 #(.E(E)) u_norm_hi (.a_i(mag), .scale_i(scale), .sig_o(sig_hi), .exp_o(exp_hi));
  f24_round_pack #(.E(E), .M(M)) u_hi (.sign_i(sign), .exp_i(exp_hi), .sig_i(sig_hi), .res_o(hi));

  always_comb begin // the remainder after the rounded hi, for lo
    at = 32'(hi[W-2:M]) - BIAS - M - scale;       // hi's last bit in the window
    rest = mag - (at >= 0 ? (128'({1'b1, hi[M-1:0]}) << at) : mag);
    rest_neg = rest[127];
    rmag = rest_neg ? -rest : rest;
  end

  f24_norm128 #(.E(E)) u_norm_lo (.a_i(rmag), .scale_i(scale), .sig_o(sig_lo), .exp_o(exp_lo));
  f24_round_pack #(.E(E), .M(M)) u_lo (.sign_i(sign ^ rest_neg), .exp_i(exp_lo), .sig_i(sig_lo), .res_o(lo));

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
