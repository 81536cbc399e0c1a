// rgs_accum: one active ray's share of the RGS's accumulation (paper section 3: the shaded colour
// added to the pixel, the child rays of the ray tree; hls/units/rgs_accum.c `rgs_accumulate_ray`,
// the loop body of `op_accumulate`), one ray per cycle, bit for bit as the C:
//   colour   per channel the background (BACKGROUND's byte widened to Q12) for an invalid surface,
//            else (emission + (kd base) diffuse) + (ks tint) highlight (4 `q12_mul`, 2 saturating
//            adders; kd, ks the material's 13-bit shader fields)
//   pixel    acc + weight colour (`q12_mul`, a saturating adder)
//   children with the spawn bit and a valid surface, `rgs_spawn`'s reflection and transmission rays;
//            otherwise none (zero rays and weights, inactive, as the C's empty tasks)
//   steps    the ray's children take T_R steps on the transformation unit: it spawns, and unless
//            the live bit (the image's PROFILE_LIVE_CHILDREN) is set, whether or not a child is
//            active (the general pipeline runs them for every spawning surface)
// The colour is computed as the ray enters and travels with the thread id through `rgs_spawn`'s
// side band (its TID_BITS widened), so both come out together. The caller feeds only the packet's
// active rays (the C skips the others) and sums the steps bits (op_accumulate's children).
// Latency 1 + `rgs_spawn`'s (default 1 + 67 = 68 cycles: the operand's register splits the colour
// for the LUT6 levels), one ray per cycle (II = 1); handshake valid/ready (the register's ready
// from `rgs_spawn`'s). Resources: `rgs_spawn`, 15 `q12_mul`, 9 saturating adders, the operand's
// register (about 560 bits at e7m16), the side band's 50 bits times the latency.
module rgs_accum #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TID_BITS = 6,
  parameter logic [23:0] BACKGROUND = 24'h1A1A24,  // 0xRRGGBB of a ray that hits nothing
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
  input  logic [E+M:0]         eta_i,        // material word 13: the index of refraction
  input  logic [12:0]          kd_i,         // Q12 shader fields: word 14 bits 0..12, 13..25
  input  logic [12:0]          kr_i,
  input  logic [12:0]          kt_i,         // word 15 bits 0..12, 13..25
  input  logic [12:0]          ks_i,
  input  logic                 sf_valid_i,   // the surface (rgs_surface's outputs)
  input  logic [3*(E+M+1)-1:0] o_i,          // T_R's origin (the ray's), D^, N^
  input  logic [3*(E+M+1)-1:0] d_i,
  input  logic [3*(E+M+1)-1:0] n_i,
  input  logic [E+M:0]         t_hat_i,
  input  logic                 entering_i,
  input  logic [3*16-1:0]      base_i,       // Q12 R, G, B from the low half-word up
  input  logic [3*16-1:0]      emission_i,
  input  logic [3*16-1:0]      tint_i,
  input  logic [3*16-1:0]      weight_i,     // the ray's weight, its light sums, the pixel's sum
  input  logic [3*16-1:0]      diffuse_i,
  input  logic [3*16-1:0]      highlight_i,
  input  logic [3*16-1:0]      acc_i,
  input  logic [E+M:0]         eps_i,        // the ray offset e
  input  logic                 spawn_i,      // the packet's depth allows children
  input  logic                 live_i,       // PROFILE_LIVE_CHILDREN
  output logic                 valid_o,
  input  logic                 ready_i,
  output logic [TID_BITS-1:0]  tid_o,
  output logic [3*16-1:0]      acc_o,
  output logic [3*(E+M+1)-1:0] r_o_o,        // the reflection ray
  output logic [3*(E+M+1)-1:0] r_d_o,
  output logic [3*16-1:0]      r_w_o,
  output logic                 r_active_o,
  output logic [3*(E+M+1)-1:0] t_o_o,        // the transmission ray
  output logic [3*(E+M+1)-1:0] t_d_o,
  output logic [3*16-1:0]      t_w_o,
  output logic                 t_active_o,
  output logic                 steps_o
);
  localparam int W = E + M + 1;
  localparam int V = 3 * W;
  localparam int SIDE = TID_BITS + 48 + 2;

  function automatic logic [15:0] q_add(input logic [15:0] a, input logic [15:0] b);
    logic [16:0] s;
    s = {1'b0, a} + {1'b0, b};
    q_add = s[16] || s[15:0] == 16'hFFFF ? 16'hFFFF : s[15:0];
  endfunction

  // the colour's first half from the inputs (4 products, 2 saturating sums, the background's
  // choice), registered with the operand; its second half (the weight's product, the pixel's sum)
  // from that register into rgs_spawn's side band: 9 LUT6 levels in one cycle otherwise
  logic [47:0] local_c;
  for (genvar k = 0; k < 3; k++) begin : g_ch
    localparam logic [7:0] BG = BACKGROUND[16-8*k +: 8];
    logic [15:0] kd_b, kd_b_d, ks_t, ks_t_h;
    q12_mul u_kd (.a_i({3'd0, kd_i}), .b_i(base_i[16*k +: 16]), .p_o(kd_b));
    q12_mul u_kd_d (.a_i(kd_b), .b_i(diffuse_i[16*k +: 16]), .p_o(kd_b_d));
    q12_mul u_ks (.a_i({3'd0, ks_i}), .b_i(tint_i[16*k +: 16]), .p_o(ks_t));
    q12_mul u_ks_h (.a_i(ks_t), .b_i(highlight_i[16*k +: 16]), .p_o(ks_t_h));
    assign local_c[16*k +: 16] = sf_valid_i ? q_add(q_add(emission_i[16*k +: 16], kd_b_d), ks_t_h) : {4'd0, BG, BG[7:4]};
  end

  // ---- the operand's register (1 cycle), then rgs_spawn ----
  logic in_v, sp_ready, sf_valid, spawn, live, entering;
  logic [TID_BITS-1:0] tid;
  logic [W-1:0] eta, eps, t_hat;
  logic [12:0] kr, kt;
  logic [V-1:0] o, d, n;
  logic [47:0] loc, weight, acc, tint, base, acc_new;
  assign ready_o = !in_v || sp_ready;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) in_v <= 1'b0;
    else if (ready_o) in_v <= valid_i;
  end
  always_ff @(posedge clk_i) begin
    if (valid_i && ready_o)
      {tid, eta, kr, kt, sf_valid, o, d, n, t_hat, entering, base, tint, weight, acc, loc, eps, spawn, live} <=
        {tid_i, eta_i, kr_i, kt_i, sf_valid_i, o_i, d_i, n_i, t_hat_i, entering_i, base_i, tint_i, weight_i, acc_i,
         local_c, eps_i, spawn_i, live_i};
  end
  for (genvar k = 0; k < 3; k++) begin : g_acc
    logic [15:0] w_local;
    q12_mul u_w (.a_i(weight[16*k +: 16]), .b_i(loc[16*k +: 16]), .p_o(w_local));
    assign acc_new[16*k +: 16] = q_add(acc[16*k +: 16], w_local);
  end

  logic [SIDE-1:0] side_o;
  logic spawn_q, live_q;
  logic [V-1:0] r_o, r_d, t_o, t_d;
  logic [47:0] r_w, t_w;
  logic r_act, t_act;
  rgs_spawn #(.E(E), .M(M), .TID_BITS(SIDE), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
    .SQRT_STAGES(SQRT_STAGES), .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES)) u_spawn (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(in_v), .ready_o(sp_ready),
    .tid_i({sf_valid && spawn, live, acc_new, tid}), .eta_i(eta), .kr_i(kr), .kt_i(kt),
    .weight_i(weight), .eps_i(eps), .o_i(o), .d_i(d), .n_i(n), .t_hat_i(t_hat), .entering_i(entering),
    .tint_i(tint), .base_i(base), .valid_o(valid_o), .ready_i(ready_i), .tid_o(side_o), .r_o_o(r_o), .r_d_o(r_d),
    .r_w_o(r_w), .r_active_o(r_act), .t_o_o(t_o), .t_d_o(t_d), .t_w_o(t_w), .t_active_o(t_act));
  assign {spawn_q, live_q, acc_o, tid_o} = side_o;
  assign r_o_o = spawn_q ? r_o : '0;
  assign r_d_o = spawn_q ? r_d : '0;
  assign r_w_o = spawn_q ? r_w : '0;
  assign r_active_o = spawn_q && r_act;
  assign t_o_o = spawn_q ? t_o : '0;
  assign t_d_o = spawn_q ? t_d : '0;
  assign t_w_o = spawn_q ? t_w : '0;
  assign t_active_o = spawn_q && t_act;
  assign steps_o = spawn_q && (!live_q || r_act || t_act);
endmodule
