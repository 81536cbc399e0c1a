// rgs_light: one light at one surface, the RGS's `light_packet` for one ray (paper section 3:
// Phong-like shading with shadow rays; hls/units/rgs_light.c `rgs_light_packet`, docs/shading.md),
// one ray per cycle, bit for bit as the C:
//   shadow ray  o = P, d = -L_dir (directional: type 0) or L_pos - P, |d| = sqrt(d . d),
//               tmin = e (directional) or e / |d|, tmax = +Inf (directional) or 1
//   diffuse     w = (N^ . d) / |d|; no light unless 0 < w; a spot light (type 2) scales w by
//               clamp((c - cos_outer) / (cos_inner - cos_outer), 0, 1), c = -(L_dir . d) / |d|;
//               diff = q(w) 3482 in Q12 (`q12_of`, a rounded 16 x 12-bit product)
//   highlight   R = T_R (1, -2 (N^ . D^), 0) with T_R = [D^, N^, D^; 0] (the C's `rgs_reflect`),
//               s = q(max(0, (R . d) / |d|)), squared k times (k = the material's exponent, at
//               most 8 squarings as the C's loop: one registered Q12 squaring per stage)
//   active      lit (a valid surface, not unlit, 0 < w) and diff or spec nonzero; diff = spec = 0
//               where not lit, the whole shadow ray 0 for an invalid or unlit surface
// Inputs are the light record's words 0 (type), 4..6 (L_pos), 7..9 (L_dir), 11 and 12 (the spot's
// inner and outer cone cosines), the ray offset e, and the surface's valid, unlit, P, N^, D^ and k;
// the light's colour (words 1..3) is applied by the accumulation (add_light). The thread id travels
// with the valid bit.
// Latency LATENCY = max(TW + MUL + ADD + TOI, TS + 8) with T1 = ADD + DOT + SQRT (|d|),
// TW = T1 + DIV + ADD + DIV + 2 CMP + MUL (the spot-scaled w), TC = max(3 DOT + ADD, T1) and
// TS = TC + DIV + CMP + MUL + ADD + TOI (the highlight's cosine in Q12): default 87 cycles; one ray
// per cycle (II = 1); handshake valid/ready, the pipeline advances when the output is free or
// taken. Resources: 8 `f24_dot3` (24 multipliers, 16 adders), 1 square root, 4 dividers, 5 adders,
// 4 comparators, 1 multiplier, 2 `q12_of`, 9 16 x 16-bit integer multipliers (the diffuse weight
// and 8 squarings, `q12_mul`), delay lines.
module rgs_light #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TID_BITS = 6,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int SQRT_STAGES = 9,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2,
  parameter int TOI_STAGES = 2
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 valid_i,
  output logic                 ready_o,
  input  logic [TID_BITS-1:0]  tid_i,
  input  logic [31:0]          type_i,     // light word 0: 0 directional, 1 point, 2 spot
  input  logic [3*(E+M+1)-1:0] lpos_i,     // words 4..6
  input  logic [3*(E+M+1)-1:0] ldir_i,     // words 7..9
  input  logic [E+M:0]         cos_in_i,   // word 11
  input  logic [E+M:0]         cos_out_i,  // word 12
  input  logic [E+M:0]         eps_i,
  input  logic                 sf_valid_i,
  input  logic                 unlit_i,
  input  logic [3*(E+M+1)-1:0] p_i,
  input  logic [3*(E+M+1)-1:0] n_i,
  input  logic [3*(E+M+1)-1:0] d_i,
  input  logic [3:0]           k_i,
  output logic                 valid_o,
  input  logic                 ready_i,
  output logic [TID_BITS-1:0]  tid_o,
  output logic [3*(E+M+1)-1:0] o_o,        // the shadow ray
  output logic [3*(E+M+1)-1:0] d_o,
  output logic [E+M:0]         tmin_o,
  output logic [E+M:0]         tmax_o,
  output logic                 active_o,
  output logic [15:0]          diff_o,     // Q12 weights
  output logic [15:0]          spec_o
);
  localparam int W = 1 + E + M;
  localparam int V = 3 * W;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [W-1:0] ONE = {1'b0, E'(BIAS), {M{1'b0}}};
  localparam logic [W-1:0] POS_INF = {1'b0, {E{1'b1}}, {M{1'b0}}};
  localparam int DOT = MUL_STAGES + 2 * ADD_STAGES;
  localparam int Q = MUL_STAGES + ADD_STAGES + TOI_STAGES;             // q12_of
  localparam int T0 = ADD_STAGES;                                      // d
  localparam int T1 = T0 + DOT + SQRT_STAGES;                          // |d|
  localparam int T2 = T1 + DIV_STAGES;                                 // tmin, w, the spot's cosine
  localparam int TW = T2 + ADD_STAGES + DIV_STAGES + 2 * CMP_STAGES + MUL_STAGES;  // w scaled
  localparam int TR = 2 * DOT + ADD_STAGES;                            // R
  localparam int TC = TR + DOT > T1 ? TR + DOT : T1;                   // R . d and |d| together
  localparam int TS = TC + DIV_STAGES + CMP_STAGES + Q;                // s in Q12
  localparam int LATENCY = TW + Q > TS + 8 ? TW + Q : TS + 8;

  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;

  /* verilator lint_off PINCONNECTEMPTY */
  // ---- the shadow ray's direction and length
  logic directional, spot;
  assign directional = type_i == 32'd0;
  assign spot = type_i == 32'd2;
  logic [V-1:0] sdp, ldir_q, sd, n_q;
  logic dir_q;
  for (genvar k = 0; k < 3; k++) begin : g_sd
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_sub (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .a_i(lpos_i[k*W +: W]), .b_i(p_i[k*W +: W]), .sub_i(1'b1), .valid_o(), .res_o(sdp[k*W +: W]));
    assign sd[k*W +: W] = dir_q ? {~ldir_q[k*W+W-1], ldir_q[k*W +: W-1]} : sdp[k*W +: W];
  end
  f24_pipe #(.W(2 * V + 1), .STAGES(T0)) u_d_in (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({directional, ldir_i, n_i}), .valid_o(), .data_o({dir_q, ldir_q, n_q}));
  logic [W-1:0] dd, dlen, dlen_q, cosn, cosl, cosn_q, cosl_q, eps_q, tmin_div, w, cs;
  f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_dd (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en), .valid_i(1'b0), .a_i(sd), .b_i(sd), .valid_o(), .res_o(dd));
  f24_sqrt #(.E(E), .M(M), .STAGES(SQRT_STAGES)) u_dist (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(dd), .valid_o(), .res_o(dlen));

  // ---- tmin, w = (N^ . d) / |d|, the spot's cosine -(L_dir . d) / |d|
  f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_cosn (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en), .valid_i(1'b0), .a_i(n_q), .b_i(sd), .valid_o(), .res_o(cosn));
  f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_cosl (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en), .valid_i(1'b0), .a_i(ldir_q), .b_i(sd), .valid_o(), .res_o(cosl));
  f24_pipe #(.W(2 * W), .STAGES(SQRT_STAGES)) u_d_cos (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({cosn, cosl}), .valid_o(), .data_o({cosn_q, cosl_q}));
  f24_pipe #(.W(W), .STAGES(T1)) u_d_eps (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(eps_i), .valid_o(), .data_o(eps_q));
  f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_tmin (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(eps_q), .b_i(dlen), .valid_o(), .res_o(tmin_div));
  f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_w (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(cosn_q), .b_i(dlen), .valid_o(), .res_o(w));
  f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_cs (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(cosl_q), .b_i(dlen), .valid_o(), .res_o(cs));

  // ---- lit: 0 < w; the spot's smooth step; diff = q(w) 0.85
  /* verilator lint_off UNUSEDSIGNAL */
  logic [3:0] lit_flags;  // lt only
  /* verilator lint_on UNUSEDSIGNAL */
  logic [W-1:0] c_out_q, cone, cone_q, num, f, fmin, fclamp, w_q, w_spot, w_sel;
  logic spot_q, spot_q2;
  logic [W-1:0] w_q2;
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_lit (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i('0), .b_i(w), .valid_o(), .flags_o(lit_flags), .min_o(), .max_o());
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_cone (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(cos_in_i), .b_i(cos_out_i), .sub_i(1'b1), .valid_o(), .res_o(cone));
  f24_pipe #(.W(W), .STAGES(T2)) u_d_out_cos (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(cos_out_i), .valid_o(), .data_o(c_out_q));
  f24_pipe #(.W(W), .STAGES(T2)) u_d_cone (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(cone), .valid_o(), .data_o(cone_q));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_num (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i({~cs[W-1], cs[W-2:0]}), .b_i(c_out_q), .sub_i(1'b1), .valid_o(), .res_o(num));
  f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_f (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(num), .b_i(cone_q), .valid_o(), .res_o(f));
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_fmin (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(f), .b_i(ONE), .valid_o(), .flags_o(), .min_o(fmin), .max_o());
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_fmax (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i('0), .b_i(fmin), .valid_o(), .flags_o(), .min_o(), .max_o(fclamp));
  f24_pipe #(.W(W), .STAGES(ADD_STAGES + DIV_STAGES + 2 * CMP_STAGES)) u_d_w (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en), .valid_i(1'b0), .data_i(w), .valid_o(), .data_o(w_q));
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_wspot (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(w_q), .b_i(fclamp), .valid_o(), .res_o(w_spot));
  f24_pipe #(.W(W + 1), .STAGES(MUL_STAGES)) u_d_w2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({spot_q, w_q}), .valid_o(), .data_o({spot_q2, w_q2}));
  f24_pipe #(.W(1), .STAGES(T2 + ADD_STAGES + DIV_STAGES + 2 * CMP_STAGES)) u_d_spot (.clk_i(clk_i),
    .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .data_i(spot), .valid_o(), .data_o(spot_q));
  assign w_sel = spot_q2 ? w_spot : w_q2;
  logic [15:0] qw, diff, diff_q;
  q12_of #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES), .TOI_STAGES(TOI_STAGES)) u_qw (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .x_i(w_sel), .valid_o(), .q_o(qw));
  q12_mul u_diff (.a_i(qw), .b_i(16'd3482), .p_o(diff));
  f24_pipe #(.W(16), .STAGES(LATENCY - TW - Q)) u_d_diff (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(diff), .valid_o(), .data_o(diff_q));

  // ---- the highlight: R = D^ - 2 (N^ . D^) N^ through T_R, s = q(max(0, (R . d) / |d|))^(2^k)
  logic [W-1:0] c0, cc, cr, cosr, smax;
  logic [V-1:0] d_q1, n_q1, refl, sd_q;
  f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_c0 (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en), .valid_i(1'b0), .a_i(n_i), .b_i(d_i), .valid_o(), .res_o(c0));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_cc (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(c0), .b_i(c0), .sub_i(1'b0), .valid_o(), .res_o(cc));
  f24_pipe #(.W(2 * V), .STAGES(DOT + ADD_STAGES)) u_d_dn (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({d_i, n_i}), .valid_o(), .data_o({d_q1, n_q1}));
  for (genvar k = 0; k < 3; k++) begin : g_refl
    f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_r (.clk_i(clk_i), .rst_ni(rst_ni),
      .en_i(en), .valid_i(1'b0), .a_i({d_q1[k*W +: W], n_q1[k*W +: W], d_q1[k*W +: W]}),
      .b_i({{W{1'b0}}, ~cc[W-1], cc[W-2:0], ONE}), .valid_o(), .res_o(refl[k*W +: W]));
  end
  f24_pipe #(.W(V), .STAGES(TR - T0)) u_d_sd (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(sd), .valid_o(), .data_o(sd_q));
  f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_cr (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en), .valid_i(1'b0), .a_i(refl), .b_i(sd_q), .valid_o(), .res_o(cr));
  logic [W-1:0] cr_q;
  f24_pipe #(.W(W), .STAGES(TC - TR - DOT)) u_d_cr (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(cr), .valid_o(), .data_o(cr_q));
  f24_pipe #(.W(W), .STAGES(TC - T1)) u_d_dist (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(dlen), .valid_o(), .data_o(dlen_q));
  f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_cosr (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(cr_q), .b_i(dlen_q), .valid_o(), .res_o(cosr));
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_smax (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i('0), .b_i(cosr), .valid_o(), .flags_o(), .min_o(), .max_o(smax));
  logic [15:0] s [0:8];
  logic [3:0] k_s [0:8];
  q12_of #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES), .TOI_STAGES(TOI_STAGES)) u_qs (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .x_i(smax), .valid_o(), .q_o(s[0]));
  f24_pipe #(.W(4), .STAGES(TS)) u_d_k (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(k_i), .valid_o(), .data_o(k_s[0]));
  for (genvar j = 0; j < 8; j++) begin : g_phong  // cos^(2^k): squaring j where j < k
    logic [15:0] sq;
    q12_mul u_sq (.a_i(s[j]), .b_i(s[j]), .p_o(sq));
    f24_pipe #(.W(20), .STAGES(1)) u_stage (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .data_i({k_s[j], 4'(j) < k_s[j] ? sq : s[j]}), .valid_o(), .data_o({k_s[j+1], s[j+1]}));
  end
  logic [15:0] spec_q;
  f24_pipe #(.W(16), .STAGES(LATENCY - TS - 8)) u_d_spec (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(s[8]), .valid_o(), .data_o(spec_q));

  // ---- the outputs: the shadow ray, the weights where lit, the control beside
  logic [V-1:0] sd_out, p_out;
  logic [W-1:0] tmin_out, eps_t2;
  logic dir_t2, lit_q, shade_q, dir_out, lit;
  f24_pipe #(.W(V), .STAGES(LATENCY - T0)) u_d_sdo (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(sd), .valid_o(), .data_o(sd_out));
  f24_pipe #(.W(1), .STAGES(T2)) u_d_dir2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(directional), .valid_o(), .data_o(dir_t2));
  f24_pipe #(.W(W), .STAGES(DIV_STAGES)) u_d_eps2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(eps_q), .valid_o(), .data_o(eps_t2));
  f24_pipe #(.W(W), .STAGES(LATENCY - T2)) u_d_tmin (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(dir_t2 ? eps_t2 : tmin_div), .valid_o(), .data_o(tmin_out));
  f24_pipe #(.W(1), .STAGES(LATENCY - T2 - CMP_STAGES)) u_d_lit (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(lit_flags[0]), .valid_o(), .data_o(lit_q));
  f24_pipe #(.W(V), .STAGES(LATENCY)) u_d_p (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(p_i), .valid_o(), .data_o(p_out));
  f24_pipe #(.W(TID_BITS + 2), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(valid_i), .data_i({tid_i, sf_valid_i && !unlit_i, directional}), .valid_o(valid_o),
    .data_o({tid_o, shade_q, dir_out}));
  /* verilator lint_on PINCONNECTEMPTY */
  assign o_o = shade_q ? p_out : '0;
  assign d_o = shade_q ? sd_out : '0;
  assign tmin_o = shade_q ? tmin_out : '0;
  assign tmax_o = !shade_q ? '0 : dir_out ? POS_INF : ONE;
  assign lit = shade_q && lit_q;  // an unlit or invalid surface takes no light, nor one behind it
  assign diff_o = lit ? diff_q : '0;
  assign spec_o = lit ? spec_q : '0;
  assign active_o = lit && (diff_q != 0 || spec_q != 0);
endmodule
