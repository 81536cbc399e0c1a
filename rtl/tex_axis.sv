// tex_axis: one axis of the RGS's bilinear texture sample (paper section 3: bilinear texture
// filtering in the shading unit; hls/units/rgs_tex.c `rgs_texel_axis`, docs/shading.md): texture
// coordinate s over n texels (centres at +1/2) to the wrapped texel index i0, its right
// neighbour i1 and the fraction in Q8 (0..256), bit for bit as the C:
//   x = s n - 1/2 (`f24_from_i32`, `f24_mul`, `f24_add`), i = floor(x) as to_i32 (`f24_to_i32`,
//   toward zero) corrected by one where x < from_i32(i) (`f24_from_i32`, `f24_cmp`; not at the
//   saturated -2^31), then f = x - from_i32(i) and q = to_i32(f 256 + 1/2) (`f24_from_i32`,
//   `f24_add`, `f24_mul`, `f24_add`, `f24_to_i32`) clamped to 0..256, and beside it the repeat
//   wrapping i mod n with the sign of C's % corrected (a restoring remainder of |i| by n, one row
//   per bit of |i|: 32 rows of 32-bit subtract-and-select spread over MOD_STAGES registers as the
//   operators spread theirs), i1 = i0 + 1 or 0 at n.
// n must be 1 .. 2^31 - 1 (mi_validate: a texture's texels lie inside the memory image).
// Anything the caller needs afterwards travels beside the datapath in side_i / side_o (SIDE_W bits).
// Latency FRONT + BACK with FRONT = CVT + MUL + ADD + TOI + CVT + CMP and BACK = max(CVT + 2 ADD +
// MUL + TOI, MOD_STAGES) (default 20 + 21 = 41 at CVT 3; 38 at CVT 2 until 2026-11-29) cycles,
// one coordinate per cycle (II = 1); clock enable en_i from the unit (it has no handshake of its
// own). Resources: 3 int-to-fp24 converters, 2 multipliers, 3 adders, 1 comparator, 2 fp24-to-int
// converters, 32 rows of a 32-bit subtractor and mux (about 1000 adder bits), the 32-bit
// correction, wrap and clamp; delay lines for x, i, n and the side band.
module tex_axis #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int SIDE_W = 1,
  parameter int CVT_STAGES = 3,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int CMP_STAGES = 2,
  parameter int TOI_STAGES = 2,
  parameter int MOD_STAGES = 16
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              en_i,
  input  logic              valid_i,
  input  logic [E+M:0]      s_i,
  input  logic [31:0]       n_i,
  input  logic [SIDE_W-1:0] side_i,
  output logic              valid_o,
  output logic [31:0]       i0_o,
  output logic [31:0]       i1_o,
  output logic [8:0]        frac_o,
  output logic [SIDE_W-1:0] side_o
);
  localparam int W = 1 + E + M;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [W-1:0] HALF = {1'b0, E'(BIAS - 1), {M{1'b0}}};
  localparam logic [W-1:0] C256 = {1'b0, E'(BIAS + 8), {M{1'b0}}};
  localparam int FRONT = CVT_STAGES + MUL_STAGES + ADD_STAGES + TOI_STAGES + CVT_STAGES + CMP_STAGES;
  localparam int FRAC_STAGES = CVT_STAGES + 2 * ADD_STAGES + MUL_STAGES + TOI_STAGES;
  localparam int BACK = FRAC_STAGES > MOD_STAGES ? FRAC_STAGES : MOD_STAGES;
  localparam int ROWS = 32;
  localparam int B = 1 + 32 + 32 + 32;  // the remainder rows' state: sign of i, n, remainder, |i| shifted

  /* verilator lint_off PINCONNECTEMPTY */
  // ---- x = s n - 1/2, i = to_i32(x), the floor's test x < from_i32(i)
  logic [W-1:0] nf, s_q, sn, x, x_q1, x_q2, x_q3, fi;
  logic [31:0] i, i_q1, i_q2;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [3:0] flags;  // lt only
  /* verilator lint_on UNUSEDSIGNAL */
  f24_from_i32 #(.E(E), .M(M), .SCALE(0), .STAGES(CVT_STAGES)) u_nf (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i),
    .valid_i(1'b0), .a_i(n_i), .valid_o(), .res_o(nf));
  f24_pipe #(.W(W), .STAGES(CVT_STAGES)) u_d_s (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .data_i(s_i), .valid_o(), .data_o(s_q));
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_sn (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .a_i(s_q), .b_i(nf), .valid_o(), .res_o(sn));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_x (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .a_i(sn), .b_i(HALF), .sub_i(1'b1), .valid_o(), .res_o(x));
  f24_to_i32 #(.E(E), .M(M), .STAGES(TOI_STAGES)) u_i (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .a_i(x), .valid_o(), .res_o(i));
  f24_pipe #(.W(W), .STAGES(TOI_STAGES + CVT_STAGES)) u_d_x1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i),
    .valid_i(1'b0), .data_i(x), .valid_o(), .data_o(x_q1));
  f24_from_i32 #(.E(E), .M(M), .SCALE(0), .STAGES(CVT_STAGES)) u_fi (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i),
    .valid_i(1'b0), .a_i(i), .valid_o(), .res_o(fi));
  f24_pipe #(.W(32), .STAGES(CVT_STAGES + CMP_STAGES)) u_d_i (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i),
    .valid_i(1'b0), .data_i(i), .valid_o(), .data_o(i_q1));
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_lt (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .a_i(x_q1), .b_i(fi), .valid_o(), .flags_o(flags), .min_o(), .max_o());
  f24_pipe #(.W(W), .STAGES(CMP_STAGES)) u_d_x2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .data_i(x_q1), .valid_o(), .data_o(x_q2));

  // ---- floor: one less where to_i32 rounded up (x negative, not an integer), except at -2^31
  assign i_q2 = flags[0] && i_q1 != 32'h8000_0000 ? i_q1 - 32'd1 : i_q1;

  // ---- the fraction: f = x - from_i32(i), q = to_i32(f 256 + 1/2), clamped to 0..256
  logic [W-1:0] fi2, f, f256, qh;
  logic [31:0] q;
  logic signed [31:0] q_s;
  logic [8:0] frac;
  f24_from_i32 #(.E(E), .M(M), .SCALE(0), .STAGES(CVT_STAGES)) u_fi2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i),
    .valid_i(1'b0), .a_i(i_q2), .valid_o(), .res_o(fi2));
  f24_pipe #(.W(W), .STAGES(CVT_STAGES)) u_d_x3 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .data_i(x_q2), .valid_o(), .data_o(x_q3));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_f (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .a_i(x_q3), .b_i(fi2), .sub_i(1'b1), .valid_o(), .res_o(f));
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_f256 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .a_i(f), .b_i(C256), .valid_o(), .res_o(f256));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_qh (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .a_i(f256), .b_i(HALF), .sub_i(1'b0), .valid_o(), .res_o(qh));
  f24_to_i32 #(.E(E), .M(M), .STAGES(TOI_STAGES)) u_q (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
    .a_i(qh), .valid_o(), .res_o(q));
  assign q_s = signed'(q);
  always_comb frac = q_s < 0 ? 9'd0 : q_s > 256 ? 9'd256 : q[8:0];
  f24_pipe #(.W(9), .STAGES(BACK - FRAC_STAGES)) u_d_frac (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i),
    .valid_i(1'b0), .data_i(frac), .valid_o(), .data_o(frac_o));

  // ---- repeat wrapping: |i| mod n by a restoring remainder, one row per bit of |i|
  logic [31:0] n_q, n_front;
  logic [SIDE_W-1:0] side_front;
  logic valid_front;
  f24_pipe #(.W(SIDE_W + 32), .STAGES(FRONT)) u_ctl_front (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i),
    .valid_i(valid_i), .data_i({side_i, n_i}), .valid_o(valid_front), .data_o({side_front, n_front}));
  logic [B-1:0] d [0:ROWS] /* verilator split_var */;
  assign d[0] = {i_q2[31], n_front, 32'd0, i_q2[31] ? 32'd0 - i_q2 : i_q2};
  for (genvar r = 0; r < ROWS; r++) begin : g_row
    logic neg;
    logic [31:0] dv, rem, a;
    logic [32:0] shifted, diff;
    always_comb begin
      {neg, dv, rem, a} = d[r];
      shifted = {rem, a[31]};
      diff = shifted - {1'b0, dv};
    end
    f24_pipe #(.W(B), .STAGES((r + 1) * MOD_STAGES / ROWS - r * MOD_STAGES / ROWS)) u_row (.clk_i(clk_i),
      .rst_ni(rst_ni), .en_i(en_i), .valid_i(1'b0),
      .data_i({neg, dv, diff[32] ? shifted[31:0] : diff[31:0], a << 1}), .valid_o(), .data_o(d[r+1]));
  end
  logic neg_l;
  logic [31:0] rem_l, m;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [31:0] a_l;  // every bit shifted out
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    {neg_l, n_q, rem_l, a_l} = d[ROWS];
    m = neg_l && rem_l != 0 ? n_q - rem_l : rem_l;  // C's % takes the sign of i; the wrap adds n
  end
  logic [31:0] m_q, n_l;
  f24_pipe #(.W(64), .STAGES(BACK - MOD_STAGES)) u_d_mod (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i),
    .valid_i(1'b0), .data_i({m, n_q}), .valid_o(), .data_o({m_q, n_l}));
  assign i0_o = m_q;
  assign i1_o = m_q + 32'd1 == n_l ? 32'd0 : m_q + 32'd1;

  f24_pipe #(.W(SIDE_W), .STAGES(BACK)) u_ctl_back (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i),
    .valid_i(valid_front), .data_i(side_front), .valid_o(valid_o), .data_o(side_o));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
