// f24_add: pipelined fp24 adder/subtractor, docs/fp24.md semantics bit for bit
// (hls/fp24/f24_add.c). Six combinational segments with STAGES pipeline registers spread evenly
// over the cuts after them (PULP FPnew style; a cut may get 0, 1 or more registers, the last cut
// always gets one, so the output is registered):
//   1 unpack, magnitude compare and swap, exponent gap, specials
//   2 align the smaller significand (31 bits, sticky)
//   3 add or subtract
//   4 normalize, first half (binary-search leading-zero count and shift by 16, 8, 4), cancellation
//   5 normalize, second half (by 2, 1), unrounded exponent
//   6 shared rounder (f24_round_pack), result or special
// Latency STAGES cycles (default 6: one register per segment, >= 60 MHz on iCE40 HX8K at e7m16,
// docs/synth.md), one operation per cycle (II = 1). Resources: one 31-bit comparator, aligner,
// adder/subtractor, leading-zero counter and normalizer, the rounder, about 6 x 80 pipeline FFs.
module f24_add #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int STAGES = 6
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  input  logic         sub_i,
  output logic         valid_o,
  output logic [E+M:0] res_o
);
  localparam int W = 1 + E + M;
  localparam int K = 6;           // segments
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] DEFAULT_NAN = {1'b0, EMAX, 1'b1, {(M-1){1'b0}}};

  // ---- segment 1: swap by magnitude, gap, specials
  logic sa, sb, s_big, s_small, spec1;
  logic [E-1:0] ea, eb, e_big, e_small;
  logic [30:0] siga, sigb, sig_big, sig_small;
  logic [E:0] gap;
  logic [W-1:0] spec_res1;
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
    spec1 = 1'b1;
    if (ea == EMAX || eb == EMAX) begin // specials, in the order of the C model
      if ((ea == EMAX && a_i[M-1:0] != 0) || (eb == EMAX && b_i[M-1:0] != 0) || (ea == eb && sa != sb))
        spec_res1 = DEFAULT_NAN;
      else
        spec_res1 = {ea == EMAX ? sa : sb, EMAX, {M{1'b0}}};
    end else if (ea == 0) begin
      spec_res1 = eb == 0 ? {sa & sb, {(E+M){1'b0}}} : {sb, eb, b_i[M-1:0]};
    end else if (eb == 0) begin
      spec_res1 = {sa, ea, a_i[M-1:0]};
    end else begin
      spec1 = 1'b0;
      spec_res1 = '0;
    end
  end

  localparam int B1 = 1 + W + 2 + E + 31 + 31 + E + 1;
  logic v1;
  logic [B1-1:0] d1;
  f24_pipe #(.W(B1), .STAGES(1 * STAGES / K)) u_c1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i),
    .data_i({spec1, spec_res1, s_big, s_big != s_small, e_big, sig_big, sig_small, gap}), .valid_o(v1), .data_o(d1)
  );

  // ---- segment 2: align with sticky
  logic spec2, s2, sub2;
  logic [W-1:0] spec_res2;
  logic [E-1:0] e2;
  logic [30:0] big2, small2, aligned;
  logic [E:0] gap2;
  always_comb begin
    {spec2, spec_res2, s2, sub2, e2, big2, small2, gap2} = d1;
    if (gap2 >= 31) aligned = 31'(small2 != 0);
    // the sticky mask of the bits shifted out as a shifted mask, not (1 << gap) - 1: a shifter
    // only, without a carry chain after the decoder (3 fewer LUT levels in the segment)
    else aligned = (small2 >> gap2) | 31'((small2 & ~({31{1'b1}} << gap2)) != 0);
  end

  localparam int B2 = 1 + W + 2 + E + 31 + 31;
  logic v2;
  logic [B2-1:0] d2;
  f24_pipe #(.W(B2), .STAGES(2 * STAGES / K - 1 * STAGES / K)) u_c2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v1),
    .data_i({spec2, spec_res2, s2, sub2, e2, big2, aligned}), .valid_o(v2), .data_o(d2)
  );

  // ---- segment 3: add or subtract (the difference is never negative: big >= aligned)
  logic spec3, s3, sub3;
  logic [W-1:0] spec_res3;
  logic [E-1:0] e3;
  logic [30:0] big3, al3, r3;
  always_comb begin
    {spec3, spec_res3, s3, sub3, e3, big3, al3} = d2;
    r3 = sub3 ? big3 - al3 : big3 + al3;
  end

  localparam int B3 = 1 + W + 2 + E + 31;
  logic v3;
  logic [B3-1:0] d3;
  f24_pipe #(.W(B3), .STAGES(3 * STAGES / K - 2 * STAGES / K)) u_c3 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v2),
    .data_i({spec3, spec_res3, s3, sub3, e3, r3}), .valid_o(v3), .data_o(d3)
  );

  // ---- segment 4: normalize, first half: the leading one moves up by 16, 8, 4 where the bits
  // above are zero (a binary-search leading-zero count merged with the shifter); exact
  // cancellation gives +0
  logic spec4, s4, sub4;
  logic [W-1:0] spec_res4;
  logic [E-1:0] e4;
  logic [30:0] r4;
  logic [31:0] x4;
  logic [4:0] n4;
  always_comb begin
    {spec4, spec_res4, s4, sub4, e4, r4} = d3;
    x4 = {r4, 1'b0};
    n4 = '0;
    if (x4[31:16] == 0) begin x4 = x4 << 16; n4[4] = 1'b1; end
    if (x4[31:24] == 0) begin x4 = x4 << 8; n4[3] = 1'b1; end
    if (x4[31:28] == 0) begin x4 = x4 << 4; n4[2] = 1'b1; end
    if (!spec4 && sub4 && r4 == 0) begin      // exact cancellation: +0
      spec4 = 1'b1;
      spec_res4 = '0;
    end
  end

  localparam int B4 = 1 + W + 1 + E + 5 + 32;
  logic v4;
  logic [B4-1:0] d4;
  f24_pipe #(.W(B4), .STAGES(4 * STAGES / K - 3 * STAGES / K)) u_c4 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v3),
    .data_i({spec4, spec_res4, s4, e4, n4, x4}), .valid_o(v4), .data_o(d4)
  );

  // ---- segment 5: normalize, second half (by 2, 1), exponent: e + 1 - leading zeros (a sum's
  // carry has none, so it keeps e + 1; a sum without carry has one)
  logic spec5, s5;
  logic [W-1:0] spec_res5;
  logic [E-1:0] e5;
  logic [4:0] n5;
  logic [31:0] x5;
  logic [30:0] sig5;
  logic signed [E+2:0] exp5;
  always_comb begin
    {spec5, spec_res5, s5, e5, n5, x5} = d4;
    if (x5[31:30] == 0) begin x5 = x5 << 2; n5[1] = 1'b1; end
    if (x5[31] == 0) begin x5 = x5 << 1; n5[0] = 1'b1; end
    sig5 = x5[31:1];
    exp5 = (E+3)'(e5) + 1 - (E+3)'(n5);
  end

  localparam int B5 = 1 + W + 1 + (E + 3) + 31;
  logic v5;
  logic [B5-1:0] d5;
  f24_pipe #(.W(B5), .STAGES(5 * STAGES / K - 4 * STAGES / K)) u_c5 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v4),
    .data_i({spec5, spec_res5, s5, exp5, sig5}), .valid_o(v5), .data_o(d5)
  );

  // ---- segment 6: round, or the special result
  logic spec6, s6;
  logic [W-1:0] spec_res6;
  logic signed [E+2:0] exp6;
  logic [30:0] sig6;
  assign {spec6, spec_res6, s6, exp6, sig6} = d5;
  f24_round_stage #(.E(E), .M(M), .STAGES(STAGES - 5 * STAGES / K)) u_c6 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v5), .spec_i(spec6), .spec_res_i(spec_res6), .sign_i(s6),
    .exp_i(exp6), .sig_i(sig6), .valid_o(valid_o), .res_o(res_o)
  );
endmodule
