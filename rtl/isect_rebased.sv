// isect_rebased: the triangle test of one ray as one pipelined unit (paper section 2.1, Figure 2
// path e: the transformation into unit-triangle space and the intersection unit; the paper's
// intersection unit is one pipeline the rays stream through): isect_unit_rebased
// (hls/units/isect_unit.c) on a ray whose origin the rebase unit moved to the double word
// p = p_hi + p_lo at distance te, bit for bit, followed by the closest hit's distance t0 + t
// (trace.c's op_tri_isect: best_t of a ray that hits). Per ray:
//   l = p_lo - C_lo, h = p_hi - C_hi (offset_from_vertex; C = the triangle's vertex, C_hi the
//   translation column of its matrix M^-1, C_lo its low part), then c = h + l;
//   O'z = n.p_hi + n.(-C_hi) + n.l in one exact sum of 9 products (plane_distance, n = row 2 of
//   M^-1), from l on;
//   O'x, O'y = rows 0 and 1 of M^-1 times c (origin_from), D' = M^-1 d (xform_vector);
//   isect_unit on (O', D', te, tmin, tmax, the shared-edge flags): hit, t, u, v, D'z;
//   t0 + t (the ray's distance to the object's rebased origin plus the hit's).
// Each step is the operator sequence the thread used to issue as separate batches on the core's
// shared adders, xform_unit, exact sum and isect_unit (the same operators in the same order, so
// the same bits); here the independent ones run side by side: the direction's transformation
// beside the offsets, the exact sum beside c and its transformation.
// Latency LATENCY = T + IS + ADD with T = max(2 ADD + XF, ADD + SUM) (XF = MUL + 3 ADD, IS =
// DIV + MUL + 2 ADD + CMP): at the default depths max(12 + 22, 6 + 25) + 29 + 6 = 69 cycles,
// one ray per cycle (II = 1), where the batches took 6 + 6 + 22 + 25 + 29 + 6 = 94 cycles of
// latency and 8 issue slots per ray.
// Resources: 10 adders (6 for l and h, 3 for c, 1 for t0 + t), two xform_units (the origin's
// third row is unused: synthesis drops it), an f24_sum_exact of 9 terms, an isect_unit, and
// delay lines for the operands that join later (the matrix 2 ADD, the rays' distances T).
// synth_xilinx at e7m16 (scripts/synth.py's flow, xilinx('isect_rebased', 7, 16), 2026-11-25):
// 24859 LUT6, 1487 SRL, 16978 flip-flops, 78 DSP48E1, 1511 CARRY4; 9 LUT6 levels (10 before its
// f24_sum_exact of 9 terms found the largest product exponent by a comparison matrix instead of
// a max tree of 4 compare-and-select levels in one segment: the sum alone 10 -> 7 levels, 10378
// LUT6, 27 DSP48E1). What it replaces in trace_core (xform_unit, isect_unit, the 9-term sum, one
// of 3 adders) was 22151 LUT6 and 60 DSP48E1 with the 3 adders; the core now has it and 2
// adders: 25537 and 78 (before the comparison matrix).
// Handshake: valid_i in, valid_o LATENCY cycles later; no back pressure (trace_core takes every
// result, as from its other per-ray units).
module isect_rebased #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int EDGE_EPS = 0,
  parameter int SHARED_EPS = M,
  parameter int ADD_STAGES = 6,
  parameter int MUL_STAGES = 4,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2,
  parameter int SUM_STAGES = 25,
  localparam int XF_LATENCY = MUL_STAGES + 3 * ADD_STAGES,
  localparam int IS_LATENCY = DIV_STAGES + MUL_STAGES + 2 * ADD_STAGES + CMP_STAGES,
  // where the origin's rows (2 ADD + XF) and its plane distance (ADD + SUM) meet
  localparam int T_JOIN = 2 * ADD_STAGES + XF_LATENCY > ADD_STAGES + SUM_STAGES ?
                          2 * ADD_STAGES + XF_LATENCY : ADD_STAGES + SUM_STAGES,
  localparam int LATENCY = T_JOIN + IS_LATENCY + ADD_STAGES
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  valid_i,
  input  logic [12*(E+M+1)-1:0] m_i,      // M^-1, rows m0 m1 m2 C_hi (row 0 in the low words)
  input  logic [3*(E+M+1)-1:0]  c_lo_i,   // the vertex's low part
  input  logic [2:0]            shared_i, // the triangle's shared-edge flags (isect_unit)
  input  logic [3*(E+M+1)-1:0]  p_hi_i,   // the rebased origin, a double word
  input  logic [3*(E+M+1)-1:0]  p_lo_i,
  input  logic [3*(E+M+1)-1:0]  d_i,      // the direction (object space)
  input  logic [E+M:0]          te_i,     // the origin's distance from the object's (rebase_leaf)
  input  logic [E+M:0]          tmin_i,
  input  logic [E+M:0]          tmax_i,
  input  logic [E+M:0]          t0_i,     // the object's origin's distance from the world ray's
  output logic                  valid_o,
  output logic                  hit_o,
  output logic [E+M:0]          t_o,      // from the rebased origin
  output logic [E+M:0]          u_o,
  output logic [E+M:0]          v_o,
  output logic [E+M:0]          cos_o,
  output logic [E+M:0]          t_world_o // t0 + t
);
  localparam int W = 1 + E + M;
  localparam logic [W-1:0] SIGN = {1'b1, {(W-1){1'b0}}};
  logic [3*W-1:0] c_hi, neg_c_hi, l, h, c, dd, p_hi_q, d_q;
  logic [12*W-1:0] m_q1, m_q2;
  logic [W-1:0] oz, oz_q, te_q, tmin_q, tmax_q, t0_q, is_t, is_u, is_v, is_cos;
  logic [2*W-1:0] oxy_q;
  logic [3*W-1:0] dd_q;
  logic [2:0] shared_q;
  logic is_hit;
  always_comb
    for (int j = 0; j < 3; j++) begin
      c_hi[j*W +: W] = m_i[(4*j+3)*W +: W];
      neg_c_hi[j*W +: W] = m_q1[(4*j+3)*W +: W] ^ SIGN;
    end

  /* verilator lint_off PINCONNECTEMPTY */
  // l = p_lo - C_lo, h = p_hi - C_hi (ADD), with the matrix, p_hi and d waiting beside them
  for (genvar j = 0; j < 3; j++) begin : g_ofs
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_l (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
      .a_i(p_lo_i[j*W +: W]), .b_i(c_lo_i[j*W +: W]), .sub_i(1'b1), .valid_o(), .res_o(l[j*W +: W]));
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_h (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
      .a_i(p_hi_i[j*W +: W]), .b_i(c_hi[j*W +: W]), .sub_i(1'b1), .valid_o(), .res_o(h[j*W +: W]));
    // c = h + l (2 ADD)
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_c (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
      .a_i(h[j*W +: W]), .b_i(l[j*W +: W]), .sub_i(1'b0), .valid_o(), .res_o(c[j*W +: W]));
  end
  f24_pipe #(.W(12 * W + 6 * W), .STAGES(ADD_STAGES)) u_d_m1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(1'b0), .data_i({m_i, p_hi_i, d_i}), .valid_o(), .data_o({m_q1, p_hi_q, d_q}));

  // O'z = n.p_hi + n.(-C_hi) + n.l, from ADD to ADD + SUM
  f24_sum_exact #(.E(E), .M(M), .N(9), .STAGES(SUM_STAGES)) u_oz (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(1'b0), .a_i({3{m_q1[8*W +: 3*W]}}), .b_i({l, neg_c_hi, p_hi_q}), .valid_o(), .hi_o(oz), .lo_o());

  // the matrix and d for the two transformations, which start with c at 2 ADD
  logic [3*W-1:0] d_q2;
  f24_pipe #(.W(12 * W + 3 * W), .STAGES(ADD_STAGES)) u_d_m2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(1'b0), .data_i({m_q1, d_q}), .valid_o(), .data_o({m_q2, d_q2}));
  xform_unit #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .MUL_STAGES(MUL_STAGES)) u_xf_d (.clk_i(clk_i),
    .rst_ni(rst_ni), .valid_i(1'b0), .ready_o(), .m_i(m_q2), .v_i(d_q2), .point_i(1'b0), .valid_o(), .ready_i(1'b1),
    .r_o(dd));
  /* verilator lint_off UNUSEDSIGNAL */
  logic [3*W-1:0] oxy3;  // row 2 unused: O'z is the exact sum's
  xform_unit #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .MUL_STAGES(MUL_STAGES)) u_xf_o (.clk_i(clk_i),
    .rst_ni(rst_ni), .valid_i(1'b0), .ready_o(), .m_i(m_q2), .v_i(c), .point_i(1'b0), .valid_o(), .ready_i(1'b1),
    .r_o(oxy3));
  /* verilator lint_on UNUSEDSIGNAL */

  // the join at T_JOIN: the later of the two paths waits no cycle, the other the difference
  f24_pipe #(.W(W), .STAGES(T_JOIN - ADD_STAGES - SUM_STAGES)) u_d_oz (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(1'b1), .valid_i(1'b0), .data_i(oz), .valid_o(), .data_o(oz_q));
  f24_pipe #(.W(5 * W), .STAGES(T_JOIN - 2 * ADD_STAGES - XF_LATENCY)) u_d_xf (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(1'b1), .valid_i(1'b0), .data_i({oxy3[0 +: 2*W], dd}), .valid_o(), .data_o({oxy_q, dd_q}));
  f24_pipe #(.W(3 * W + 3), .STAGES(T_JOIN)) u_d_ray (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
    .data_i({te_i, tmin_i, tmax_i, shared_i}), .valid_o(), .data_o({te_q, tmin_q, tmax_q, shared_q}));

  isect_unit #(.E(E), .M(M), .EDGE_EPS(EDGE_EPS), .SHARED_EPS(SHARED_EPS), .ADD_STAGES(ADD_STAGES),
               .MUL_STAGES(MUL_STAGES), .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES)) u_is (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(1'b0), .ready_o(), .o_i({oz_q, oxy_q}), .d_i(dd_q), .te_i(te_q),
    .tmin_i(tmin_q), .tmax_i(tmax_q), .shared_i(shared_q), .valid_o(), .ready_i(1'b1), .hit_o(is_hit), .t_o(is_t),
    .u_o(is_u), .v_o(is_v), .cos_o(is_cos));

  // t0 + t (ADD), the test's results beside it
  f24_pipe #(.W(W), .STAGES(T_JOIN + IS_LATENCY)) u_d_t0 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(1'b0), .data_i(t0_i), .valid_o(), .data_o(t0_q));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_tw (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
    .a_i(t0_q), .b_i(is_t), .sub_i(1'b0), .valid_o(), .res_o(t_world_o));
  f24_pipe #(.W(4 * W + 1), .STAGES(ADD_STAGES)) u_d_out (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(1'b0), .data_i({is_hit, is_t, is_u, is_v, is_cos}), .valid_o(), .data_o({hit_o, t_o, u_o, v_o, cos_o}));
  f24_pipe #(.W(1), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(valid_i),
    .data_i(1'b0), .valid_o(valid_o), .data_o());
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
