// xform_unit: the transformation unit (paper sections 2.1-2.2, 3; hls/units/xform_unit.c).
// One affine step per cycle: r = M v (+ t when point_i), each row ((m0*x + m1*y) + m2*z) + t,
// the translation through a mux (not an add of zero) so a -0 sum keeps its sign.
// Datapath: 9 pipelined multipliers, 9 pipelined adders (Table 2: 9 add, 9 mul); the operands
// that join later (m2*z, t, point_i, the sum without t) wait in f24_pipe delay lines.
// Latency LATENCY = MUL_STAGES + 3 ADD_STAGES (default 4 + 3 x 6 = 22) cycles, one step per
// cycle (II = 1); the clock is that of the operators (docs/synth.md).
// Handshake: valid/ready; the pipeline advances when the output is free or taken.
module xform_unit #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int ADD_STAGES = 6,
  parameter int MUL_STAGES = 4
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
  localparam int LATENCY = MUL_STAGES + 3 * ADD_STAGES;
  logic en, point_q;
  assign en = ready_i || !valid_o;
  assign ready_o = en;

  /* verilator lint_off PINCONNECTEMPTY */
  for (genvar row = 0; row < 3; row++) begin : g_row
    logic [W-1:0] p0, p1, p2, p2_q, s01, s012, s012_q, t_q, st;
    f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_m0 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
      .a_i(m_i[(4*row+0)*W +: W]), .b_i(v_i[0*W +: W]), .valid_o(), .res_o(p0));
    f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_m1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
      .a_i(m_i[(4*row+1)*W +: W]), .b_i(v_i[1*W +: W]), .valid_o(), .res_o(p1));
    f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_m2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
      .a_i(m_i[(4*row+2)*W +: W]), .b_i(v_i[2*W +: W]), .valid_o(), .res_o(p2));
    f24_pipe #(.W(W), .STAGES(ADD_STAGES)) u_d_p2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .data_i(p2), .valid_o(), .data_o(p2_q));
    f24_pipe #(.W(W), .STAGES(MUL_STAGES + 2 * ADD_STAGES)) u_d_t (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i(m_i[(4*row+3)*W +: W]), .valid_o(), .data_o(t_q));
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_a0 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .a_i(p0), .b_i(p1), .sub_i(1'b0), .valid_o(), .res_o(s01));
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_a1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .a_i(s01), .b_i(p2_q), .sub_i(1'b0), .valid_o(), .res_o(s012));
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_a2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .a_i(s012), .b_i(t_q), .sub_i(1'b0), .valid_o(), .res_o(st));
    f24_pipe #(.W(W), .STAGES(ADD_STAGES)) u_d_s (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .data_i(s012), .valid_o(), .data_o(s012_q));
    assign r_o[row*W +: W] = point_q ? st : s012_q;
  end

  // valid and point_i beside the datapath
  f24_pipe #(.W(1), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
    .data_i(point_i), .valid_o(valid_o), .data_o(point_q));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
