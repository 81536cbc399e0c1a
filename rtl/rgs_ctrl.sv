// rgs_ctrl: the RGS's per-block control (paper sections 2.2 and 3, Figure 2: the RGS's thread of a
// 2x2 pixel block; hls/units/rgs.c `rgs_block_begin`, `rgs_step`, `rgs_block_finish`), bit for bit
// as `rgs_render_block`:
//   frame    once after reset: the header's texture and light counts (at most 64 lights), the
//            scene bounds and the region starts (words 9..34), the camera block (loaded into
//            `rgs_raygen`, its profile word kept); e = max of the bounds' extents / 2^10 (the C's
//            f24_sub, f24_max from 0 and f24_div on one `f24_add`, `f24_cmp`, `f24_div`)
//   RB_GEN   a block (x0, y0) in: its primary packet from `rgs_raygen`, pushed with weights one
//   RB_NEXT  pop the ray-tree stack (RGS_STACK = MAX_DEPTH + 2 tasks: rays, Q12 weights, depth),
//            unless it is empty or RGS_MAX_PACKETS packets were started: then RB_DONE
//   RB_TRACE the packet out on the trace port (tmin 0, tmax +Inf, TRACE_* flags of the profile),
//            its hits back; the first packet's hits are the block's primary hits
//   RB_SURFACES  the 4 surfaces (`rgs_surface`, which owns the line port meanwhile), their
//            exponents, diffuse sums at the ambient 0.15 (one for unlit), highlights zero
//   RB_LIGHT per light: its 16 words read (4 or 5 lines), `rgs_light` on the 4 surfaces, `rgs_light_colour`;
//            RB_SHADOW_TRACE with shadows and an active shadow ray: the shadow packet traced
//            (TRACE_ANY_HIT under PROFILE_ANY_HIT), light reaching the rays without a hit;
//            `rgs_add_light` adds it to the visible rays
//   RB_ACCUM `rgs_accum` for each active ray (pixel sums, children while the depth + 1 is at most
//            max_depth_i and MAX_DEPTH and the profile has secondary rays); the transmission task,
//            then the reflection task pushed if they have an active ray (dropped on a full stack)
//   RB_DONE  the pixels (per channel min(255, (acc 255 + 2048) >> 12), 0xRRGGBB) and the primary
//            hits out
// The configuration is the general design (hls/config.h: shadows, secondary rays, refraction,
// textures) with the traversal unit's stack algorithm (flags bits 4..6 zero).
// BLOCKS = 1: one block at a time, its state (the stack of RGS_STACK tasks, about 1 Kbit each at
// e7m16, the current packet, its surfaces, sums and shadow packet) in registers; the DynRTP's 64
// threads will keep it in block RAM with several blocks in flight. The tag given with the block
// goes out with its trace requests and its pixels (the top routes the hits back by it).
// Latency: a sequence per block, its phases one after another, the 4 rays streamed through each
// phase's unit: about 20 + `rgs_surface` (the 4 rays offered as it takes them: its steps per hit,
// the last frame's 118 overlapped by none) + per light (`rgs_light` 87 + 4, after its 16 words' 4 or 5 lines
// unless the record held is that light's: one light is read once) + 4 `rgs_add_light` + 4 +
// `rgs_accum` 67 cycles per packet, plus the trace; the bench measures it (cornell 32x24: 764
// cycles a block, per state with tb_rgs_ctrl). Throughput: one block per its latency. Resources: `rgs_raygen`,
// `rgs_surface`, `rgs_light`, `rgs_light_colour`, `rgs_add_light`, `rgs_accum`, one `f24_add`,
// `f24_cmp`, `f24_div` (frame set-up), the block's registers (the stack dominates: RGS_STACK x 4
// rays x (6 W + 48) bits).
module rgs_ctrl #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TAG_BITS = 6,
  parameter int MAX_DEPTH = 8,    // RGS_MAX_DEPTH (SAARCOR_CFG_MAX_DEPTH)
  parameter int CVT_STAGES = 2,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int SQRT_STAGES = 9,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2,
  parameter int TOI_STAGES = 2,
  parameter int MOD_STAGES = 16,
  parameter int LW = 4            // words per line of the read port (the shading cache's 16 bytes)
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic [3:0]               max_depth_i,  // rgs_config: secondary levels, shadow rays
  input  logic                     shadows_i,
  // a block from the tile controller
  input  logic                     blk_valid_i,
  output logic                     blk_ready_o,
  input  logic [TAG_BITS-1:0]      blk_tag_i,
  input  logic [31:0]              blk_x_i,
  input  logic [31:0]              blk_y_i,
  // packets to trace (trace_core's packet input) and their hits back (its result output)
  output logic                     tr_valid_o,
  input  logic                     tr_ready_i,
  output logic [TAG_BITS-1:0]      tr_tag_o,
  output logic [2:0]               tr_flags_o,
  output logic [3:0]               tr_active_o,
  output logic [4*3*(E+M+1)-1:0]   tr_o_o,
  output logic [4*3*(E+M+1)-1:0]   tr_d_o,
  output logic [4*(E+M+1)-1:0]     tr_tmin_o,
  output logic [4*(E+M+1)-1:0]     tr_tmax_o,
  input  logic                     hit_valid_i,
  output logic                     hit_ready_o,
  input  logic [4*32-1:0]          hit_inst_i,
  input  logic [4*32-1:0]          hit_tri_i,
  input  logic [4*(E+M+1)-1:0]     hit_t_i,
  input  logic [4*(E+M+1)-1:0]     hit_u_i,
  input  logic [4*(E+M+1)-1:0]     hit_v_i,
  input  logic [4*(E+M+1)-1:0]     hit_cos_i,
  // line read port: a request names a line by its first word's address, the response is its LW words
  output logic                     mem_req_valid_o,
  input  logic                     mem_req_ready_i,
  output logic [31:0]              mem_addr_o,
  input  logic                     mem_rsp_valid_i,
  input  logic [32*LW-1:0]         mem_rdata_i,
  // the block's pixels and primary hits
  output logic                     px_valid_o,
  input  logic                     px_ready_i,
  output logic [TAG_BITS-1:0]      px_tag_o,
  output logic [4*24-1:0]          px_rgb_o,     // pixel i (x0 + (i & 1), y0 + (i >> 1)) at bits 24 i
  output logic [4*32-1:0]          px_inst_o,
  output logic [4*32-1:0]          px_tri_o,
  output logic [4*(E+M+1)-1:0]     px_t_o,
  output logic [4*(E+M+1)-1:0]     px_u_o,
  output logic [4*(E+M+1)-1:0]     px_v_o,
  output logic [4*(E+M+1)-1:0]     px_cos_o
);
  localparam int W = 1 + E + M;
  localparam int V = 3 * W;
  localparam int STACK = MAX_DEPTH + 2;
  localparam int SPW = $clog2(STACK + 1);
  localparam int MAX_PACKETS = (1 << (MAX_DEPTH + 1)) - 1;
  localparam int PW = MAX_DEPTH + 2;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [W-1:0] POS_INF = {1'b0, {E{1'b1}}, {M{1'b0}}};
  localparam logic [W-1:0] F1024 = {1'b0, E'(BIAS + 10), {M{1'b0}}};
  localparam logic [31:0] NO_HIT = 32'hFFFFFFFF;
  localparam logic [15:0] Q_ONE = 16'd4096, Q_AMBIENT = 16'd614;
  localparam int SETUP_AT = 9, SETUP_WORDS = 26;  // header words 9..34

  typedef enum logic [4:0] {
    S_RESET, S_SETUP, S_CAMERA, S_EXTENT, S_MAX, S_EPS, S_IDLE, S_GEN, S_NEXT, S_TRACE, S_HITS, S_SURF, S_LIGHT,
    S_LREC, S_LCALC, S_STRACE, S_SHITS, S_ADD, S_ACCUM, S_PUSH_R, S_DONE
  } state_t;
  state_t st;

  // ---- reads of the control: bursts of n words into buf_q (line_reader), the port rgs_surface's
  // in S_SURF ----
  logic [31:0] buf_q [SETUP_WORDS], rd_at, rd_addr;
  logic [32*SETUP_WORDS-1:0] rd_words;
  logic burst_done, sf_port, rd_start, rd_req;
  logic [4:0] cam_q;  // the camera word into rgs_raygen next
  logic sf_req_valid;
  logic [31:0] sf_req_addr;
  assign sf_port = st == S_SURF;
  assign mem_req_valid_o = sf_port ? sf_req_valid : rd_req;
  assign mem_addr_o = sf_port ? sf_req_addr : rd_addr;
  // a burst starts in the cycle its address is known: the header's words 9..34 after reset, then the
  // camera block (its address among them), a light's record
  logic light_read;
  assign light_read = st == S_LIGHT && light_q < n_lights_q && !(lrec_ok_q && lrec_at_q == light_q);
  assign rd_start = st == S_RESET || (st == S_SETUP && burst_done) || light_read;
  assign rd_at = st == S_RESET ? 32'(SETUP_AT) : st == S_SETUP ? buf_q[18 + 2 * 6 - SETUP_AT]
                                                                : light_base_q + 32'd16 * light_q;
  line_reader #(.MAXW(SETUP_WORDS), .LW(LW)) u_rd (
    .clk_i, .rst_ni, .start_i(rd_start), .addr_i(rd_at), .n_i(st == S_RESET ? 5'(SETUP_WORDS) : 5'd16),
    .req_valid_o(rd_req), .req_ready_i(!sf_port && mem_req_ready_i), .req_addr_o(rd_addr),
    .rsp_valid_i(!sf_port && mem_rsp_valid_i), .rsp_line_i(mem_rdata_i), .done_o(burst_done), .words_o(rd_words));
  for (genvar k = 0; k < SETUP_WORDS; k++) begin : g_buf
    assign buf_q[k] = rd_words[32*k +: 32];
  end

  // ---- the frame's constants ----
  logic [31:0] n_tex_q, n_lights_q, inst_base_q, obj_base_q, mat_base_q, tex_base_q, light_base_q;
  logic [4:0] profile_q;  // PROFILE_* bits
  logic [W-1:0] eps_q, ext_q [3], bnd_q [6];  // e; the extents, the scene bounds (lo, hi)
  logic [2:0] flags_prim, flags_shadow;
  assign flags_prim = {profile_q[0] && profile_q[4], 1'b0, profile_q[0]};
  assign flags_shadow = {profile_q[0] && profile_q[4], profile_q[1], profile_q[0]};

  // ---- the block's state ----
  logic [TAG_BITS-1:0] tag_q;
  logic [V-1:0] so_q [STACK][4], sd_q [STACK][4];
  logic [3:0] sact_q [STACK];
  logic [47:0] sw_q [STACK][4];
  logic [3:0] sdep_q [STACK];
  logic [SPW-1:0] sp_q;
  logic [PW-1:0] packets_q;
  logic [V-1:0] co_q [4], cd_q [4];   // the current packet
  logic [3:0] cact_q, cdep_q;
  logic [47:0] cw_q [4];
  logic [31:0] hinst_q [4], htri_q [4], pinst_q [4], ptri_q [4];
  logic [W-1:0] ht_q [4], hu_q [4], hv_q [4], hcos_q [4], pt_q [4], pu_q [4], pv_q [4], pcos_q [4];
  logic [47:0] acc_q [4], dif_q [4], hil_q [4];
  // the surfaces
  logic sfv_q [4], ent_q [4], unlit_q [4];
  logic [V-1:0] sp_p_q [4], sf_d_q [4], sf_n_q [4];
  logic [W-1:0] that_q [4];
  logic [3:0] k_q [4];
  logic [W-1:0] eta_q [4];
  logic [12:0] kd_q [4], kr_q [4], kt_q [4], ks_q [4];
  logic [47:0] base_q [4], emis_q [4], tint_q [4];
  // the light and its shadow packet
  logic [31:0] light_q, lrec_q [13], lrec_at_q;  // lrec_q holds light lrec_at_q's record if lrec_ok_q
  logic lrec_ok_q;
  logic [V-1:0] sho_q [4], shd_q [4];
  logic [W-1:0] shmin_q [4], shmax_q [4];
  logic [3:0] shact_q, visible_q;
  logic [15:0] diff_q [4], spec_q [4];
  logic [47:0] colour_q;
  logic colour_done_q;
  // the children being formed
  logic [V-1:0] ro_q [4], rdir_q [4], to_q [4], tdir_q [4];
  logic [47:0] rw_q [4], tw_q [4];
  logic [3:0] ract_q, tact_q;
  logic [2:0] in_q, out_q;  // rays issued to and collected from the unit of the current step

  // ---- units ----
  /* verilator lint_off PINCONNECTEMPTY */
  logic cam_valid, rg_blk_ready, rg_valid;
  logic [3:0] rg_active;
  logic [4*V-1:0] rg_o, rg_d;
  assign cam_valid = st == S_CAMERA && burst_done && cam_q < 5'd16;  // from the burst's words, one a cycle
  rgs_raygen #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .MUL_STAGES(MUL_STAGES), .CVT_STAGES(CVT_STAGES)) u_gen (
    .clk_i(clk_i), .rst_ni(rst_ni), .cam_valid_i(cam_valid), .cam_ready_o(), .cam_idx_i(cam_q[3:0]),
    .cam_word_i(buf_q[cam_q]), .blk_valid_i(st == S_IDLE && blk_valid_i), .blk_ready_o(rg_blk_ready),
    .blk_x_i(blk_x_i), .blk_y_i(blk_y_i), .pkt_valid_o(rg_valid), .pkt_ready_i(st == S_GEN),
    .pkt_active_o(rg_active), .pkt_o_o(rg_o), .pkt_d_o(rg_d), .pkt_tmin_o(), .pkt_tmax_o());

  // frame set-up: the extents (f24_sub), their maximum from 0 (f24_max), / 2^10
  logic ad_valid, cm_valid, dv_valid;
  logic [W-1:0] ad_r, cm_max, dv_r;
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_sub (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(st == S_EXTENT && in_q < 3'd3), .a_i(bnd_q[3 + in_q]), .b_i(bnd_q[in_q]),
    .sub_i(1'b1), .valid_o(ad_valid), .res_o(ad_r));
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_max (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(st == S_MAX && in_q == out_q), .a_i(eps_q), .b_i(ext_q[out_q[1:0]]), .valid_o(cm_valid), .flags_o(),
    .min_o(), .max_o(cm_max));
  f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_div (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(st == S_EPS && in_q == 3'd0), .a_i(eps_q), .b_i(F1024), .valid_o(dv_valid), .res_o(dv_r));

  // the surfaces
  logic sf_ready, sf_valid, sf_sfv, sf_ent, sf_unlit;
  logic [V-1:0] sf_p, sf_d, sf_n;
  logic [W-1:0] sf_that;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [31:0] sf_mat;  // the accumulation takes the material's fields from the surface
  /* verilator lint_on UNUSEDSIGNAL */
  logic [3:0] sf_k;
  logic [W-1:0] sf_eta;
  logic [12:0] sf_kd, sf_kr, sf_kt, sf_ks;
  logic [47:0] sf_base, sf_emis, sf_tint;
  rgs_surface #(.E(E), .M(M), .TID_BITS(1), .CVT_STAGES(CVT_STAGES), .MUL_STAGES(MUL_STAGES),
    .ADD_STAGES(ADD_STAGES), .SQRT_STAGES(SQRT_STAGES), .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES),
    .TOI_STAGES(TOI_STAGES), .MOD_STAGES(MOD_STAGES)) u_surface (
    .clk_i(clk_i), .rst_ni(rst_ni), .inst_base_i(inst_base_q), .obj_base_i(obj_base_q), .mat_base_i(mat_base_q),
    .tex_base_i(tex_base_q), .n_tex_i(n_tex_q), .valid_i(st == S_SURF && in_q < 3'd4),
    .ready_o(sf_ready), .tid_i(1'b0), .active_i(cact_q[in_q[1:0]]), .o_i(co_q[in_q[1:0]]), .d_i(cd_q[in_q[1:0]]),
    .inst_i(hinst_q[in_q[1:0]]), .tri_i(htri_q[in_q[1:0]]), .t_i(ht_q[in_q[1:0]]), .u_i(hu_q[in_q[1:0]]),
    .v_i(hv_q[in_q[1:0]]), .cos_n_i(hcos_q[in_q[1:0]]), .mem_req_valid_o(sf_req_valid),
    .mem_req_ready_i(sf_port && mem_req_ready_i), .mem_addr_o(sf_req_addr),
    .mem_rsp_valid_i(sf_port && mem_rsp_valid_i), .mem_rdata_i(mem_rdata_i), .valid_o(sf_valid), .ready_i(1'b1),
    .tid_o(), .sf_valid_o(sf_sfv), .p_o(sf_p), .d_o(sf_d), .n_o(sf_n), .t_hat_o(sf_that), .entering_o(sf_ent),
    .mat_o(sf_mat), .unlit_o(sf_unlit), .k_o(sf_k), .eta_o(sf_eta), .kd_o(sf_kd), .kr_o(sf_kr),
    .kt_o(sf_kt), .ks_o(sf_ks), .base_o(sf_base), .emission_o(sf_emis), .tint_o(sf_tint));

  // a light: the 4 surfaces streamed through rgs_light, its colour beside
  logic li_ready, li_valid, li_active, lc_valid;
  logic [1:0] li_tid;
  logic [V-1:0] li_o, li_d;
  logic [W-1:0] li_tmin, li_tmax;
  logic [15:0] li_diff, li_spec;
  logic [47:0] lc_q;
  logic [V-1:0] v_lpos, v_ldir;
  assign v_lpos = {lrec_q[6][W-1:0], lrec_q[5][W-1:0], lrec_q[4][W-1:0]};
  assign v_ldir = {lrec_q[9][W-1:0], lrec_q[8][W-1:0], lrec_q[7][W-1:0]};
  rgs_light #(.E(E), .M(M), .TID_BITS(2), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
    .SQRT_STAGES(SQRT_STAGES), .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES), .TOI_STAGES(TOI_STAGES)) u_light (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(st == S_LCALC && in_q < 3'd4), .ready_o(li_ready), .tid_i(in_q[1:0]),
    .type_i(lrec_q[0]), .lpos_i(v_lpos), .ldir_i(v_ldir), .cos_in_i(lrec_q[11][W-1:0]),
    .cos_out_i(lrec_q[12][W-1:0]), .eps_i(eps_q), .sf_valid_i(sfv_q[in_q[1:0]]), .unlit_i(unlit_q[in_q[1:0]]),
    .p_i(sp_p_q[in_q[1:0]]), .n_i(sf_n_q[in_q[1:0]]), .d_i(sf_d_q[in_q[1:0]]), .k_i(k_q[in_q[1:0]]),
    .valid_o(li_valid), .ready_i(1'b1), .tid_o(li_tid), .o_o(li_o), .d_o(li_d), .tmin_o(li_tmin), .tmax_o(li_tmax),
    .active_o(li_active), .diff_o(li_diff), .spec_o(li_spec));
  rgs_light_colour #(.E(E), .M(M), .TID_BITS(1), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
    .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES), .TOI_STAGES(TOI_STAGES)) u_colour (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(st == S_LCALC && in_q == 3'd0), .ready_o(), .tid_i(1'b0),
    .colour_i({lrec_q[3][W-1:0], lrec_q[2][W-1:0], lrec_q[1][W-1:0]}), .valid_o(lc_valid), .ready_i(1'b1),
    .tid_o(), .q_o(lc_q));

  // the visible rays' sums, one ray at a time
  logic al_valid;
  logic [1:0] al_tid;
  logic [47:0] al_dif, al_hil;
  rgs_add_light #(.TID_BITS(2)) u_add (.clk_i(clk_i), .rst_ni(rst_ni),
    .valid_i(st == S_ADD && in_q < 3'd4 && visible_q[in_q[1:0]]), .ready_o(), .tid_i(in_q[1:0]),
    .diffuse_i(dif_q[in_q[1:0]]), .highlight_i(hil_q[in_q[1:0]]), .diff_i(diff_q[in_q[1:0]]),
    .spec_i(spec_q[in_q[1:0]]), .colour_i(colour_q), .valid_o(al_valid), .ready_i(1'b1), .tid_o(al_tid),
    .diffuse_o(al_dif), .highlight_o(al_hil));

  // the accumulation of the active rays, streamed
  logic ac_ready, ac_valid, ac_ract, ac_tact, children_on;
  logic [1:0] ac_tid;
  logic [47:0] ac_acc, ac_rw, ac_tw;
  logic [V-1:0] ac_ro, ac_rd, ac_to, ac_td;
  logic [4:0] depth1;
  assign depth1 = {1'b0, cdep_q} + 5'd1;
  assign children_on = depth1 <= {1'b0, max_depth_i} && depth1 <= 5'(MAX_DEPTH) && !profile_q[2];
  rgs_accum #(.E(E), .M(M), .TID_BITS(2), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
    .SQRT_STAGES(SQRT_STAGES), .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES)) u_accum (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(st == S_ACCUM && in_q < 3'd4 && cact_q[in_q[1:0]]), .ready_o(ac_ready),
    .tid_i(in_q[1:0]), .eta_i(eta_q[in_q[1:0]]), .kd_i(kd_q[in_q[1:0]]), .kr_i(kr_q[in_q[1:0]]),
    .kt_i(kt_q[in_q[1:0]]), .ks_i(ks_q[in_q[1:0]]), .sf_valid_i(sfv_q[in_q[1:0]]),
    .o_i(co_q[in_q[1:0]]), .d_i(sf_d_q[in_q[1:0]]), .n_i(sf_n_q[in_q[1:0]]), .t_hat_i(that_q[in_q[1:0]]),
    .entering_i(ent_q[in_q[1:0]]), .base_i(base_q[in_q[1:0]]), .emission_i(emis_q[in_q[1:0]]),
    .tint_i(tint_q[in_q[1:0]]), .weight_i(cw_q[in_q[1:0]]), .diffuse_i(dif_q[in_q[1:0]]),
    .highlight_i(hil_q[in_q[1:0]]), .acc_i(acc_q[in_q[1:0]]), .eps_i(eps_q), .spawn_i(children_on),
    .live_i(profile_q[3]), .valid_o(ac_valid), .ready_i(1'b1), .tid_o(ac_tid), .acc_o(ac_acc), .r_o_o(ac_ro),
    .r_d_o(ac_rd), .r_w_o(ac_rw), .r_active_o(ac_ract), .t_o_o(ac_to), .t_d_o(ac_td), .t_w_o(ac_tw),
    .t_active_o(ac_tact), .steps_o());
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- outputs ----
  assign blk_ready_o = st == S_IDLE && rg_blk_ready;
  assign tr_valid_o = st == S_TRACE || st == S_STRACE;
  assign tr_tag_o = tag_q;
  assign tr_flags_o = st == S_STRACE ? flags_shadow : flags_prim;
  assign hit_ready_o = st == S_HITS || st == S_SHITS;
  assign px_valid_o = st == S_DONE;
  assign px_tag_o = tag_q;
  for (genvar i = 0; i < 4; i++) begin : g_ray
    assign tr_active_o[i] = st == S_STRACE ? shact_q[i] : cact_q[i];
    assign tr_o_o[V*i +: V] = st == S_STRACE ? sho_q[i] : co_q[i];
    assign tr_d_o[V*i +: V] = st == S_STRACE ? shd_q[i] : cd_q[i];
    assign tr_tmin_o[W*i +: W] = st == S_STRACE ? shmin_q[i] : '0;
    assign tr_tmax_o[W*i +: W] = st == S_STRACE ? shmax_q[i] : POS_INF;
    for (genvar k = 0; k < 3; k++) begin : g_ch
      logic [23:0] v;
      assign v = (acc_q[i][16*k +: 16] * 24'd255 + 24'd2048) >> 12;
      assign px_rgb_o[24*i + 16 - 8*k +: 8] = v < 24'd255 ? v[7:0] : 8'hFF;
    end
    assign px_inst_o[32*i +: 32] = pinst_q[i];
    assign px_tri_o[32*i +: 32] = ptri_q[i];
    assign px_t_o[W*i +: W] = pt_q[i];
    assign px_u_o[W*i +: W] = pu_q[i];
    assign px_v_o[W*i +: W] = pv_q[i];
    assign px_cos_o[W*i +: W] = pcos_q[i];
  end

  // ---- the sequence ----
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st <= S_RESET;
      lrec_ok_q <= 1'b0;
    end else begin
      if (cam_valid) cam_q <= cam_q + 5'd1;
      unique case (st)
        S_RESET: st <= S_SETUP;  // the header's words (rd_start)
        S_SETUP:  // words 9..34: buf_q[w - 9]
          if (burst_done) begin
            n_tex_q <= buf_q[0];
            n_lights_q <= buf_q[1] < 32'd64 ? buf_q[1] : 32'd64;
            mat_base_q <= buf_q[18 + 2 * 1 - SETUP_AT];
            tex_base_q <= buf_q[18 + 2 * 2 - SETUP_AT];
            obj_base_q <= buf_q[18 + 2 * 5 - SETUP_AT];
            light_base_q <= buf_q[18 + 2 * 7 - SETUP_AT];
            inst_base_q <= buf_q[18 + 2 * 8 - SETUP_AT];
            cam_q <= '0;  // the camera's words (rd_start)
            for (int k = 0; k < 6; k++) bnd_q[k] <= buf_q[12 + k - SETUP_AT][W-1:0];
            st <= S_CAMERA;
          end
        S_CAMERA:  // into rgs_raygen once read; the profile is word 3
          if (burst_done && cam_q == 5'd16) begin
            profile_q <= buf_q[3][4:0];
            in_q <= '0;
            out_q <= '0;
            st <= S_EXTENT;
          end
        S_EXTENT: begin
          if (in_q < 3'd3) in_q <= in_q + 3'd1;
          if (ad_valid) begin
            ext_q[out_q[1:0]] <= ad_r;
            out_q <= out_q + 3'd1;
            if (out_q == 3'd2) begin
              eps_q <= '0;
              in_q <= '0;
              out_q <= '0;
              st <= S_MAX;
            end
          end
        end
        S_MAX: begin
          if (in_q == out_q) in_q <= in_q + 3'd1;
          if (cm_valid) begin
            eps_q <= cm_max;
            out_q <= out_q + 3'd1;
            if (out_q == 3'd2) begin
              in_q <= '0;
              st <= S_EPS;
            end
          end
        end
        S_EPS: begin
          if (in_q == 3'd0) in_q <= 3'd1;
          if (dv_valid) begin
            eps_q <= dv_r;
            st <= S_IDLE;
          end
        end
        S_IDLE:
          if (blk_valid_i && rg_blk_ready) begin
            tag_q <= blk_tag_i;
            st <= S_GEN;
          end
        S_GEN:
          if (rg_valid) begin
            for (int i = 0; i < 4; i++) begin
              so_q[0][i] <= rg_o[V*i +: V];
              sd_q[0][i] <= rg_d[V*i +: V];
              sw_q[0][i] <= {3{Q_ONE}};
              acc_q[i] <= '0;
            end
            sact_q[0] <= rg_active;
            sdep_q[0] <= '0;
            sp_q <= SPW'(1);
            packets_q <= '0;
            st <= S_NEXT;
          end
        S_NEXT:
          if (sp_q == '0 || packets_q >= PW'(MAX_PACKETS)) st <= S_DONE;
          else begin
            for (int i = 0; i < 4; i++) begin
              co_q[i] <= so_q[sp_q - SPW'(1)][i];
              cd_q[i] <= sd_q[sp_q - SPW'(1)][i];
              cw_q[i] <= sw_q[sp_q - SPW'(1)][i];
            end
            cact_q <= sact_q[sp_q - SPW'(1)];
            cdep_q <= sdep_q[sp_q - SPW'(1)];
            sp_q <= sp_q - SPW'(1);
            packets_q <= packets_q + PW'(1);
            st <= S_TRACE;
          end
        S_TRACE:
          if (tr_ready_i) st <= S_HITS;
        S_HITS:
          if (hit_valid_i) begin
            for (int i = 0; i < 4; i++) begin
              hinst_q[i] <= hit_inst_i[32*i +: 32];
              htri_q[i] <= hit_tri_i[32*i +: 32];
              ht_q[i] <= hit_t_i[W*i +: W];
              hu_q[i] <= hit_u_i[W*i +: W];
              hv_q[i] <= hit_v_i[W*i +: W];
              hcos_q[i] <= hit_cos_i[W*i +: W];
              if (packets_q == PW'(1)) begin
                pinst_q[i] <= hit_inst_i[32*i +: 32];
                ptri_q[i] <= hit_tri_i[32*i +: 32];
                pt_q[i] <= hit_t_i[W*i +: W];
                pu_q[i] <= hit_u_i[W*i +: W];
                pv_q[i] <= hit_v_i[W*i +: W];
                pcos_q[i] <= hit_cos_i[W*i +: W];
              end
            end
            in_q <= '0;
            out_q <= '0;
            st <= S_SURF;
          end
        S_SURF: begin
          if (in_q < 3'd4 && sf_ready) in_q <= in_q + 3'd1;  // the next ray while the last is shaded
          if (sf_valid) begin
            sfv_q[out_q[1:0]] <= sf_sfv;
            sp_p_q[out_q[1:0]] <= sf_p;
            sf_d_q[out_q[1:0]] <= sf_d;
            sf_n_q[out_q[1:0]] <= sf_n;
            that_q[out_q[1:0]] <= sf_that;
            ent_q[out_q[1:0]] <= sf_ent;
            unlit_q[out_q[1:0]] <= sf_unlit;
            k_q[out_q[1:0]] <= sf_k;
            eta_q[out_q[1:0]] <= sf_eta;
            kd_q[out_q[1:0]] <= sf_kd;
            kr_q[out_q[1:0]] <= sf_kr;
            kt_q[out_q[1:0]] <= sf_kt;
            ks_q[out_q[1:0]] <= sf_ks;
            base_q[out_q[1:0]] <= sf_base;
            emis_q[out_q[1:0]] <= sf_emis;
            tint_q[out_q[1:0]] <= sf_tint;
            dif_q[out_q[1:0]] <= {3{sf_unlit ? Q_ONE : Q_AMBIENT}};
            hil_q[out_q[1:0]] <= '0;
            out_q <= out_q + 3'd1;
            if (out_q == 3'd3) begin
              light_q <= '0;
              st <= S_LIGHT;
            end
          end
        end
        S_LIGHT:
          if (light_q >= n_lights_q) begin
            in_q <= '0;
            out_q <= '0;
            ract_q <= '0;
            tact_q <= '0;
            for (int i = 0; i < 4; i++) begin
              ro_q[i] <= '0;
              rdir_q[i] <= '0;
              to_q[i] <= '0;
              tdir_q[i] <= '0;
              rw_q[i] <= '0;
              tw_q[i] <= '0;
            end
            st <= S_ACCUM;
          end else if (lrec_ok_q && lrec_at_q == light_q) begin  // held (a scene of one light: always)
            in_q <= '0;
            out_q <= '0;
            colour_done_q <= 1'b0;
            st <= S_LCALC;
          end else st <= S_LREC;  // its record (light_read)
        S_LREC:
          if (burst_done) begin
            for (int k = 0; k < 13; k++) lrec_q[k] <= buf_q[k];
            lrec_at_q <= light_q;
            lrec_ok_q <= 1'b1;
            in_q <= '0;
            out_q <= '0;
            colour_done_q <= 1'b0;
            st <= S_LCALC;
          end
        S_LCALC: begin
          if (in_q < 3'd4 && li_ready) in_q <= in_q + 3'd1;
          if (lc_valid) begin
            colour_q <= lc_q;
            colour_done_q <= 1'b1;
          end
          if (li_valid) begin
            sho_q[li_tid] <= li_o;
            shd_q[li_tid] <= li_d;
            shmin_q[li_tid] <= li_tmin;
            shmax_q[li_tid] <= li_tmax;
            shact_q[li_tid] <= li_active;
            diff_q[li_tid] <= li_diff;
            spec_q[li_tid] <= li_spec;
            out_q <= out_q + 3'd1;
          end
          if (out_q == 3'd4 && colour_done_q) begin
            visible_q <= shact_q;
            in_q <= '0;
            out_q <= '0;
            st <= shadows_i && shact_q != '0 ? S_STRACE : S_ADD;
          end
        end
        S_STRACE:
          if (tr_ready_i) st <= S_SHITS;
        S_SHITS:
          if (hit_valid_i) begin
            for (int i = 0; i < 4; i++)
              if (hit_inst_i[32*i +: 32] != NO_HIT) visible_q[i] <= 1'b0;
            st <= S_ADD;
          end
        S_ADD: begin  // a visible ray a cycle; rgs_add_light's sum of the last comes as in_q reaches 4
          if (in_q < 3'd4) in_q <= in_q + 3'd1;
          if (al_valid) begin
            dif_q[al_tid] <= al_dif;
            hil_q[al_tid] <= al_hil;
          end
          if (in_q == 3'd4) begin
            light_q <= light_q + 32'd1;
            st <= S_LIGHT;
          end
        end
        S_ACCUM: begin
          if (in_q < 3'd4 && (!cact_q[in_q[1:0]] || ac_ready)) in_q <= in_q + 3'd1;
          if (ac_valid) begin
            acc_q[ac_tid] <= ac_acc;
            ro_q[ac_tid] <= ac_ro;
            rdir_q[ac_tid] <= ac_rd;
            rw_q[ac_tid] <= ac_rw;
            ract_q[ac_tid] <= ac_ract;
            to_q[ac_tid] <= ac_to;
            tdir_q[ac_tid] <= ac_td;
            tw_q[ac_tid] <= ac_tw;
            tact_q[ac_tid] <= ac_tact;
            out_q <= out_q + 3'd1;
          end
          if (in_q == 3'd4 && out_q == {2'd0, cact_q[0]} + {2'd0, cact_q[1]} + {2'd0, cact_q[2]} + {2'd0, cact_q[3]}) begin
            // push the transmission task, then the reflection task (popped first)
            if (tact_q != '0 && sp_q < SPW'(STACK)) begin
              for (int i = 0; i < 4; i++) begin
                so_q[sp_q][i] <= to_q[i];
                sd_q[sp_q][i] <= tdir_q[i];
                sw_q[sp_q][i] <= tw_q[i];
              end
              sact_q[sp_q] <= tact_q;
              sdep_q[sp_q] <= depth1[3:0];
            end
            in_q <= '0;
            st <= S_NEXT;
            sp_q <= sp_q + SPW'(tact_q != '0 && sp_q < SPW'(STACK));
            if (ract_q != '0) st <= S_PUSH_R;
          end
        end
        S_PUSH_R: begin
          if (sp_q < SPW'(STACK)) begin
            for (int i = 0; i < 4; i++) begin
              so_q[sp_q][i] <= ro_q[i];
              sd_q[sp_q][i] <= rdir_q[i];
              sw_q[sp_q][i] <= rw_q[i];
            end
            sact_q[sp_q] <= ract_q;
            sdep_q[sp_q] <= depth1[3:0];
            sp_q <= sp_q + SPW'(1);
          end
          st <= S_NEXT;
        end
        S_DONE:
          if (px_ready_i) st <= S_IDLE;
        default: st <= S_IDLE;
      endcase
    end
  end
endmodule
