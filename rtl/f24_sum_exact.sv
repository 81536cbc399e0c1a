// f24_sum_exact: pipelined exact dot product of N fp24 pairs into a double word
// (hls/fp24/f24_sum_exact.c bit for bit, docs/numerics.md): hi = the exact sum rounded, lo = the
// exact remainder rounded. The N products are exact ((M+1)x(M+1) bits), aligned to the largest
// product exponent in a 128-bit two's-complement window with HEAD bits of headroom (bits below it
// ORed into its last bit), summed; then a normalizer (f24_norm128) and the shared rounder for hi,
// the remainder, and a normalizer and the rounder again for lo. Specials as the C model: NaN in,
// Inf * 0 or Inf - Inf give the default NaN, an Inf product Inf; a sum of zero products is -0 only
// if every one is -0. The operator of the accuracy datapath: N = 8 in the transformation unit's
// wide mode, 4 in the rebase unit, 9 for the intersection unit's plane distance.
// 25 combinational segments with STAGES pipeline registers spread evenly over the cuts after
// them (PULP FPnew style; the last cut always gets one, so the outputs are registered); every
// 128-bit carry chain is split into two 64-bit halves in consecutive segments:
//   1 classes, specials, exponent sums and the comparison keys (0 for a dead term), partial
//     products (6-bit slices as f24_mul)
//   2 products, the largest live product exponent (a comparison matrix)
//   3-5 alignment: right shift of each product by 64, 32 | 16, 8, 4 | 2, 1 with sticky; negative
//       terms as ones' complement
//   6-7 carry-save sum of the N terms and the count of negative terms (3:2 compressors)
//   8-9 the sum's carry-propagate add, low and high half;  10-11 sign and magnitude
//  12-14 normalize hi (f24_norm128);  15 round hi (f24_round_pack)
//  16-17 hi's significand shifted to its place in the window;  18-19 the remainder mag - hi
//  20-21 its magnitude;  22-24 normalize lo;  25 round lo, specials
// Latency STAGES cycles (default 25), one set per cycle (II = 1). Resources: N (M+1)x(M+1)
// multipliers, N 128-bit aligners, a 128-bit (N+1)-input carry-save adder and five 128-bit
// adders, two normalizers, two rounders; at N >= 2 it does not fit an iCE40 HX8K
// (docs/synth.md gives the one-term form's clock there).
module f24_sum_exact #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int N = 4,
  parameter int STAGES = 25
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 en_i,
  input  logic                 valid_i,
  input  logic [N*(E+M+1)-1:0] a_i,
  input  logic [N*(E+M+1)-1:0] b_i,
  output logic                 valid_o,
  output logic [E+M:0]         hi_o,
  output logic [E+M:0]         lo_o
);
  localparam int W = 1 + E + M;
  localparam int K = 25;                     // segments
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam int HEAD = 5;
  localparam int TOP = 127 - HEAD - (2 * M + 1);  // where the largest product's last bit sits
  localparam int SL = 6;                     // bits of b per partial product
  localparam int NP = (M + 1 + SL - 1) / SL; // partial products per term
  localparam int PW = M + 1 + SL;            // bits of one partial product
  localparam int PB = 2 * M + 2;             // bits of one product
  localparam int XW = E + 1;                 // bits of a product exponent ea + eb
  localparam int CW = $clog2(N + 1);         // bits of the count of negative terms
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] DEFAULT_NAN = {1'b0, EMAX, 1'b1, {(M-1){1'b0}}};

  // cut c gets (c * STAGES / K) - ((c - 1) * STAGES / K) registers
  function automatic int regs(input int c);
    regs = c * STAGES / K - (c - 1) * STAGES / K;
  endfunction

  // ---- segment 1: classes, specials, exponent sums, partial products
  logic [E-1:0] ea [N], eb [N];
  logic [N-1:0] sgn1, live1, is_nan, is_inf;
  logic [N*XW-1:0] ex1, key1;
  logic [N*NP*PW-1:0] pp1;
  for (genvar k = 0; k < N; k++) begin : g_term
    logic [NP*SL-1:0] mb;
    assign ea[k] = a_i[k*W+M +: E];
    assign eb[k] = b_i[k*W+M +: E];
    assign sgn1[k] = a_i[k*W+W-1] ^ b_i[k*W+W-1];
    assign is_nan[k] = (ea[k] == EMAX && a_i[k*W +: M] != 0) || (eb[k] == EMAX && b_i[k*W +: M] != 0);
    assign is_inf[k] = ea[k] == EMAX || eb[k] == EMAX;
    assign live1[k] = !is_inf[k] && ea[k] != 0 && eb[k] != 0;
    assign ex1[k*XW +: XW] = XW'(ea[k]) + XW'(eb[k]);
    // the comparison key here, not in segment 2: there it was one LUT6 level too many
    assign key1[k*XW +: XW] = live1[k] ? ex1[k*XW +: XW] : '0;   // a live exponent sum is at least 2
    assign mb = (NP*SL)'({1'b1, b_i[k*W +: M]});
    for (genvar j = 0; j < NP; j++) begin : g_pp
      assign pp1[(k*NP+j)*PW +: PW] = PW'({1'b1, a_i[k*W +: M]}) * PW'(mb[j*SL +: SL]);
    end
  end

  logic nan1, inf1, inf_sign1, zero_sign1;
  always_comb begin // specials, in the order of the C model
    nan1 = 1'b0;
    inf1 = 1'b0;
    inf_sign1 = 1'b0;
    zero_sign1 = 1'b1;
    for (int k = 0; k < N; k++) begin
      zero_sign1 = zero_sign1 & sgn1[k];
      if (is_nan[k] || (is_inf[k] && (ea[k] == 0 || eb[k] == 0 || (inf1 && inf_sign1 != sgn1[k]))))
        nan1 = 1'b1;
      if (is_inf[k]) begin
        inf1 = 1'b1;
        inf_sign1 = sgn1[k];
      end
    end
  end

  localparam int SP = 4;                     // specials: nan, inf, inf_sign, zero_sign
  localparam int B1 = SP + 2 * N + 2 * N * XW + N * NP * PW;
  logic v1;
  logic [B1-1:0] d1;
  f24_pipe #(.W(B1), .STAGES(regs(1))) u_c1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i),
    .data_i({nan1, inf1, inf_sign1, zero_sign1, sgn1, live1, ex1, key1, pp1}), .valid_o(v1), .data_o(d1));

  // ---- segment 2: products, the largest live product exponent
  logic [SP-1:0] sp2;
  logic [N-1:0] sgn2, live2;
  logic [N*XW-1:0] ex2, key2;
  logic [N*NP*PW-1:0] pp2;
  logic [N*PB-1:0] prod2;
  logic [XW-1:0] key [N];
  logic [N-1:0] top;
  logic [XW-1:0] emax2;
  always_comb begin
    {sp2, sgn2, live2, ex2, key2, pp2} = d1;
    for (int k = 0; k < N; k++) begin
      prod2[k*PB +: PB] = '0;
      for (int j = 0; j < NP; j++)
        prod2[k*PB +: PB] = prod2[k*PB +: PB] + (PB'(pp2[(k*NP+j)*PW +: PW]) << (j * SL));
      key[k] = key2[k*XW +: XW];
    end
    // the largest by a comparison matrix, all N (N - 1) comparisons side by side: the keys not
    // below any other are the maximum (ties agree on the value), ORed together; a max tree's
    // log2 N compare-and-select levels in a row are more LUT levels than a segment has
    emax2 = '0;
    for (int k = 0; k < N; k++) begin
      top[k] = 1'b1;
      for (int j = 0; j < N; j++)
        if (j != k && key[j] > key[k]) top[k] = 1'b0;
      emax2 = emax2 | (top[k] ? key[k] : '0);
    end
  end

  localparam int B2 = SP + 2 * N + N * XW + XW + N * PB;
  logic v2;
  logic [B2-1:0] d2;
  f24_pipe #(.W(B2), .STAGES(regs(2))) u_c2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v1),
    .data_i({sp2, sgn2, live2, ex2, emax2, prod2}), .valid_o(v2), .data_o(d2));

  // ---- segment 3: align (right shift of prod << TOP by emax - exponent, sticky): by 64, 32
  logic [SP-1:0] sp3;
  logic [N-1:0] sgn3, live3, st3;
  logic [N*XW-1:0] ex3;
  logic [XW-1:0] emax3;
  logic [N*PB-1:0] prod3;
  logic [N*128-1:0] x3;
  logic [N*5-1:0] dn3;
  logic [XW-1:0] down;
  logic [127:0] x;
  logic st;
  always_comb begin
    {sp3, sgn3, live3, ex3, emax3, prod3} = d2;
    for (int k = 0; k < N; k++) begin
      down = emax3 - ex3[k*XW +: XW];
      x = 128'(prod3[k*PB +: PB]) << TOP;
      st = 1'b0;
      if (down >= 128) begin                     // everything below the window: the sticky bit
        st = x != 0;
        x = '0;
      end else begin
        if (down[6]) begin st = st | (x[63:0] != 0); x = x >> 64; end
        if (down[5]) begin st = st | (x[31:0] != 0); x = x >> 32; end
      end
      x3[k*128 +: 128] = x;
      st3[k] = st;
      dn3[k*5 +: 5] = down[4:0] & {5{down < 128}};
    end
  end

  localparam int B3 = SP + 3 * N + N * 5 + N * 128;
  logic v3;
  logic [B3-1:0] d3;
  f24_pipe #(.W(B3), .STAGES(regs(3))) u_c3 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v2),
    .data_i({sp3, sgn3, live3, st3, dn3, x3}), .valid_o(v3), .data_o(d3));
  // the largest exponent travels beside segments 3 .. 10 to the scale in segment 11
  logic [XW-1:0] emax11;
  /* verilator lint_off PINCONNECTEMPTY */
  f24_pipe #(.W(XW), .STAGES(regs(3) + regs(4) + regs(5) + regs(6) + regs(7) + regs(8) + regs(9) + regs(10))) u_emax (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0), .data_i(emax3), .valid_o(), .data_o(emax11));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- segment 4: by 16, 8, 4
  logic [SP-1:0] sp4;
  logic [N-1:0] sgn4, live4, st4, st4o;
  logic [N*5-1:0] dn4;
  logic [N*2-1:0] dn4o;
  logic [N*128-1:0] x4, x4o;
  logic [127:0] y4;
  logic sty4;
  always_comb begin
    {sp4, sgn4, live4, st4, dn4, x4} = d3;
    for (int k = 0; k < N; k++) begin
      y4 = x4[k*128 +: 128];
      sty4 = st4[k];
      if (dn4[k*5+4]) begin sty4 = sty4 | (y4[15:0] != 0); y4 = y4 >> 16; end
      if (dn4[k*5+3]) begin sty4 = sty4 | (y4[7:0] != 0); y4 = y4 >> 8; end
      if (dn4[k*5+2]) begin sty4 = sty4 | (y4[3:0] != 0); y4 = y4 >> 4; end
      x4o[k*128 +: 128] = y4;
      st4o[k] = sty4;
      dn4o[k*2 +: 2] = dn4[k*5 +: 2];
    end
  end

  localparam int B4 = SP + 3 * N + N * 2 + N * 128;
  logic v4;
  logic [B4-1:0] d4;
  f24_pipe #(.W(B4), .STAGES(regs(4))) u_c4 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v3),
    .data_i({sp4, sgn4, live4, st4o, dn4o, x4o}), .valid_o(v4), .data_o(d4));

  // ---- segment 5: by 2, 1; the sticky bit into bit 0; negative terms inverted (ones' complement,
  // the ones added back with the count of negative terms)
  logic [SP-1:0] sp5;
  logic [N-1:0] sgn5, live5, st5;
  logic [N*2-1:0] dn5;
  logic [N*128-1:0] x5, t5;
  logic [127:0] y5;
  logic sty5;
  logic [CW-1:0] neg5;
  always_comb begin
    {sp5, sgn5, live5, st5, dn5, x5} = d4;
    neg5 = '0;
    for (int k = 0; k < N; k++) begin
      y5 = x5[k*128 +: 128];
      sty5 = st5[k];
      if (dn5[k*2+1]) begin sty5 = sty5 | (y5[1:0] != 0); y5 = y5 >> 2; end
      if (dn5[k*2+0]) begin sty5 = sty5 | y5[0]; y5 = y5 >> 1; end
      y5[0] = y5[0] | sty5;
      t5[k*128 +: 128] = !live5[k] ? '0 : sgn5[k] ? ~y5 : y5;
      neg5 = neg5 + CW'(live5[k] && sgn5[k]);
    end
  end

  localparam int B5 = SP + 1 + CW + N * 128;
  logic v5;
  logic [B5-1:0] d5;
  f24_pipe #(.W(B5), .STAGES(regs(5))) u_c5 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v4),
    .data_i({sp5, live5 != 0, neg5, t5}), .valid_o(v5), .data_o(d5));

  // ---- segments 6, 7: carry-save sum of the terms (3:2 compressors, no carry chain), terms
  // 0 .. H-1 in segment 6, H .. N-1 in segment 7
  localparam int H = N / 2;
  localparam int CS = SP + 1;                // specials and any
  logic [CS-1:0] cs6;
  logic [CW-1:0] neg6;
  logic [N*128-1:0] t6;
  logic [127:0] s6, c6, tmp6;
  always_comb begin
    {cs6, neg6, t6} = d5;
    s6 = 128'(neg6);
    c6 = '0;
    for (int k = 0; k < H; k++) begin
      tmp6 = s6 ^ c6 ^ t6[k*128 +: 128];
      c6 = ((s6 & c6) | (s6 & t6[k*128 +: 128]) | (c6 & t6[k*128 +: 128])) << 1;
      s6 = tmp6;
    end
  end

  localparam int B6 = CS + 256 + (N - H) * 128;
  logic v6;
  logic [B6-1:0] d6;
  f24_pipe #(.W(B6), .STAGES(regs(6))) u_c6 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v5),
    .data_i({cs6, s6, c6, t6[N*128-1:H*128]}), .valid_o(v6), .data_o(d6));

  logic [CS-1:0] cs7;
  logic [(N-H)*128-1:0] t7;
  logic [127:0] s7, c7, tmp7;
  always_comb begin
    {cs7, s7, c7, t7} = d6;
    for (int k = 0; k < N - H; k++) begin
      tmp7 = s7 ^ c7 ^ t7[k*128 +: 128];
      c7 = ((s7 & c7) | (s7 & t7[k*128 +: 128]) | (c7 & t7[k*128 +: 128])) << 1;
      s7 = tmp7;
    end
  end

  localparam int B7 = CS + 256;
  logic v7;
  logic [B7-1:0] d7;
  f24_pipe #(.W(B7), .STAGES(regs(7))) u_c7 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v6),
    .data_i({cs7, s7, c7}), .valid_o(v7), .data_o(d7));

  // ---- segments 8, 9: the sum s + c, low half then high half
  logic [CS-1:0] cs8;
  logic [127:0] s8, c8;
  logic [64:0] lo8;
  always_comb begin
    {cs8, s8, c8} = d7;
    lo8 = {1'b0, s8[63:0]} + {1'b0, c8[63:0]};
  end

  localparam int B8 = CS + 128 + 65;
  logic v8;
  logic [B8-1:0] d8;
  f24_pipe #(.W(B8), .STAGES(regs(8))) u_c8 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v7),
    .data_i({cs8, s8[127:64], c8[127:64], lo8}), .valid_o(v8), .data_o(d8));

  logic [CS-1:0] cs9;
  logic [63:0] sh9, ch9;
  logic [64:0] lo9;
  logic [127:0] acc9;
  always_comb begin
    {cs9, sh9, ch9, lo9} = d8;
    acc9 = {sh9 + ch9 + 64'(lo9[64]), lo9[63:0]};
  end

  localparam int B9 = CS + 128;
  logic v9;
  logic [B9-1:0] d9;
  f24_pipe #(.W(B9), .STAGES(regs(9))) u_c9 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v8),
    .data_i({cs9, acc9}), .valid_o(v9), .data_o(d9));

  // ---- segments 10, 11: sign and magnitude (a negation in two halves), the window's scale
  logic [CS-1:0] cs10;
  logic [127:0] acc10;
  logic sign10;
  logic [64:0] nl10;
  always_comb begin
    {cs10, acc10} = d9;
    sign10 = acc10[127];
    nl10 = {1'b0, acc10[63:0] ^ {64{sign10}}} + 65'(sign10);
  end

  localparam int B10 = CS + 1 + 64 + 65;
  logic v10;
  logic [B10-1:0] d10;
  f24_pipe #(.W(B10), .STAGES(regs(10))) u_c10 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v9),
    .data_i({cs10, sign10, acc10[127:64], nl10}), .valid_o(v10), .data_o(d10));

  logic [CS-1:0] cs11;
  logic sign11;
  logic [63:0] ah11;
  logic [64:0] nl11;
  logic [127:0] mag11;
  logic signed [15:0] scale11;
  always_comb begin
    {cs11, sign11, ah11, nl11} = d10;
    mag11 = {(ah11 ^ {64{sign11}}) + 64'(nl11[64]), nl11[63:0]};
    scale11 = 16'(32'(emax11) - 2 * BIAS - 2 * M - TOP);
  end

  localparam int B11 = CS + 1 + 16 + 128;
  logic v11;
  logic [B11-1:0] d11;
  f24_pipe #(.W(B11), .STAGES(regs(11))) u_c11 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v10),
    .data_i({cs11, sign11, scale11, mag11}), .valid_o(v11), .data_o(d11));

  // ---- segments 12 .. 14: normalize hi (f24_norm128), the rest beside it
  logic [CS-1:0] cs12, cs14;
  logic sign12, sign14, zero14;
  logic signed [15:0] scale12, scale14;
  logic [127:0] mag12, mag14;
  logic [30:0] sig_hi;
  logic signed [E+2:0] exp_hi;
  assign {cs12, sign12, scale12, mag12} = d11;
  f24_norm128 #(.E(E), .R1(regs(12)), .R2(regs(13)), .R3(regs(14))) u_norm_hi (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en_i), .a_i(mag12), .scale_i(scale12), .sig_o(sig_hi), .exp_o(exp_hi));
  logic v14;
  f24_pipe #(.W(CS + 2 + 16 + 128), .STAGES(regs(12) + regs(13) + regs(14))) u_c14 (.clk_i(clk_i),
    .rst_ni(rst_ni), .en_i(en_i), .valid_i(v11), .data_i({cs12, sign12, mag12 == 0, scale12, mag12}),
    .valid_o(v14), .data_o({cs14, sign14, zero14, scale14, mag14}));

  // ---- segment 15: round hi
  logic [W-1:0] hi15;
  f24_round_pack #(.E(E), .M(M)) u_hi (.sign_i(sign14), .exp_i(exp_hi), .sig_i(sig_hi), .res_o(hi15));

  localparam int B15 = CS + 2 + 16 + 128 + W;
  logic v15;
  logic [B15-1:0] d15;
  f24_pipe #(.W(B15), .STAGES(regs(15))) u_c15 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v14),
    .data_i({cs14, sign14, zero14, scale14, mag14, hi15}), .valid_o(v15), .data_o(d15));

  // ---- segments 16, 17: hi's last bit in the window (at), hi's significand shifted there
  logic [CS-1:0] cs16;
  logic sign16, zero16, atneg16, atbig16;
  logic signed [15:0] scale16;
  logic signed [31:0] at16;
  logic [127:0] mag16;
  logic [W-1:0] hi16;
  always_comb begin
    {cs16, sign16, zero16, scale16, mag16, hi16} = d15;
    at16 = 32'(hi16[W-2:M]) - BIAS - M - 32'(scale16);
    atneg16 = at16 < 0;
    atbig16 = at16 >= 128;
  end

  localparam int B16 = CS + 4 + 7 + 128 + W;
  logic v16;
  logic [B16-1:0] d16;
  f24_pipe #(.W(B16), .STAGES(regs(16))) u_c16 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v15),
    .data_i({cs16, sign16, zero16, atneg16, atbig16, at16[6:0], mag16, hi16}), .valid_o(v16), .data_o(d16));

  logic [CS-1:0] cs17;
  logic sign17, zero17, atneg17, atbig17;
  logic [6:0] at17;
  logic [127:0] mag17, sub17;
  logic [W-1:0] hi17;
  always_comb begin
    {cs17, sign17, zero17, atneg17, atbig17, at17, mag17, hi17} = d16;
    sub17 = atneg17 ? mag17 : atbig17 ? '0 : 128'({1'b1, hi17[M-1:0]}) << at17;
  end

  localparam int B17 = CS + 3 + 128 + 128 + W;
  logic v17;
  logic [B17-1:0] d17;
  f24_pipe #(.W(B17), .STAGES(regs(17))) u_c17 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v16),
    .data_i({cs17, sign17, zero17, atneg17, mag17, sub17, hi17}), .valid_o(v17), .data_o(d17));

  // ---- segments 18, 19: the remainder mag - sub in two halves
  logic [CS-1:0] cs18;
  logic sign18, zero18, atneg18;
  logic [127:0] mag18, sub18;
  logic [W-1:0] hi18;
  logic [64:0] rl18;
  always_comb begin
    {cs18, sign18, zero18, atneg18, mag18, sub18, hi18} = d17;
    rl18 = {1'b0, mag18[63:0]} + {1'b0, ~sub18[63:0]} + 65'd1;
  end

  localparam int B18 = CS + 3 + 64 + 64 + 65 + W;
  logic v18;
  logic [B18-1:0] d18;
  f24_pipe #(.W(B18), .STAGES(regs(18))) u_c18 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v17),
    .data_i({cs18, sign18, zero18, atneg18, mag18[127:64], sub18[127:64], rl18, hi18}), .valid_o(v18),
    .data_o(d18));

  logic [CS-1:0] cs19;
  logic sign19, zero19, atneg19, rneg19;
  logic [63:0] mh19, sh19;
  logic [64:0] rl19;
  logic [127:0] rest19;
  logic [W-1:0] hi19;
  always_comb begin
    {cs19, sign19, zero19, atneg19, mh19, sh19, rl19, hi19} = d18;
    rest19 = {mh19 + ~sh19 + 64'(rl19[64]), rl19[63:0]};
    rneg19 = rest19[127];
  end

  localparam int B19 = CS + 4 + 128 + W;
  logic v19;
  logic [B19-1:0] d19;
  f24_pipe #(.W(B19), .STAGES(regs(19))) u_c19 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v18),
    .data_i({cs19, sign19 ^ rneg19, zero19, atneg19, rneg19, rest19, hi19}), .valid_o(v19), .data_o(d19));

  // ---- segments 20, 21: the remainder's magnitude (a negation in two halves)
  logic [CS-1:0] cs20;
  logic lsign20, zero20, atneg20, rneg20;
  logic [127:0] rest20;
  logic [W-1:0] hi20;
  logic [64:0] ml20;
  always_comb begin
    {cs20, lsign20, zero20, atneg20, rneg20, rest20, hi20} = d19;
    ml20 = {1'b0, rest20[63:0] ^ {64{rneg20}}} + 65'(rneg20);
  end

  localparam int B20 = CS + 4 + 64 + 65 + W;
  logic v20;
  logic [B20-1:0] d20;
  f24_pipe #(.W(B20), .STAGES(regs(20))) u_c20 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v19),
    .data_i({cs20, lsign20, zero20, atneg20, rneg20, rest20[127:64], ml20, hi20}), .valid_o(v20), .data_o(d20));

  logic [CS-1:0] cs21;
  logic lsign21, zero21, atneg21, rneg21;
  logic [63:0] rh21;
  logic [64:0] ml21;
  logic [127:0] rmag21;
  logic [W-1:0] hi21;
  always_comb begin
    {cs21, lsign21, zero21, atneg21, rneg21, rh21, ml21, hi21} = d20;
    rmag21 = {(rh21 ^ {64{rneg21}}) + 64'(ml21[64]), ml21[63:0]};
  end

  // the scale travels beside segments 12 .. 20 into the cut after segment 21
  logic signed [15:0] scale_lo;
  /* verilator lint_off PINCONNECTEMPTY */
  f24_pipe #(.W(16), .STAGES(regs(12) + regs(13) + regs(14) + regs(15) + regs(16) + regs(17) + regs(18) + regs(19)
    + regs(20))) u_scale (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0), .data_i(scale12),
    .valid_o(), .data_o(scale_lo));
  /* verilator lint_on PINCONNECTEMPTY */
  localparam int B21 = CS + 3 + 16 + 128 + W;
  logic v21;
  logic [B21-1:0] d21;
  f24_pipe #(.W(B21), .STAGES(regs(21))) u_c21 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v20),
    .data_i({cs21, lsign21, zero21, atneg21, scale_lo, rmag21, hi21}), .valid_o(v21), .data_o(d21));

  // ---- segments 22 .. 24: normalize lo, the rest beside it
  logic [CS-1:0] cs22, cs24;
  logic lsign22, zero22, atneg22, lsign24, zero24, nolo24;
  logic signed [15:0] scale22;
  logic [127:0] rmag22;
  logic [W-1:0] hi22, hi24;
  logic [30:0] sig_lo;
  logic signed [E+2:0] exp_lo;
  assign {cs22, lsign22, zero22, atneg22, scale22, rmag22, hi22} = d21;
  f24_norm128 #(.E(E), .R1(regs(22)), .R2(regs(23)), .R3(regs(24))) u_norm_lo (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en_i), .a_i(rmag22), .scale_i(scale22), .sig_o(sig_lo), .exp_o(exp_lo));
  logic v24;
  f24_pipe #(.W(CS + 3 + W), .STAGES(regs(22) + regs(23) + regs(24))) u_c24 (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en_i), .valid_i(v21), .data_i({cs22, lsign22, zero22, atneg22 || rmag22 == 0, hi22}),
    .valid_o(v24), .data_o({cs24, lsign24, zero24, nolo24, hi24}));

  // ---- segment 25: round lo; specials, then the rounded words
  logic nan, inf, inf_sign, zero_sign, any;
  logic [W-1:0] lo, hi25, lo25;
  assign {nan, inf, inf_sign, zero_sign, any} = cs24;
  f24_round_pack #(.E(E), .M(M)) u_lo (.sign_i(lsign24), .exp_i(exp_lo), .sig_i(sig_lo), .res_o(lo));
  always_comb begin
    if (nan) begin
      hi25 = DEFAULT_NAN;
      lo25 = '0;
    end else if (inf) begin
      hi25 = {inf_sign, EMAX, {M{1'b0}}};
      lo25 = '0;
    end else if (!any) begin
      hi25 = {zero_sign, {(E+M){1'b0}}};
      lo25 = '0;
    end else if (zero24) begin
      hi25 = '0;
      lo25 = '0;
    end else begin
      hi25 = hi24;
      lo25 = (hi24[W-2:M] == 0 || hi24[W-2:M] == EMAX || nolo24) ? '0 : lo;
    end
  end

  f24_pipe #(.W(2 * W), .STAGES(regs(25))) u_c25 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v24),
    .data_i({hi25, lo25}), .valid_o(valid_o), .data_o({hi_o, lo_o}));
endmodule
