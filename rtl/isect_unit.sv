// isect_unit: the unit-triangle intersection unit (paper section 2.1; hls/units/isect_unit.c).
// On a ray already in unit-triangle space whose origin the rebase unit moved to distance te:
// t' = -O'z / D'z, t = te + t', u = O'x + t' D'x, v = O'y + t' D'y, hit when u >= 0, v >= 0,
// u + v <= 1 and tmin <= t < tmax; D'z is the cosine output.
// Datapath: 1 divider, 2 multipliers, 4 adders (Table 2's 3 and the rebase's t), 5 comparators.
// Latency LATENCY (default: divider 6 + multiplier 3 + adder 3 + adder 3 + comparator 1 = 16;
// te + t' runs beside the multiplier and first adder), one ray per cycle (II = 1). Handshake:
// valid/ready.
// shared_i: the triangle's shared-edge flags {u + v <= 1, v >= 0, u >= 0} (TRI_SHARED_W, _V, _U
// of hls/units/vec3.h): a flagged bound lies on an edge another triangle of the object shares and
// is widened by 2^-SHARED_EPS (SAARCOR_CFG_SHARED_EDGE_EPS, default M: one ulp at 1), so rays
// through the edge cannot slip between the two triangles' roundings; the others stay exact.
// EDGE_EPS = k > 0: the robust edge option (SAARCOR_CFG_EDGE_EPS, docs/stress.md): every bound
// becomes u, v >= -2^-k and u + v <= 1 + 2^-k (shared ones the wider of the two). Only the
// comparators' constant inputs change, picked per bound by a flag.
module isect_unit #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int LATENCY = 16,
  parameter int EDGE_EPS = 0,
  parameter int SHARED_EPS = M
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
  /* verilator lint_off UNUSEDSIGNAL */
  logic nc_lt_o [64], nc_le_o [64], nc_eq_o [64], nc_unordered_o [64];
  logic [E+M:0] nc_min_o [64], nc_max_o [64]; // comparator outputs this datapath does not use
  logic [3:0] f_u, f_v, f_uv, f_tmin, f_tmax; // {unordered, eq, le, lt}: le and lt are used
  /* verilator lint_on UNUSEDSIGNAL */
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [W-1:0] ONE = {1'b0, E'(BIAS), {M{1'b0}}};
  localparam int SK = EDGE_EPS > 0 && (SHARED_EPS == 0 || EDGE_EPS < SHARED_EPS) ? EDGE_EPS : SHARED_EPS;
  localparam logic [W-1:0] LO = EDGE_EPS > 0 ? {1'b1, E'(BIAS - EDGE_EPS), {M{1'b0}}} : '0;
  localparam logic [W-1:0] HI = EDGE_EPS > 0 ? ONE | W'(1 << (M - EDGE_EPS)) : ONE;
  localparam logic [W-1:0] LO_S = SK > 0 ? {1'b1, E'(BIAS - SK), {M{1'b0}}} : '0;
  localparam logic [W-1:0] HI_S = SK > 0 ? ONE | W'(1 << (M - SK)) : ONE;
  logic [W-1:0] oz_neg, tl, t, tdx, tdy, u, v, uv, lo_u, lo_v, hi_uv;
  logic hit;

  assign oz_neg = o_i[2*W +: W] ^ {1'b1, {(W-1){1'b0}}};
  f24_div_core #(.E(E), .M(M)) u_t (.a_i(oz_neg), .b_i(d_i[2*W +: W]), .res_o(tl));
  f24_add_core #(.E(E), .M(M)) u_te (.a_i(te_i), .b_i(tl), .sub_i(1'b0), .res_o(t));
  f24_mul_core #(.E(E), .M(M)) u_mx (.a_i(tl), .b_i(d_i[0 +: W]), .res_o(tdx));
  f24_mul_core #(.E(E), .M(M)) u_my (.a_i(tl), .b_i(d_i[W +: W]), .res_o(tdy));
  f24_add_core #(.E(E), .M(M)) u_u (.a_i(o_i[0 +: W]), .b_i(tdx), .sub_i(1'b0), .res_o(u));
  f24_add_core #(.E(E), .M(M)) u_v (.a_i(o_i[W +: W]), .b_i(tdy), .sub_i(1'b0), .res_o(v));
  f24_add_core #(.E(E), .M(M)) u_uv (.a_i(u), .b_i(v), .sub_i(1'b0), .res_o(uv));
  assign lo_u = shared_i[0] ? LO_S : LO;
  assign lo_v = shared_i[1] ? LO_S : LO;
  assign hi_uv = shared_i[2] ? HI_S : HI;
  // comparator flags {unordered, eq, le, lt}
  f24_cmp_core #(.E(E), .M(M)) u_c0 (.a_i(lo_u), .b_i(u), .lt_o(f_u[0]), .le_o(f_u[1]), .eq_o(f_u[2]),
                                     .unordered_o(f_u[3]), .min_o(nc_min_o[0]), .max_o(nc_max_o[1]));
  f24_cmp_core #(.E(E), .M(M)) u_c1 (.a_i(lo_v), .b_i(v), .lt_o(f_v[0]), .le_o(f_v[1]), .eq_o(f_v[2]),
                                     .unordered_o(f_v[3]), .min_o(nc_min_o[2]), .max_o(nc_max_o[3]));
  f24_cmp_core #(.E(E), .M(M)) u_c2 (.a_i(uv), .b_i(hi_uv), .lt_o(f_uv[0]), .le_o(f_uv[1]), .eq_o(f_uv[2]),
                                     .unordered_o(f_uv[3]), .min_o(nc_min_o[4]), .max_o(nc_max_o[5]));
  f24_cmp_core #(.E(E), .M(M)) u_c3 (.a_i(tmin_i), .b_i(t), .lt_o(f_tmin[0]), .le_o(f_tmin[1]), .eq_o(f_tmin[2]),
                                     .unordered_o(f_tmin[3]), .min_o(nc_min_o[6]), .max_o(nc_max_o[7]));
  f24_cmp_core #(.E(E), .M(M)) u_c4 (.a_i(t), .b_i(tmax_i), .lt_o(f_tmax[0]), .le_o(f_tmax[1]), .eq_o(f_tmax[2]),
                                     .unordered_o(f_tmax[3]), .min_o(nc_min_o[8]), .max_o(nc_max_o[9]));
  assign hit = f_u[1] && f_v[1] && f_uv[1] && f_tmin[1] && f_tmax[0];

  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;
  f24_pipe #(.W(1 + 4 * W), .STAGES(LATENCY)) u_pipe (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i), .data_i({hit, t, u, v, d_i[2*W +: W]}),
    .valid_o(valid_o), .data_o({hit_o, t_o, u_o, v_o, cos_o})
  );
endmodule
