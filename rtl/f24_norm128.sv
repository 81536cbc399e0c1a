// f24_norm128: the normalizer of the exact dot product (rtl/f24_sum_exact_core.sv): a nonzero
// 128-bit magnitude a worth a * 2^scale into the shared rounder's input, the significand with its
// leading one at bit 30 and everything below ORed into bit 0, and the exponent, clamped to the
// rounder's range (at most -2: zero even after a carry; at least the Inf exponent: Inf).
// Combinational: a 128-bit leading-one detector, a 128-bit shifter, an OR tree for the sticky bit.
module f24_norm128 #(
  parameter int E = 7
) (
  input  logic [127:0]        a_i,
  input  logic signed [31:0]  scale_i,
  output logic [30:0]         sig_o,
  output logic signed [E+2:0] exp_o
);
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam int EXP_MAX = (1 << E) - 1;

  logic [6:0] p;
  logic [127:0] lost;
  logic signed [31:0] e;

  always_comb begin
    p = 7'd0;
    for (int i = 0; i < 128; i++)
      if (a_i[i]) p = 7'(i);
    lost = '0;
    if (p >= 7'd30) begin
      sig_o = 31'(a_i >> (p - 7'd30));
      lost = a_i & ((128'd1 << (p - 7'd30)) - 128'd1);
      sig_o[0] = sig_o[0] | (lost != 0);
    end else begin
      sig_o = 31'(a_i << (7'd30 - p));
    end
    e = 32'(p) + scale_i + BIAS;
    exp_o = (E+3)'(e < -2 ? -2 : e > EXP_MAX ? EXP_MAX : e);
  end
endmodule
