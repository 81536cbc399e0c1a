// f24_mul: pipelined fp24 multiplier, docs/fp24.md semantics bit for bit (hls/fp24/f24_mul.c).
// Four combinational segments with STAGES pipeline registers spread evenly over the cuts after
// them (PULP FPnew style; the last cut always gets one, so the output is registered):
//   1 partial products: (M+1) x PP_BITS-bit slices of the significand product, exponent sum, specials
//   2 sum of the partial products
//   3 one-bit normalize with sticky, exponent carry
//   4 shared rounder (f24_round_pack), result or special
// Latency STAGES cycles (default 4, >= 60 MHz on iCE40 HX8K at e7m16, docs/synth.md), one
// operation per cycle (II = 1). Resources: one (M+1) x (M+1) multiplier as ceil((M+1)/PP_BITS)
// slices (one DSP48E1 each on Xilinx: PP_BITS = M + 1 for one), an exponent adder, the rounder,
// about 4 x 60 pipeline FFs.
module f24_mul #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int STAGES = 4,
  parameter int PP_BITS = 6  // bits of b per partial product; M + 1: one product (one DSP48E1 on Xilinx)
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  output logic         valid_o,
  output logic [E+M:0] res_o
);
  localparam int W = 1 + E + M;
  localparam int K = 4;                      // segments
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam int SL = PP_BITS;               // bits of b per partial product
  localparam int NP = (M + 1 + SL - 1) / SL; // partial products
  localparam int PW = M + 1 + SL;            // bits of one partial product
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] DEFAULT_NAN = {1'b0, EMAX, 1'b1, {(M-1){1'b0}}};

  // ---- segment 1: partial products, exponent, specials
  logic sign, a_nan, b_nan, spec1;
  logic [E-1:0] ea, eb;
  logic [M:0] ma;
  logic [NP*SL-1:0] mb;
  logic [NP*PW-1:0] pp;
  logic signed [E+2:0] exp1;
  logic [W-1:0] spec_res1;
  always_comb begin
    sign = a_i[W-1] ^ b_i[W-1];
    ea = a_i[W-2:M];
    eb = b_i[W-2:M];
    a_nan = ea == EMAX && a_i[M-1:0] != 0;
    b_nan = eb == EMAX && b_i[M-1:0] != 0;
    ma = {1'b1, a_i[M-1:0]};
    mb = (NP*SL)'({1'b1, b_i[M-1:0]});
    for (int k = 0; k < NP; k++) pp[k*PW +: PW] = PW'(ma) * PW'(mb[k*SL +: SL]);
    exp1 = (E+3)'(ea) + (E+3)'(eb) - (E+3)'(BIAS);
    spec1 = 1'b1;
    if (a_nan || b_nan)
      spec_res1 = DEFAULT_NAN;
    else if (ea == EMAX || eb == EMAX)
      spec_res1 = (ea == 0 || eb == 0) ? DEFAULT_NAN : {sign, EMAX, {M{1'b0}}};
    else if (ea == 0 || eb == 0)
      spec_res1 = {sign, {(E+M){1'b0}}};
    else begin
      spec1 = 1'b0;
      spec_res1 = '0;
    end
  end

  localparam int B1 = 1 + W + 1 + (E + 3) + NP * PW;
  logic v1;
  logic [B1-1:0] d1;
  f24_pipe #(.W(B1), .STAGES(1 * STAGES / K)) u_c1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i),
    .data_i({spec1, spec_res1, sign, exp1, pp}), .valid_o(v1), .data_o(d1)
  );

  // ---- segment 2: sum of the partial products, in [2^2M, 2^(2M+2))
  logic spec2, s2;
  logic [W-1:0] spec_res2;
  logic signed [E+2:0] exp2;
  logic [NP*PW-1:0] pp2;
  logic [2*M+1:0] prod;
  always_comb begin
    {spec2, spec_res2, s2, exp2, pp2} = d1;
    prod = '0;
    for (int k = 0; k < NP; k++) prod = prod + ((2*M+2)'(pp2[k*PW +: PW]) << (k * SL));
  end

  localparam int B2 = 1 + W + 1 + (E + 3) + 2 * M + 2;
  logic v2;
  logic [B2-1:0] d2;
  f24_pipe #(.W(B2), .STAGES(2 * STAGES / K - 1 * STAGES / K)) u_c2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v1),
    .data_i({spec2, spec_res2, s2, exp2, prod}), .valid_o(v2), .data_o(d2)
  );

  // ---- segment 3: the leading one to bit 30, everything below ORed into bit 0
  logic spec3, s3, carry;
  logic [W-1:0] spec_res3;
  logic signed [E+2:0] exp3, exp3n;
  logic [2*M+1:0] prod3;
  logic [63:0] wide;
  logic [5:0] lead;
  logic [30:0] sig;
  always_comb begin
    {spec3, spec_res3, s3, exp3, prod3} = d2;
    carry = prod3[2*M+1];
    lead = 6'(2 * M) + 6'(carry);                      // position of the leading one
    wide = 64'(prod3);
    if (lead >= 30)
      sig = 31'((wide >> (lead - 30)) | 64'((wide & ~({64{1'b1}} << (lead - 30))) != 0));
    else
      sig = 31'(wide << (30 - lead));
    exp3n = exp3 + (E+3)'(carry);
  end

  localparam int B3 = 1 + W + 1 + (E + 3) + 31;
  logic v3;
  logic [B3-1:0] d3;
  f24_pipe #(.W(B3), .STAGES(3 * STAGES / K - 2 * STAGES / K)) u_c3 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v2),
    .data_i({spec3, spec_res3, s3, exp3n, sig}), .valid_o(v3), .data_o(d3)
  );

  // ---- segment 4: round, or the special result
  logic spec4, s4;
  logic [W-1:0] spec_res4;
  logic signed [E+2:0] exp4;
  logic [30:0] sig4;
  assign {spec4, spec_res4, s4, exp4, sig4} = d3;
  f24_round_stage #(.E(E), .M(M), .STAGES(STAGES - 3 * STAGES / K)) u_c4 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v3), .spec_i(spec4), .spec_res_i(spec_res4), .sign_i(s4),
    .exp_i(exp4), .sig_i(sig4), .valid_o(valid_o), .res_o(res_o)
  );
endmodule
