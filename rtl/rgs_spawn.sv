// rgs_spawn: the child rays of one surface (paper section 2.2: secondary rays through the
// transformation unit with T_R = [D^, N^, D^; O]; hls/units/rgs_spawn.c `rgs_spawn_children`,
// docs/shading.md "Secondary rays through the transformation unit"), one surface per cycle, bit for
// bit as the C:
//   c        N^ . D^                                            (`f24_dot3`)
//   back     T_R (-e, 0, t_hat), ahead T_R (e, 0, t_hat): per row ((D^_k x + N^_k 0) + D^_k t_hat) + O_k
//   mirror   T_R (1, -(c + c), 0) without translation           (`f24_dot3` rows, `f24_add`)
//   refract  eta_r = 1 / eta entering, else eta (`f24_div`); k = 1 - eta_r^2 (1 - c^2) (4 `f24_mul`,
//            2 `f24_add`), total internal reflection where k < 0 (`f24_cmp`); mu = -eta_r c -
//            sqrt(k) (`f24_mul`, `f24_sqrt`, `f24_add`); T_R (eta_r, mu, 0) (`f24_dot3` rows)
//   weights  reflection w kr tint, transmission w kt base per channel (two `q12_mul` each: kr, kt
//            the material's 13-bit shader fields), a child active if its largest channel is >= 16
//   children reflection: back, mirror; transmission: ahead and D^ for eta = 1 (`f24_cmp` eq),
//            ahead and the refracted direction, or back and mirror on total internal reflection
// The thread id travels with the valid bit.
// Latency LATENCY = max(TR, 2 DOT + ADD) with TA = max(DOT + MUL + ADD, DIV + MUL),
// TK = TA + MUL + ADD (k) and TR = TK + SQRT + ADD + DOT (the refracted direction): default 67
// cycles; one surface per cycle (II = 1); handshake valid/ready, the pipeline advances when the
// output is free or taken. Resources: 10 `f24_dot3` (30 multipliers, 20 adders), 1 divider, 1
// square root, 5 multipliers, 10 adders, 2 comparators, 12 `q12_mul`, delay lines.
module rgs_spawn #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TID_BITS = 6,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int SQRT_STAGES = 9,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 valid_i,
  output logic                 ready_o,
  input  logic [TID_BITS-1:0]  tid_i,
  input  logic [E+M:0]         eta_i,      // material word 13: the index of refraction
  input  logic [12:0]          kr_i,       // Q12 reflection weight: material word 14, bits 13..25
  input  logic [12:0]          kt_i,       // Q12 transmission weight: material word 15, bits 0..12
  input  logic [3*16-1:0]      weight_i,   // the ray's Q12 weight, R from the low half-word up
  input  logic [E+M:0]         eps_i,      // the ray offset e
  input  logic [3*(E+M+1)-1:0] o_i,        // T_R's origin, D^, N^ (x from the low word up)
  input  logic [3*(E+M+1)-1:0] d_i,
  input  logic [3*(E+M+1)-1:0] n_i,
  input  logic [E+M:0]         t_hat_i,
  input  logic                 entering_i,
  input  logic [3*16-1:0]      tint_i,
  input  logic [3*16-1:0]      base_i,
  output logic                 valid_o,
  input  logic                 ready_i,
  output logic [TID_BITS-1:0]  tid_o,
  output logic [3*(E+M+1)-1:0] r_o_o,      // the reflection ray
  output logic [3*(E+M+1)-1:0] r_d_o,
  output logic [3*16-1:0]      r_w_o,
  output logic                 r_active_o,
  output logic [3*(E+M+1)-1:0] t_o_o,      // the transmission ray
  output logic [3*(E+M+1)-1:0] t_d_o,
  output logic [3*16-1:0]      t_w_o,
  output logic                 t_active_o
);
  localparam int W = 1 + E + M;
  localparam int V = 3 * W;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [W-1:0] ONE = {1'b0, E'(BIAS), {M{1'b0}}};
  localparam int DOT = MUL_STAGES + 2 * ADD_STAGES;
  localparam int TB = DOT + ADD_STAGES;                                  // back, ahead
  localparam int TM = 2 * DOT + ADD_STAGES;                              // mirror
  localparam int TS1 = DOT + MUL_STAGES + ADD_STAGES;                    // 1 - c^2
  localparam int TE2 = DIV_STAGES + MUL_STAGES;                          // eta_r^2
  localparam int TA = TS1 > TE2 ? TS1 : TE2;
  localparam int TK = TA + MUL_STAGES + ADD_STAGES;                      // k
  localparam int TEC = (DOT > DIV_STAGES ? DOT : DIV_STAGES) + MUL_STAGES;  // eta_r c
  localparam int TMU = TK + SQRT_STAGES + ADD_STAGES;                    // mu
  localparam int TR = TMU + DOT;                                         // the refracted direction
  localparam int LATENCY = TR > TM ? TR : TM;

  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;

  /* verilator lint_off PINCONNECTEMPTY */
  // ---- c, back, ahead, mirror
  logic [W-1:0] c, cc, eps_neg;
  logic [V-1:0] back, ahead, mirror, o_q, d_q, n_q;
  assign eps_neg = {~eps_i[W-1], eps_i[W-2:0]};
  f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_c (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en), .valid_i(1'b0), .a_i(n_i), .b_i(d_i), .valid_o(), .res_o(c));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_cc (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(c), .b_i(c), .sub_i(1'b0), .valid_o(), .res_o(cc));
  f24_pipe #(.W(V), .STAGES(DOT)) u_d_o (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .data_i(o_i),
    .valid_o(), .data_o(o_q));
  f24_pipe #(.W(2 * V), .STAGES(DOT + ADD_STAGES)) u_d_dn (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({d_i, n_i}), .valid_o(), .data_o({d_q, n_q}));
  for (genvar k = 0; k < 3; k++) begin : g_row
    logic [V-1:0] row, row_q;
    logic [W-1:0] pb, pa;
    assign row = {d_i[k*W +: W], n_i[k*W +: W], d_i[k*W +: W]};
    assign row_q = {d_q[k*W +: W], n_q[k*W +: W], d_q[k*W +: W]};
    f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_pb (.clk_i(clk_i),
      .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .a_i(row), .b_i({t_hat_i, {W{1'b0}}, eps_neg}), .valid_o(),
      .res_o(pb));
    f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_pa (.clk_i(clk_i),
      .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .a_i(row), .b_i({t_hat_i, {W{1'b0}}, eps_i}), .valid_o(),
      .res_o(pa));
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_back (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .a_i(pb), .b_i(o_q[k*W +: W]), .sub_i(1'b0), .valid_o(), .res_o(back[k*W +: W]));
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_ahead (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .a_i(pa), .b_i(o_q[k*W +: W]), .sub_i(1'b0), .valid_o(), .res_o(ahead[k*W +: W]));
    f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_mirror (.clk_i(clk_i),
      .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .a_i(row_q), .b_i({{W{1'b0}}, ~cc[W-1], cc[W-2:0], ONE}),
      .valid_o(), .res_o(mirror[k*W +: W]));
  end

  // ---- refraction: eta_r, k = 1 - eta_r^2 (1 - c^2), mu = -eta_r c - sqrt(k)
  logic [W-1:0] inv, eta_q, eta, c_q1, cs, s1, s1_q, e2, e2_q, m2, kk, sk, eta_q2, ec, ec_q, mu, eta_q3;
  logic entering_q;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [3:0] k_flags, one_flags;  // lt, eq only
  /* verilator lint_on UNUSEDSIGNAL */
  f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_inv (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(ONE), .b_i(eta_i), .valid_o(), .res_o(inv));
  f24_pipe #(.W(W + 1), .STAGES(DIV_STAGES)) u_d_eta (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({entering_i, eta_i}), .valid_o(), .data_o({entering_q, eta_q}));
  assign eta = entering_q ? inv : eta_q;
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_cs (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(c), .b_i(c), .valid_o(), .res_o(cs));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_s1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(ONE), .b_i(cs), .sub_i(1'b1), .valid_o(), .res_o(s1));
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_e2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(eta), .b_i(eta), .valid_o(), .res_o(e2));
  f24_pipe #(.W(W), .STAGES(TA - TS1)) u_d_s1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(s1), .valid_o(), .data_o(s1_q));
  f24_pipe #(.W(W), .STAGES(TA - TE2)) u_d_e2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(e2), .valid_o(), .data_o(e2_q));
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_m2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(e2_q), .b_i(s1_q), .valid_o(), .res_o(m2));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_k (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(ONE), .b_i(m2), .sub_i(1'b1), .valid_o(), .res_o(kk));
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_tir (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(kk), .b_i('0), .valid_o(), .flags_o(k_flags), .min_o(), .max_o());
  f24_sqrt #(.E(E), .M(M), .STAGES(SQRT_STAGES)) u_sk (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(kk), .valid_o(), .res_o(sk));
  // eta_r c, from eta_r and c aligned at the later of the two
  f24_pipe #(.W(W), .STAGES(TEC - MUL_STAGES - DIV_STAGES)) u_d_eta2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(eta), .valid_o(), .data_o(eta_q2));
  f24_pipe #(.W(W), .STAGES(TEC - MUL_STAGES - DOT)) u_d_c1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(c), .valid_o(), .data_o(c_q1));
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_ec (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(eta_q2), .b_i(c_q1), .valid_o(), .res_o(ec));
  f24_pipe #(.W(W), .STAGES(TK + SQRT_STAGES - TEC)) u_d_ec (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(ec), .valid_o(), .data_o(ec_q));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_mu (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i({~ec_q[W-1], ec_q[W-2:0]}), .b_i(sk), .sub_i(1'b1), .valid_o(), .res_o(mu));
  f24_pipe #(.W(W), .STAGES(TMU - DIV_STAGES)) u_d_eta3 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(eta), .valid_o(), .data_o(eta_q3));
  logic [V-1:0] d_r, n_r, refr;
  f24_pipe #(.W(2 * V), .STAGES(TMU)) u_d_dn2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({d_i, n_i}), .valid_o(), .data_o({d_r, n_r}));
  for (genvar k = 0; k < 3; k++) begin : g_refr
    f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_r (.clk_i(clk_i), .rst_ni(rst_ni),
      .en_i(en), .valid_i(1'b0), .a_i({d_r[k*W +: W], n_r[k*W +: W], d_r[k*W +: W]}),
      .b_i({{W{1'b0}}, mu, eta_q3}), .valid_o(), .res_o(refr[k*W +: W]));
  end
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_one (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(eta_i), .b_i(ONE), .valid_o(), .flags_o(one_flags), .min_o(), .max_o());

  // ---- the outputs aligned at LATENCY
  logic [V-1:0] back_l, ahead_l, mirror_l, refr_l, d_l;
  logic tir_l, one_l;
  f24_pipe #(.W(2 * V), .STAGES(LATENCY - TB)) u_l_ba (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({back, ahead}), .valid_o(), .data_o({back_l, ahead_l}));
  f24_pipe #(.W(V), .STAGES(LATENCY - TM)) u_l_m (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(mirror), .valid_o(), .data_o(mirror_l));
  f24_pipe #(.W(V), .STAGES(LATENCY - TR)) u_l_r (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(refr), .valid_o(), .data_o(refr_l));
  f24_pipe #(.W(V), .STAGES(LATENCY)) u_l_d (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(d_i), .valid_o(), .data_o(d_l));
  f24_pipe #(.W(1), .STAGES(LATENCY - TK - CMP_STAGES)) u_l_tir (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(k_flags[0]), .valid_o(), .data_o(tir_l));
  f24_pipe #(.W(1), .STAGES(LATENCY - CMP_STAGES)) u_l_one (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(one_flags[2]), .valid_o(), .data_o(one_l));

  // ---- the weights in Q12: w kr tint, w kt base; a child is active from 16 on
  logic [3*16-1:0] wr, wt;
  logic act_r, act_t;
  for (genvar k = 0; k < 3; k++) begin : g_w
    logic [15:0] wkr, wkt;
    q12_mul u_kr (.a_i(weight_i[16*k +: 16]), .b_i({3'b0, kr_i}), .p_o(wkr));
    q12_mul u_tint (.a_i(wkr), .b_i(tint_i[16*k +: 16]), .p_o(wr[16*k +: 16]));
    q12_mul u_kt (.a_i(weight_i[16*k +: 16]), .b_i({3'b0, kt_i}), .p_o(wkt));
    q12_mul u_base (.a_i(wkt), .b_i(base_i[16*k +: 16]), .p_o(wt[16*k +: 16]));
  end
  assign act_r = wr[0 +: 16] >= 16'd16 || wr[16 +: 16] >= 16'd16 || wr[32 +: 16] >= 16'd16;
  assign act_t = wt[0 +: 16] >= 16'd16 || wt[16 +: 16] >= 16'd16 || wt[32 +: 16] >= 16'd16;
  f24_pipe #(.W(TID_BITS + 2 + 6 * 16), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(valid_i), .data_i({tid_i, act_r, act_t, wr, wt}), .valid_o(valid_o),
    .data_o({tid_o, r_active_o, t_active_o, r_w_o, t_w_o}));
  /* verilator lint_on PINCONNECTEMPTY */

  assign r_o_o = back_l;
  assign r_d_o = mirror_l;
  assign t_o_o = !one_l && tir_l ? back_l : ahead_l;  // total internal reflection: the mirror ray
  assign t_d_o = one_l ? d_l : tir_l ? mirror_l : refr_l;
endmodule
