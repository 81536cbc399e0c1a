// f24_from_i32: pipelined int32-to-fp24 converter scaled by a power of two, round(a * 2^SCALE)
// (docs/fp24.md; hls/fp24/f24_from_i32.c for SCALE = 0). The scale is an exponent offset applied
// before the shared rounder, so a caller that multiplies the converted integer by 2^SCALE (an
// exact product while the result stays normal) gets the same bits from one converter: the RGS's
// pixel centre f24_mul(f24_from_i32(2x + 1), 1/2) is SCALE = -1 (rgs_raygen). Three combinational
// segments with STAGES pipeline registers spread evenly over the cuts after them (PULP FPnew style,
// as the operators; the last cut always gets one, so the output is registered):
//   1 magnitude, leading-zero count (6 LUT6 levels, synth_xilinx)
//   2 normalizing shift (leading one to bit 30; 5)
//   3 f24_round_pack (ties to even; a zero input gives +0; 5)
// (Until 2026-11-29 two segments, the shift in the first: 8 levels, so every caller that computed
// a_i in the cycle before had more than 8 between registers; STAGES 2 then.)
// Latency STAGES cycles (default 3), II = 1. Resources: a 32-bit negator, a 32-bit leading-zero
// counter and barrel shifter, the shared rounder; Yosys 0.23 at e7m16 (`python3 scripts/synth.py
// --levels f24_from_i32`): synth_xilinx 274 LUT6, 120 FFs (two segments at STAGES 2: 310, 69;
// synth_ice40 then 380 LUT4, 66 FFs, not remeasured).
module f24_from_i32 #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int SCALE = 0,
  parameter int STAGES = 3
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [31:0]  a_i,      // two's complement
  output logic         valid_o,
  output logic [E+M:0] res_o
);
  localparam int K = 3;          // segments
  localparam int BIAS = (1 << (E - 1)) - 1;

  // ---- segment 1: magnitude, leading zeros
  logic sign1, zero1;
  logic [31:0] mag;
  logic [5:0] lz;
  logic signed [E+2:0] exp1;
  always_comb begin
    sign1 = a_i[31];
    mag = sign1 ? 32'd0 - a_i : a_i;
    zero1 = a_i == 0;
    lz = 6'd32;
    for (int b = 0; b < 32; b++)
      if (mag[b]) lz = 6'(31 - b);
    exp1 = (E+3)'(31 + BIAS + SCALE) - (E+3)'(lz);
  end

  localparam int B1 = 2 + (E + 3) + 32 + 6;
  logic v1;
  logic [B1-1:0] d1;
  f24_pipe #(.W(B1), .STAGES(1 * STAGES / K)) u_c1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i),
    .data_i({sign1, zero1, exp1, mag, lz}), .valid_o(v1), .data_o(d1)
  );

  // ---- segment 2: normalization
  logic sign2a, zero2a;
  logic signed [E+2:0] exp2a;
  logic [31:0] mag2;
  logic [5:0] lz2;
  logic [30:0] sig1;
  assign {sign2a, zero2a, exp2a, mag2, lz2} = d1;
  assign sig1 = 31'((mag2 << lz2) >> 1);  // the lost bit is 0: |a| <= 2^31 (the C's jam never sets a bit)

  localparam int B2 = 2 + (E + 3) + 31;
  logic v2;
  logic [B2-1:0] d2;
  f24_pipe #(.W(B2), .STAGES(2 * STAGES / K - 1 * STAGES / K)) u_c2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v1),
    .data_i({sign2a, zero2a, exp2a, sig1}), .valid_o(v2), .data_o(d2)
  );

  // ---- segment 3: round and pack
  logic sign2, zero2;
  logic signed [E+2:0] exp2;
  logic [30:0] sig2;
  logic [E+M:0] rounded, res2;
  assign {sign2, zero2, exp2, sig2} = d2;
  f24_round_pack #(.E(E), .M(M)) u_round (.sign_i(sign2), .exp_i(exp2), .sig_i(sig2), .res_o(rounded));
  assign res2 = zero2 ? '0 : rounded;

  f24_pipe #(.W(E + M + 1), .STAGES(STAGES - 2 * STAGES / K)) u_c3 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v2), .data_i(res2), .valid_o(valid_o), .data_o(res_o)
  );
endmodule
