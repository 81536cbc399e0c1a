// f24_add_core: fp24 addition/subtraction, combinational (docs/fp24.md, hls/fp24/f24_add.c).
// Swap by magnitude, align with sticky (31 bits), add or subtract, leading-zero count and
// normalize, shared rounder. Exact cancellation gives +0; NaN in or Inf - Inf gives the default
// NaN; a zero operand passes the other through.
module f24_add_core #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  input  logic         sub_i,
  output logic [E+M:0] res_o
);
  localparam int W = 1 + E + M;
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] DEFAULT_NAN = {1'b0, EMAX, 1'b1, {(M-1){1'b0}}};

  function automatic logic [5:0] clz32(input logic [31:0] x);
    clz32 = 6'd32;
    for (int i = 0; i < 32; i++) if (x[i]) clz32 = 6'(31 - i);
  endfunction

  logic sa, sb, s_big, s_small;
  logic [E-1:0] ea, eb, e_big, e_small;
  logic [30:0] siga, sigb, sig_big, sig_small, aligned, sum, diff;
  logic [E:0] gap;
  logic [5:0] shift;
  logic rp_sign;
  logic signed [E+2:0] rp_exp;
  logic [30:0] rp_sig;
  logic [W-1:0] rounded;

  f24_round_pack #(.E(E), .M(M)) u_round (.sign_i(rp_sign), .exp_i(rp_exp), .sig_i(rp_sig), .res_o(rounded));

  always_comb begin
    sa = a_i[W-1];
    sb = b_i[W-1] ^ sub_i;
    ea = a_i[W-2:M];
    eb = b_i[W-2:M];
    siga = 31'({1'b1, a_i[M-1:0]}) << (29 - M);
    sigb = 31'({1'b1, b_i[M-1:0]}) << (29 - M);
    if (ea < eb || (ea == eb && siga < sigb)) begin
      {s_big, e_big, sig_big, s_small, e_small, sig_small} = {sb, eb, sigb, sa, ea, siga};
    end else begin
      {s_big, e_big, sig_big, s_small, e_small, sig_small} = {sa, ea, siga, sb, eb, sigb};
    end
    gap = {1'b0, e_big} - {1'b0, e_small};
    if (gap >= 31) aligned = 31'(sig_small != 0);
    else aligned = (sig_small >> gap) | 31'((sig_small & ((31'd1 << gap) - 1)) != 0);
    sum = sig_big + aligned;
    diff = sig_big - aligned;
    shift = clz32({1'b0, diff}) - 6'd1;
    rp_sign = s_big;
    if (s_big == s_small) begin
      if (sum[30]) begin
        rp_exp = (E+3)'(e_big) + 1;
        rp_sig = sum;
      end else begin
        rp_exp = (E+3)'(e_big);
        rp_sig = sum << 1;
      end
    end else begin
      rp_exp = (E+3)'(e_big) + 1 - (E+3)'(shift);
      rp_sig = diff << shift;
    end
  end

  always_comb begin // specials, in the order of the C model, else the rounded result
    if (ea == EMAX || eb == EMAX) begin
      if ((ea == EMAX && a_i[M-1:0] != 0) || (eb == EMAX && b_i[M-1:0] != 0) || (ea == eb && sa != sb))
        res_o = DEFAULT_NAN;
      else
        res_o = {ea == EMAX ? sa : sb, EMAX, {M{1'b0}}};
    end else if (ea == 0) begin
      res_o = eb == 0 ? {sa & sb, {(E+M){1'b0}}} : {sb, eb, b_i[M-1:0]};
    end else if (eb == 0) begin
      res_o = {sa, ea, a_i[M-1:0]};
    end else if (s_big != s_small && diff == 0) begin
      res_o = '0; // exact cancellation: +0
    end else begin
      res_o = rounded;
    end
  end
endmodule
