// q12_mul: the product of two of the RGS's Q12 colour values (4096 = 1.0; docs/shading.md,
// "Integer colour arithmetic"; hls/units/rgs_ops.h `q_mul`): (a b + 2048) >> 12, saturated at
// 65535, bit for bit as the C's 32-bit arithmetic (whose a b + 2048 never wraps for 16-bit a, b).
// Used for the weights, the Phong power's squarings and the accumulation of light (paper section 3).
// Combinational (latency 0; the caller registers it); one 16 x 16-bit multiplier, an adder, a
// saturation mux.
module q12_mul (
  input  logic [15:0] a_i,
  input  logic [15:0] b_i,
  output logic [15:0] p_o
);
  /* verilator lint_off UNUSEDSIGNAL */
  logic [32:0] prod;  // the 12 bits below the Q12 point are dropped
  /* verilator lint_on UNUSEDSIGNAL */
  assign prod = 33'(a_i) * 33'(b_i) + 33'd2048;
  assign p_o = prod[32:28] != 0 ? 16'hFFFF : prod[27:12];
endmodule
