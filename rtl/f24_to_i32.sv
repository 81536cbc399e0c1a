// f24_to_i32: pipelined fp24 to 32-bit signed integer conversion, rounding toward zero,
// docs/fp24.md bit for bit (hls/fp24/f24_to_i32.c): the RGS's colour quantizer to Q12 and the
// texel coordinates of its texture filter (Sec. 4, shading; hls/units/rgs.c). Saturates to
// INT32_MIN / INT32_MAX from 2^31 on (+-Inf too, as the C model's exponent test covers Inf for
// E >= 6); NaN, zeros, subnormal encodings and |a| < 1 give 0.
// Two combinational segments with STAGES pipeline registers spread evenly over the cuts after them
// (PULP FPnew style; the last cut always gets one, so the output is registered):
//   1 unbiased exponent, zero/saturation decisions, a 31-bit right shifter of the significand
//     (leading one at bit 30) by 30 - exponent: the truncated magnitude
//   2 negation for a negative operand, saturation or zero select
// Latency STAGES cycles (default 2, >= 60 MHz on iCE40 HX8K at e7m16, docs/synth.md), II = 1.
// Resources: one 31-bit 5-level right shifter, one 32-bit negator, a 32-bit mux, about
// STAGES x 34 pipeline FFs.
module f24_to_i32 #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int STAGES = 2
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  output logic         valid_o,
  output logic [31:0]  res_o
);
  localparam int W = 1 + E + M;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam int K = 2;              // segments
  localparam logic [E-1:0] EMAX = '1;

  // ---- segment 1: exponent, decisions, shifter
  logic sign1, zero1, sat1;
  logic [E-1:0] ea;
  logic signed [E+2:0] e;            // value = 1.f x 2^e
  logic [4:0] shift;
  logic [30:0] mag1;
  always_comb begin
    sign1 = a_i[W-1];
    ea = a_i[W-2:M];
    e = (E+3)'(ea) - (E+3)'(BIAS);
    zero1 = (ea == EMAX && a_i[M-1:0] != 0) || ea == 0 || e < 0;   // NaN, zero, |a| < 1
    sat1 = !zero1 && e >= 31;
    shift = 5'd30 - e[4:0];                                        // used for 0 <= e <= 30 only
    mag1 = {1'b1, a_i[M-1:0], (30 - M)'(0)} >> shift;
  end

  logic v1;
  logic [33:0] d1;
  f24_pipe #(.W(34), .STAGES(1 * STAGES / K)) u_c1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i),
    .data_i({sign1, zero1, sat1, mag1}), .valid_o(v1), .data_o(d1)
  );

  // ---- segment 2: sign, saturation
  logic sign, zero, sat;
  logic [30:0] mag;
  logic [31:0] res;
  always_comb begin
    {sign, zero, sat, mag} = d1;
    if (zero)
      res = '0;
    else if (sat)
      res = sign ? 32'h8000_0000 : 32'h7FFF_FFFF;
    else
      res = sign ? -{1'b0, mag} : {1'b0, mag};
  end
  f24_pipe #(.W(32), .STAGES(STAGES - (K - 1) * STAGES / K)) u_c2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v1), .data_i(res), .valid_o(valid_o), .data_o(res_o)
  );
endmodule
