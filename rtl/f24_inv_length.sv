// f24_inv_length: the length of an fp24 3-vector and its reciprocal in the C's operations,
// |v| = sqrt(v . v) and 1 / |v| (hls/units/rgs_geom.c `rgs_length3` and the shading's
// f24_div(F24_ONE, rgs_length3(v)); shade_rec.c's 1 / sqrt(len2)), for the RGS's normalizations
// (paper section 3: the unit ray direction and the unit shading normal of a hit, the decoded
// vertex normals): an `f24_dot3`, an `f24_sqrt` and an `f24_div` of the constant 1 in a chain.
// Latency: len_o after LEN_LATENCY = MUL + 2 ADD + SQRT (default 25) cycles, inv_o and valid_o
// after LATENCY = LEN_LATENCY + DIV (default 36); one vector per cycle (II = 1); clock enable en_i
// from the unit. Resources: 3 multipliers, 2 adders, 1 square root, 1 divider.
module f24_inv_length #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int SQRT_STAGES = 9,
  parameter int DIV_STAGES = 11
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 en_i,
  input  logic                 valid_i,
  input  logic [3*(E+M+1)-1:0] v_i,    // x, y, z from the low word up
  output logic                 valid_o,
  output logic [E+M:0]         len_o,  // |v|, DIV_STAGES cycles before inv_o
  output logic [E+M:0]         inv_o   // 1 / |v|
);
  localparam int W = 1 + E + M;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [W-1:0] ONE = {1'b0, E'(BIAS), {M{1'b0}}};
  logic [W-1:0] len2;
  logic v_len2, v_len;
  f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_len2 (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en_i), .valid_i(valid_i), .a_i(v_i), .b_i(v_i), .valid_o(v_len2), .res_o(len2));
  f24_sqrt #(.E(E), .M(M), .STAGES(SQRT_STAGES)) u_len (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v_len2),
    .a_i(len2), .valid_o(v_len), .res_o(len_o));
  f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_inv (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v_len),
    .a_i(ONE), .b_i(len_o), .valid_o(valid_o), .res_o(inv_o));
endmodule
