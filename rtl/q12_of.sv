// q12_of: fp24 to the RGS's Q12 colour fixed point (4096 = 1.0; docs/shading.md, "Integer colour
// arithmetic"; hls/units/rgs_geom.c `rgs_q_of`): to_i32(x 4096 + 1/2) clamped to 0 .. 65535, bit for bit
// as the C, on its operators: `f24_mul` by the constant 4096, `f24_add` of 1/2, `f24_to_i32`
// (toward zero, saturating), then the clamp (negative to 0, above 65535 to 65535). Used for the
// cosines, spot factors, light colours and material factors of shading (paper section 3).
// Latency LATENCY = MUL_STAGES + ADD_STAGES + TOI_STAGES (default 12) cycles, one value per cycle
// (II = 1); clock enable en_i from the unit. Resources: 1 multiplier, 1 adder, 1 fp24-to-int
// converter, a 32-bit clamp.
module q12_of #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int TOI_STAGES = 2
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] x_i,
  output logic         valid_o,
  output logic [15:0]  q_o
);
  localparam int W = 1 + E + M;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [W-1:0] C4096 = {1'b0, E'(BIAS + 12), {M{1'b0}}};
  localparam logic [W-1:0] HALF = {1'b0, E'(BIAS - 1), {M{1'b0}}};
  logic [W-1:0] scaled, rounded;
  logic [31:0] i;
  logic v_s, v_r;
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_scale (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i),
    .a_i(x_i), .b_i(C4096), .valid_o(v_s), .res_o(scaled));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_half (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v_s),
    .a_i(scaled), .b_i(HALF), .sub_i(1'b0), .valid_o(v_r), .res_o(rounded));
  f24_to_i32 #(.E(E), .M(M), .STAGES(TOI_STAGES)) u_int (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v_r),
    .a_i(rounded), .valid_o(valid_o), .res_o(i));
  assign q_o = i[31] ? 16'd0 : i > 32'd65535 ? 16'hFFFF : i[15:0];
endmodule
