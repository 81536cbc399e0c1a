// xform_unit: the transformation unit (paper sections 2.1-2.2, 3; hls/units/xform_unit.c).
// One affine step per cycle: r = M v (+ t when point_i), each row ((m0*x + m1*y) + m2*z) + t,
// the translation through a mux (not an add of zero) so a -0 sum keeps its sign.
// Datapath: 9 multipliers, 9 adders (Table 2: 9 add, 9 mul). Latency LATENCY cycles
// (default: multiplier 3 + three adders 3 = 12), one step per cycle (II = 1).
// Handshake: valid/ready; the pipeline advances when the output is free or taken.
module xform_unit #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int LATENCY = 12
) (
  input  logic               clk_i,
  input  logic               rst_ni,
  input  logic               valid_i,
  output logic               ready_o,
  input  logic [12*(E+M+1)-1:0] m_i,   // rows m0 m1 m2 t, row 0 in the low words
  input  logic [3*(E+M+1)-1:0]  v_i,   // x, y, z from the low word up
  input  logic               point_i,  // 1: add the translation (origin), 0: direction
  output logic               valid_o,
  input  logic               ready_i,
  output logic [3*(E+M+1)-1:0]  r_o
);
  localparam int W = 1 + E + M;
  logic [3*W-1:0] r;

  for (genvar row = 0; row < 3; row++) begin : g_row
    logic [W-1:0] p0, p1, p2, s01, s012, st;
    f24_mul_core #(.E(E), .M(M)) u_m0 (.a_i(m_i[(4*row+0)*W +: W]), .b_i(v_i[0*W +: W]), .res_o(p0));
    f24_mul_core #(.E(E), .M(M)) u_m1 (.a_i(m_i[(4*row+1)*W +: W]), .b_i(v_i[1*W +: W]), .res_o(p1));
    f24_mul_core #(.E(E), .M(M)) u_m2 (.a_i(m_i[(4*row+2)*W +: W]), .b_i(v_i[2*W +: W]), .res_o(p2));
    f24_add_core #(.E(E), .M(M)) u_a0 (.a_i(p0), .b_i(p1), .sub_i(1'b0), .res_o(s01));
    f24_add_core #(.E(E), .M(M)) u_a1 (.a_i(s01), .b_i(p2), .sub_i(1'b0), .res_o(s012));
    f24_add_core #(.E(E), .M(M)) u_a2 (.a_i(s012), .b_i(m_i[(4*row+3)*W +: W]), .sub_i(1'b0), .res_o(st));
    assign r[row*W +: W] = point_i ? st : s012;
  end

  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;
  f24_pipe #(.W(3 * W), .STAGES(LATENCY)) u_pipe (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i), .data_i(r), .valid_o(valid_o), .data_o(r_o)
  );
endmodule
