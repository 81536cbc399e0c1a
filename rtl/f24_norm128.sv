// f24_norm128: the normalizer of the exact dot product (rtl/f24_sum_exact.sv): a nonzero
// 128-bit magnitude a worth a * 2^scale into the shared rounder's input, the significand with its
// leading one at bit 30 and everything below ORed into bit 0, and the exponent, clamped to the
// rounder's range (at most -2: zero even after a carry; at least the Inf exponent: Inf).
// A binary-search leading-zero count merged with the shifter (shift by 64, 32, ..., 1 where the
// bits above are zero), an OR tree for the sticky bit, a 12-bit exponent adder, in three segments
// with R1, R2, R3 pipeline registers at the cuts after them (the caller spreads its own STAGES
// over them; 0 is a wire): 1 shift by 64, 32; 2 by 16, 8, 4; 3 by 2, 1, sticky, exponent.
// Latency R1 + R2 + R3 cycles (default 3), II = 1. Resources: a 128-bit 7-level shifter with zero
// detectors, a 97-input OR, 12-bit exponent adders and clamp, about 3 x 150 pipeline FFs.
module f24_norm128 #(
  parameter int E = 7,
  parameter int R1 = 1,
  parameter int R2 = 1,
  parameter int R3 = 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                en_i,
  input  logic [127:0]        a_i,
  input  logic signed [15:0]  scale_i,   // the window's scale (small: about +-2^(E+1))
  output logic [30:0]         sig_o,
  output logic signed [E+2:0] exp_o
);
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic signed [11:0] EXP_MAX = 12'((1 << E) - 1);

  // ---- segment 1: by 64, 32
  logic [127:0] x1;
  logic [1:0] n1;
  always_comb begin
    x1 = a_i;
    n1 = '0;
    if (x1[127:64] == 0) begin x1 = x1 << 64; n1[1] = 1'b1; end
    if (x1[127:96] == 0) begin x1 = x1 << 32; n1[0] = 1'b1; end
  end
  logic [127:0] x2;
  logic [1:0] n2;
  /* verilator lint_off UNUSEDSIGNAL */
  logic signed [15:0] s2;       // 12 bits of it are used
  /* verilator lint_on UNUSEDSIGNAL */
  /* verilator lint_off PINCONNECTEMPTY */
  f24_pipe #(.W(128 + 2 + 16), .STAGES(R1)) u_c1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .data_i({x1, n1, scale_i}), .valid_o(), .data_o({x2, n2, s2}));

  // ---- segment 2: by 16, 8, 4; the exponent but for the last two shift bits (12 bits hold it:
  // |scale| stays below 2^(E+2))
  logic [127:0] xs2;
  logic [4:0] ns2;
  logic signed [11:0] base2;
  always_comb begin
    xs2 = x2;
    ns2 = {n2, 3'b000};
    if (xs2[127:112] == 0) begin xs2 = xs2 << 16; ns2[2] = 1'b1; end
    if (xs2[127:120] == 0) begin xs2 = xs2 << 8; ns2[1] = 1'b1; end
    if (xs2[127:124] == 0) begin xs2 = xs2 << 4; ns2[0] = 1'b1; end
    base2 = 12'sd127 - 12'({ns2, 2'b00}) + 12'(s2) + 12'(BIAS);
  end
  logic [127:0] x3;
  logic signed [11:0] base3;
  f24_pipe #(.W(128 + 12), .STAGES(R2)) u_c2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .data_i({xs2, base2}), .valid_o(), .data_o({x3, base3}));

  // ---- segment 3: by 2, 1; sticky (the bits below bit 94 ORed beside the shift); exponent
  logic [127:0] xs3;
  logic [1:0] n;
  logic low, sticky;
  logic [30:0] sig;
  logic signed [11:0] e;
  logic signed [E+2:0] ex;
  always_comb begin
    xs3 = x3;
    n = '0;
    if (xs3[127:126] == 0) begin xs3 = xs3 << 2; n[1] = 1'b1; end
    if (xs3[127] == 0) begin xs3 = xs3 << 1; n[0] = 1'b1; end
    low = x3[93:0] != 0;                         // bits 96 .. 0 after the shift by n: x3[96-n:0]
    sticky = low | (n <= 2'd2 && x3[94]) | (n <= 2'd1 && x3[95]) | (n == 2'd0 && x3[96]);
    sig = {xs3[127:98], xs3[97] | sticky};      // the leading one (bit 127 - n of a) at bit 30
    e = base3 - 12'(n);
    ex = (E+3)'(e < -12'sd2 ? -12'sd2 : e > EXP_MAX ? EXP_MAX : e);
  end
  f24_pipe #(.W(31 + E + 3), .STAGES(R3)) u_c3 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .data_i({sig, ex}), .valid_o(), .data_o({sig_o, exp_o}));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
