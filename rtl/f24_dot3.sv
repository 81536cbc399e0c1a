// f24_dot3: the dot product of two fp24 3-vectors in the C's order ((a.x b.x + a.y b.y) + a.z b.z),
// rounded after every operation (hls/units/rgs_geom.c `rgs_dot3`; a row of the transformation
// unit without its translation, hls/units/xform_unit.c `row_of`), for the RGS's shading (paper
// section 3: lengths, cosines, the rows of the instance's transposed matrix and of T_R).
// 3 `f24_mul` side by side, 2 `f24_add` in a chain; a.z b.z waits one adder in an `f24_pipe`.
// Latency LATENCY = MUL_STAGES + 2 ADD_STAGES (default 4 + 12 = 16) cycles, one dot product per
// cycle (II = 1); clock enable en_i from the unit. Resources: 3 multipliers, 2 adders, W x ADD_STAGES
// delay flip-flops.
module f24_dot3 #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 en_i,
  input  logic                 valid_i,
  input  logic [3*(E+M+1)-1:0] a_i,    // x, y, z from the low word up
  input  logic [3*(E+M+1)-1:0] b_i,
  output logic                 valid_o,
  output logic [E+M:0]         res_o
);
  localparam int W = 1 + E + M;
  logic [W-1:0] p [3];
  logic [W-1:0] pz_q, pxy;
  logic v_p, v_xy;
  /* verilator lint_off PINCONNECTEMPTY */
  for (genvar k = 0; k < 3; k++) begin : g_mul
    if (k == 0) begin : g_v
      f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_m (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i),
        .a_i(a_i[k*W +: W]), .b_i(b_i[k*W +: W]), .valid_o(v_p), .res_o(p[k]));
    end else begin : g_nv
      f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_m (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
        .a_i(a_i[k*W +: W]), .b_i(b_i[k*W +: W]), .valid_o(), .res_o(p[k]));
    end
  end
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_xy (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v_p),
    .a_i(p[0]), .b_i(p[1]), .sub_i(1'b0), .valid_o(v_xy), .res_o(pxy));
  f24_pipe #(.W(W), .STAGES(ADD_STAGES)) u_d_z (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .data_i(p[2]), .valid_o(), .data_o(pz_q));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_xyz (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v_xy),
    .a_i(pxy), .b_i(pz_q), .sub_i(1'b0), .valid_o(valid_o), .res_o(res_o));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
