// isect_unit: the unit-triangle intersection unit (paper section 2.1; hls/units/isect_unit.c).
// On a ray already in unit-triangle space whose origin the rebase unit moved to distance te:
// t' = -O'z / D'z, t = te + t', u = O'x + t' D'x, v = O'y + t' D'y, hit when u >= 0, v >= 0,
// u + v <= 1 and tmin <= t < tmax; D'z is the cosine output.
// Datapath: 1 divider, 2 multipliers, 4 adders (Table 2's 3 and the rebase's t), 5 comparators,
// all pipelined (rtl/f24_*.sv); the operands that join later wait in f24_pipe delay lines.
// Latency LATENCY = DIV_STAGES + MUL_STAGES + 2 ADD_STAGES + CMP_STAGES (default
// 11 + 4 + 2 x 6 + 2 = 29; te + t' runs beside the multiplier and first adder), one ray per
// cycle (II = 1); the clock is that of the operators (docs/synth.md). Handshake: valid/ready.
// shared_i: the triangle's shared-edge flags {u + v <= 1, v >= 0, u >= 0} (TRI_SHARED_W, _V, _U
// of hls/units/vec3.h): a flagged bound lies on an edge another triangle of the object shares and
// is widened by 2^-SHARED_EPS (SAARCOR_CFG_SHARED_EDGE_EPS, default M: one ulp at 1), so rays
// through the edge cannot slip between the two triangles' roundings; the others stay exact.
// The flags wait beside the datapath for the comparators.
// EDGE_EPS = k > 0: the robust edge option (SAARCOR_CFG_EDGE_EPS, docs/stress.md): every bound
// becomes u, v >= -2^-k and u + v <= 1 + 2^-k (shared ones the wider of the two). Only the
// comparators' constant inputs change, picked per bound by a flag.
module isect_unit #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int EDGE_EPS = 0,
  parameter int SHARED_EPS = M,
  parameter int ADD_STAGES = 6,
  parameter int MUL_STAGES = 4,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 valid_i,
  output logic                 ready_o,
  input  logic [3*(E+M+1)-1:0] o_i,
  input  logic [3*(E+M+1)-1:0] d_i,
  input  logic [E+M:0]         te_i,
  input  logic [E+M:0]         tmin_i,
  input  logic [E+M:0]         tmax_i,
  input  logic [2:0]           shared_i,
  output logic                 valid_o,
  input  logic                 ready_i,
  output logic                 hit_o,
  output logic [E+M:0]         t_o,
  output logic [E+M:0]         u_o,
  output logic [E+M:0]         v_o,
  output logic [E+M:0]         cos_o
);
  localparam int W = 1 + E + M;
  localparam int LATENCY = DIV_STAGES + MUL_STAGES + 2 * ADD_STAGES + CMP_STAGES;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [3:0] f_u, f_v, f_uv, f_tmin, f_tmax; // {unordered, eq, le, lt}: le and lt are used
  /* verilator lint_on UNUSEDSIGNAL */
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [W-1:0] ONE = {1'b0, E'(BIAS), {M{1'b0}}};
  localparam logic [W-1:0] LO = EDGE_EPS > 0 ? {1'b1, E'(BIAS - EDGE_EPS), {M{1'b0}}} : '0;
  localparam logic [W-1:0] HI = EDGE_EPS > 0 ? ONE | W'(1 << (M - EDGE_EPS)) : ONE;
  localparam int SK = EDGE_EPS > 0 && (SHARED_EPS == 0 || EDGE_EPS < SHARED_EPS) ? EDGE_EPS : SHARED_EPS;
  localparam logic [W-1:0] LO_S = SK > 0 ? {1'b1, E'(BIAS - SK), {M{1'b0}}} : '0;
  localparam logic [W-1:0] HI_S = SK > 0 ? ONE | W'(1 << (M - SK)) : ONE;
  logic [W-1:0] oz_neg, tl, te_q, dx_q, dy_q, ox_q, oy_q, t, tdx, tdy, u, v, uv, u_q, v_q, t_q, tmin_q, tmax_q;
  logic [W-1:0] lo_u, lo_v, hi_uv;
  logic [2:0] shared_q;
  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;

  /* verilator lint_off PINCONNECTEMPTY */
  // divider: t' (Ld), with te, D'x, D'y waiting beside it
  assign oz_neg = o_i[2*W +: W] ^ {1'b1, {(W-1){1'b0}}};
  f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_t (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(oz_neg), .b_i(d_i[2*W +: W]), .valid_o(), .res_o(tl));
  f24_pipe #(.W(3 * W), .STAGES(DIV_STAGES)) u_d_div (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({te_i, d_i[0 +: W], d_i[W +: W]}), .valid_o(), .data_o({te_q, dx_q, dy_q}));
  f24_pipe #(.W(2 * W), .STAGES(DIV_STAGES + MUL_STAGES)) u_d_o (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i({o_i[0 +: W], o_i[W +: W]}), .valid_o(), .data_o({ox_q, oy_q}));
  f24_pipe #(.W(2 * W + 3), .STAGES(LATENCY - CMP_STAGES)) u_d_tb (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i({tmin_i, tmax_i, shared_i}), .valid_o(), .data_o({tmin_q, tmax_q, shared_q}));
  // t = te + t' (Ld + La), waits for the comparators' inputs
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_te (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(te_q), .b_i(tl), .sub_i(1'b0), .valid_o(), .res_o(t));
  f24_pipe #(.W(W), .STAGES(MUL_STAGES + ADD_STAGES)) u_d_t (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(t), .valid_o(), .data_o(t_q));
  // u, v (Ld + Lm + La), u + v (Ld + Lm + 2 La)
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_mx (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(tl), .b_i(dx_q), .valid_o(), .res_o(tdx));
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_my (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(tl), .b_i(dy_q), .valid_o(), .res_o(tdy));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_u (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(ox_q), .b_i(tdx), .sub_i(1'b0), .valid_o(), .res_o(u));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_v (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(oy_q), .b_i(tdy), .sub_i(1'b0), .valid_o(), .res_o(v));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_uv (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(u), .b_i(v), .sub_i(1'b0), .valid_o(), .res_o(uv));
  f24_pipe #(.W(2 * W), .STAGES(ADD_STAGES)) u_d_uv (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({u, v}), .valid_o(), .data_o({u_q, v_q}));
  assign lo_u = shared_q[0] ? LO_S : LO;
  assign lo_v = shared_q[1] ? LO_S : LO;
  assign hi_uv = shared_q[2] ? HI_S : HI;
  // the five comparisons (LATENCY), flags {unordered, eq, le, lt}
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_c0 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(lo_u), .b_i(u_q), .valid_o(), .flags_o(f_u), .min_o(), .max_o());
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_c1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(lo_v), .b_i(v_q), .valid_o(), .flags_o(f_v), .min_o(), .max_o());
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_c2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(uv), .b_i(hi_uv), .valid_o(), .flags_o(f_uv), .min_o(), .max_o());
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_c3 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(tmin_q), .b_i(t_q), .valid_o(), .flags_o(f_tmin), .min_o(), .max_o());
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_c4 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(t_q), .b_i(tmax_q), .valid_o(), .flags_o(f_tmax), .min_o(), .max_o());
  assign hit_o = f_u[1] && f_v[1] && f_uv[1] && f_tmin[1] && f_tmax[0];
  f24_pipe #(.W(3 * W), .STAGES(CMP_STAGES)) u_d_out (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({t_q, u_q, v_q}), .valid_o(), .data_o({t_o, u_o, v_o}));
  // valid and the cosine beside the datapath
  f24_pipe #(.W(W), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
    .data_i(d_i[2*W +: W]), .valid_o(valid_o), .data_o(cos_o));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
