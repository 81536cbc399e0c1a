// rgs_frame: the frame of a hit the RGS shades (paper sections 2.2 and 3: the shading normal, the
// hit point and T_R = [D^, N^, D^; O] of the secondary rays; hls/units/rgs_geom.c
// `rgs_surface_frame`, called by `surface_at`), one ray per cycle, bit for bit as the C:
//   d^      |d| = sqrt(d . d), d^ = d (1 / |d|)          (`f24_inv_length`, 3 `f24_mul`)
//   t_hat   t |d|                                        (`f24_mul`)
//   n_w     the object-space normal n through the transposed 3x3 of the world-to-object matrix:
//           row r = (w2o[0][r], w2o[1][r], w2o[2][r]) . n (3 `f24_dot3`: the transformation
//           unit's rows without translation), started at once and waiting for d^
//   facing  n_w negated unless d^ . n_w < 0 (sign bit set)  (`f24_dot3`)
//   n^      n_w (1 / sqrt(n_w . n_w))                    (`f24_inv_length`, 3 `f24_mul`)
//   P       T_R (0, 0, t_hat): per row ((d^_k 0 + n^_k 0) + d^_k t_hat) + o_k (3 `f24_dot3`,
//           3 `f24_add`: xform_point's rows, so signed zeros, Inf and NaN come out as the C's)
//   entering  the sign bit of the hit's cos_n
// T_R itself is wiring (d^, n^, o). The object-space normal is selected by the caller (the
// interpolated vertex normals, or the geometric normal where their squared length is zero: a
// read the control makes). The thread id (TID_BITS) travels with the valid bit.
// Latency LATENCY = TN + DOT + ADD with DOT = MUL + 2 ADD, TD = DOT + SQRT + DIV + MUL (d^) and
// TN = TD + 2 DOT + SQRT + DIV + MUL (n^): default TD 40, TN 96, 118 cycles; one ray per cycle
// (II = 1); handshake valid/ready, the pipeline advances when the output is free or taken.
// Resources: 2 `f24_inv_length`, 7 `f24_dot3` (with those: 27 multipliers, 18 adders), 2 square
// roots, 2 dividers, and 7 multipliers,
// 3 adders, delay lines for d, n_w, d^, n^, t, t_hat, o and the control (about 25 W-bit words times
// their depths).
module rgs_frame #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TID_BITS = 6,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int SQRT_STAGES = 9,
  parameter int DIV_STAGES = 11
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 valid_i,
  output logic                 ready_o,
  input  logic [TID_BITS-1:0]  tid_i,
  input  logic [3*(E+M+1)-1:0] o_i,       // the ray: origin, direction (x, y, z from the low word up)
  input  logic [3*(E+M+1)-1:0] d_i,
  input  logic [E+M:0]         t_i,       // the hit: distance, cos_n (its sign: entering)
  input  logic [E+M:0]         cos_n_i,
  input  logic [3*(E+M+1)-1:0] n_i,       // object-space shading normal (not normalized)
  input  logic [9*(E+M+1)-1:0] w2o_i,     // the world-to-object matrix's 3x3, m[k][r] at word 3k + r
  output logic                 valid_o,
  input  logic                 ready_i,
  output logic [TID_BITS-1:0]  tid_o,
  output logic [3*(E+M+1)-1:0] d_o,       // unit direction D^
  output logic [3*(E+M+1)-1:0] n_o,       // unit shading normal N^, facing the ray
  output logic                 entering_o,
  output logic [E+M:0]         t_hat_o,
  output logic [3*(E+M+1)-1:0] p_o        // hit point
);
  localparam int W = 1 + E + M;
  localparam int V = 3 * W;
  localparam int DOT = MUL_STAGES + 2 * ADD_STAGES;
  localparam int TL = DOT + SQRT_STAGES;                       // |d|
  localparam int TD = TL + DIV_STAGES + MUL_STAGES;            // d^
  localparam int TF = TD + DOT;                                // n_w facing the ray
  localparam int TN = TF + DOT + SQRT_STAGES + DIV_STAGES + MUL_STAGES;  // n^
  localparam int LATENCY = TN + DOT + ADD_STAGES;

  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;

  /* verilator lint_off PINCONNECTEMPTY */
  // ---- d^ = d / |d|, t_hat = t |d|
  logic [W-1:0] dlen, dinv, t_q, t_hat;
  logic [V-1:0] d_q, dh;
  f24_inv_length #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES), .SQRT_STAGES(SQRT_STAGES),
    .DIV_STAGES(DIV_STAGES)) u_dinv (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .v_i(d_i),
    .valid_o(), .len_o(dlen), .inv_o(dinv));
  for (genvar k = 0; k < 3; k++) begin : g_d_d
    f24_pipe #(.W(W), .STAGES(TL + DIV_STAGES)) u_d_d (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i(d_i[k*W +: W]), .valid_o(), .data_o(d_q[k*W +: W]));
  end
  f24_pipe #(.W(W), .STAGES(TL)) u_d_t (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(t_i), .valid_o(), .data_o(t_q));
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_that (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(t_q), .b_i(dlen), .valid_o(), .res_o(t_hat));

  // ---- n_w = transposed w2o n, then turned towards the ray
  logic [V-1:0] nw, nw_q, nw_q2, nf, nf_q, nh, dh_q, dh_q2;
  logic [W-1:0] facing, ninv, that_q;
  for (genvar k = 0; k < 3; k++) begin : g_vec
    f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_dh (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .a_i(d_q[k*W +: W]), .b_i(dinv), .valid_o(), .res_o(dh[k*W +: W]));
    f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_nw (.clk_i(clk_i), .rst_ni(rst_ni),
      .en_i(en), .valid_i(1'b0), .a_i({w2o_i[(6+k)*W +: W], w2o_i[(3+k)*W +: W], w2o_i[k*W +: W]}), .b_i(n_i),
      .valid_o(), .res_o(nw[k*W +: W]));
    assign nf[k*W +: W] = {nw_q2[k*W+W-1] ^ !facing[W-1], nw_q2[k*W +: W-1]};
    f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_nh (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .a_i(nf_q[k*W +: W]), .b_i(ninv), .valid_o(), .res_o(nh[k*W +: W]));
  end
  for (genvar k = 0; k < 3; k++) begin : g_d_nw
    f24_pipe #(.W(W), .STAGES(TD - DOT)) u_d_nw (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i(nw[k*W +: W]), .valid_o(), .data_o(nw_q[k*W +: W]));
  end
  f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_facing (.clk_i(clk_i),
    .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .a_i(nw_q), .b_i(dh), .valid_o(), .res_o(facing));
  for (genvar k = 0; k < 3; k++) begin : g_d_nw2
    f24_pipe #(.W(W), .STAGES(DOT)) u_d_nw2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i(nw_q[k*W +: W]), .valid_o(), .data_o(nw_q2[k*W +: W]));
  end

  // ---- n^ = n_f / |n_f|
  f24_inv_length #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES), .SQRT_STAGES(SQRT_STAGES),
    .DIV_STAGES(DIV_STAGES)) u_ninv (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .v_i(nf),
    .valid_o(), .len_o(), .inv_o(ninv));
  for (genvar k = 0; k < 3; k++) begin : g_d_nf
    f24_pipe #(.W(W), .STAGES(DOT + SQRT_STAGES + DIV_STAGES)) u_d_nf (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i(nf[k*W +: W]), .valid_o(), .data_o(nf_q[k*W +: W]));
  end

  // ---- P = T_R (0, 0, t_hat): per row ((d^ 0 + n^ 0) + d^ t_hat) + o
  for (genvar k = 0; k < 3; k++) begin : g_d_dh
    f24_pipe #(.W(W), .STAGES(TN - TD)) u_d_dh (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i(dh[k*W +: W]), .valid_o(), .data_o(dh_q[k*W +: W]));
  end
  f24_pipe #(.W(W), .STAGES(TN - TL - MUL_STAGES)) u_d_that (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(t_hat), .valid_o(), .data_o(that_q));
  logic [V-1:0] o_q, pr;
  for (genvar k = 0; k < 3; k++) begin : g_d_o
    f24_pipe #(.W(W), .STAGES(TN + DOT)) u_d_o (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i(o_i[k*W +: W]), .valid_o(), .data_o(o_q[k*W +: W]));
  end
  for (genvar k = 0; k < 3; k++) begin : g_p
    f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_row (.clk_i(clk_i),
      .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .a_i({dh_q[k*W +: W], nh[k*W +: W], dh_q[k*W +: W]}),
      .b_i({that_q, {(2*W){1'b0}}}), .valid_o(), .res_o(pr[k*W +: W]));
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_t (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .a_i(pr[k*W +: W]), .b_i(o_q[k*W +: W]), .sub_i(1'b0), .valid_o(), .res_o(p_o[k*W +: W]));
  end

  // ---- the outputs that wait: d^, n^, t_hat; valid, the thread id and entering beside
  for (genvar k = 0; k < 3; k++) begin : g_d_dh2
    f24_pipe #(.W(W), .STAGES(DOT + ADD_STAGES)) u_d_dh2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i(dh_q[k*W +: W]), .valid_o(), .data_o(dh_q2[k*W +: W]));
  end
  assign d_o = dh_q2;
  logic [V+W-1:0] out_d, out_q;
  assign out_d = {that_q, nh};
  for (genvar k = 0; k < 4; k++) begin : g_d_out
    f24_pipe #(.W(W), .STAGES(DOT + ADD_STAGES)) u_d_out (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i(out_d[k*W +: W]), .valid_o(), .data_o(out_q[k*W +: W]));
  end
  assign {t_hat_o, n_o} = out_q;
  f24_pipe #(.W(TID_BITS + 1), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(valid_i), .data_i({tid_i, cos_n_i[W-1]}), .valid_o(valid_o), .data_o({tid_o, entering_o}));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
