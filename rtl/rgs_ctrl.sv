// rgs_ctrl: the RGS's per-block control (paper sections 2.2 and 3, Figure 2: the RGS's thread of a
// 2x2 pixel block; hls/units/rgs.c `rgs_step`, `rgs_block_finish`), bit for bit as
// `rgs_render_block`. The datapaths are not here: every step hands its rays to the RGS's one set of
// shared units (`rgs_units`: `rgs_raygen`, one of its SURF_UNITS `rgs_surface`s, `rgs_light`,
// `rgs_light_colour`, `rgs_add_light`, `rgs_accum`; an operand offered until taken, req/ack, each
// result back with the ray's index), which also did the frame set-up once after reset (the header's constants, the
// camera, e: frame_ok_i and the constants in).
//   RB_GEN   a block (x0, y0) in: its corner to `rgs_raygen`, its primary packet back, pushed
//            with weights one
//   RB_NEXT  pop the ray-tree stack (RGS_STACK = MAX_DEPTH + 2 tasks: rays, Q12 weights, depth),
//            unless it is empty or RGS_MAX_PACKETS packets were started: then RB_DONE (a task pushed
//            last is popped at once: it goes from the children's registers to the current packet's;
//            the stack's top was read into them while rgs_accum computed the last ray)
//   RB_TRACE the packet out on the trace port (tmin 0, tmax +Inf, TRACE_* flags of the profile),
//            its hits back; the first packet's hits are the block's primary hits
//   RB_SURFACES  the 4 rays and hits to `rgs_surface`, their surfaces back: exponents, diffuse
//            sums at the ambient 0.15 (one for unlit), highlights zero
//   RB_LIGHT per light: its 16 words read (4 or 5 lines, this controller's line port), `rgs_light`
//            on the 4 surfaces, `rgs_light_colour`; RB_SHADOW_TRACE with shadows and an active
//            shadow ray: the shadow packet traced (TRACE_ANY_HIT under PROFILE_ANY_HIT), light
//            reaching the rays without a hit; `rgs_add_light` adds it to the visible rays
//   RB_ACCUM `rgs_accum` for each active ray (pixel sums, children while the depth + 1 is at most
//            max_depth_i and MAX_DEPTH and the profile has secondary rays); the transmission task,
//            then the reflection task pushed if they have an active ray (dropped on a full stack; the
//            transmission task under a reflection task written into the stack memory a word a cycle
//            while the next packet is traced and shaded)
//   RB_DONE  the pixels (per channel min(255, (acc 255 + 2048) >> 12), 0xRRGGBB) and the primary
//            hits out
// The configuration is the general design (hls/config.h: shadows, secondary rays, refraction,
// textures) with the traversal unit's stack algorithm (flags bits 4..6 zero).
// BLOCKS = 1: one block at a time. The ray-tree stack's rays (RGS_STACK tasks of 4 x (6 W + 48)
// bits, 768 at e7m16) are in a memory with a registered read (thread_ram: block RAM), a task at
// CH = 24 words of 32 bits; only the transmission task pushed under a reflection task is written
// (the task pushed last is the next one and goes straight to the packet's registers), and the top
// is read a word a cycle into the packet's registers while rgs_accum computes the packet's last
// ray (CH + 1 cycles within its 68: no cycle added; LIGHT waits for a write still under way, which
// the trace and the surfaces of the packet between outlast). The rest of the block's state (the
// current packet, the children being formed, its hits, surfaces, sums and shadow packet, the tasks'
// active bits and depths) is in registers. The tag given with the block
// goes out with its trace requests and its pixels (the top routes the hits back by it).
// Latency: a sequence per block, its phases one after another, the 4 rays streamed through each
// phase's shared unit: about 20 + `rgs_surface` (the 4 rays offered as it takes them: its steps per
// hit, the last frame's 118 overlapped by none) + per light (`rgs_light` 87 + 4, after its 16
// words' 4 or 5 lines unless the record held is that light's: one light is read once) + 4
// `rgs_add_light` + 4 + `rgs_accum` 68 cycles per packet, each unit's result a cycle later for
// its arbiter's register in rgs_units (the ADD state waits for its sums since then), plus the
// trace, plus the cycles its operands wait for other controllers' in the shared units; the bench
// measures it alone (cornell 32x24: 488 cycles a block before the arbiters' registers, per state
// with tb_rgs_ctrl). Throughput: one block per its latency.
// Resources: the stack's rays in STACK x CH words of 32 bits (2 SB_RAM40_4K, 1 RAMB18), the block's
// registers (the surfaces 1,868 bits, the children 1,544, the hits 1,280, the shadow packet about
// 1,000, the current packet 776, the sums 576 at e7m16), a `line_reader` of 16 words (the light
// record), the operand multiplexers (the ray in_q of the packet into each unit's operand).
// Yosys 0.23 per module (python3 scripts/synth.py --ice40 rgs_ctrl, 2026-11-30): 7,502 SB_LUT4,
// 8,110 flip-flops, 2 SB_RAM40_4K, 12 SB_MAC16 (21,057 and 15,774 with the stack in registers);
// synth_xilinx (--levels rgs_ctrl --hier) 6,054 LUT6, 8,111 FF, 1 RAMB18, 5 LUT6 levels.
module rgs_ctrl #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TAG_BITS = 6,
  parameter int MAX_DEPTH = 8,    // RGS_MAX_DEPTH (SAARCOR_CFG_MAX_DEPTH)
  parameter int LW = 4,           // words per line of the read port (the shading cache's 16 bytes)
  localparam int W = 1 + E + M,
  localparam int V = 3 * W,
  localparam int SF_DW = 67 + 2 * V + 4 * W,  // rgs_units' operand layouts
  localparam int SR_DW = 205 + 3 * V + 2 * W,  // rgs_units' surface result
  localparam int LI_DW = 40 + 5 * V + 2 * W,
  localparam int AL_DW = 178,
  localparam int AC_DW = 393 + 3 * V + 2 * W
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic [3:0]               max_depth_i,  // rgs_config: secondary levels, shadow rays
  input  logic                     shadows_i,
  // the frame's constants (rgs_units' set-up), valid from frame_ok_i on
  input  logic                     frame_ok_i,
  input  logic [31:0]              n_lights_i,
  input  logic [31:0]              light_base_i,
  /* verilator lint_off UNUSEDSIGNAL */
  input  logic [4:0]               profile_i,     // bit 3 (live children) is rgs_accum's, in rgs_units
  /* verilator lint_on UNUSEDSIGNAL */
  // the shared units (rgs_units): per unit an operand out (req until ack; layouts in rgs_units)
  // and this controller's results back (valid)
  output logic                     gen_req_o,     // rgs_raygen: the block's corner {y0, x0}
  input  logic                     gen_ack_i,
  output logic [63:0]              gen_data_o,
  input  logic                     gen_valid_i,
  input  logic [3:0]               gen_active_i,
  input  logic [4*V-1:0]           gen_o_i,
  input  logic [4*V-1:0]           gen_d_i,
  output logic                     sf_req_o,      // rgs_surface: a ray and its hit
  input  logic                     sf_ack_i,
  output logic [SF_DW-1:0]         sf_data_o,
  input  logic                     sf_valid_i,
  input  logic [SR_DW-1:0]         sf_res_i,      // {ray, sf_valid, P, D^, N^, t_hat, entering, unlit, k, eta,
                                                  //  kd, kr, kt, ks, base, emission, tint}
  output logic                     li_req_o,      // rgs_light: a ray's surface and the light
  input  logic                     li_ack_i,
  output logic [LI_DW-1:0]         li_data_o,
  input  logic                     li_valid_i,
  input  logic [1:0]               li_ray_i,
  input  logic [V-1:0]             li_o_i,
  input  logic [V-1:0]             li_d_i,
  input  logic [W-1:0]             li_tmin_i,
  input  logic [W-1:0]             li_tmax_i,
  input  logic                     li_active_i,
  input  logic [15:0]              li_diff_i,
  input  logic [15:0]              li_spec_i,
  output logic                     lc_req_o,      // rgs_light_colour: the light's colour
  input  logic                     lc_ack_i,
  output logic [V-1:0]             lc_data_o,
  input  logic                     lc_valid_i,
  input  logic [47:0]              lc_q_i,
  output logic                     al_req_o,      // rgs_add_light: a visible ray's sums
  input  logic                     al_ack_i,
  output logic [AL_DW-1:0]         al_data_o,
  input  logic                     al_valid_i,
  input  logic [1:0]               al_ray_i,
  input  logic [47:0]              al_dif_i,
  input  logic [47:0]              al_hil_i,
  output logic                     ac_req_o,      // rgs_accum: an active ray
  input  logic                     ac_ack_i,
  output logic [AC_DW-1:0]         ac_data_o,
  input  logic                     ac_valid_i,
  input  logic [1:0]               ac_ray_i,
  input  logic [47:0]              ac_acc_i,
  input  logic [V-1:0]             ac_ro_i,
  input  logic [V-1:0]             ac_rd_i,
  input  logic [47:0]              ac_rw_i,
  input  logic                     ac_ract_i,
  input  logic [V-1:0]             ac_to_i,
  input  logic [V-1:0]             ac_td_i,
  input  logic [47:0]              ac_tw_i,
  input  logic                     ac_tact_i,
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
  localparam int STACK = MAX_DEPTH + 2;
  localparam int SPW = $clog2(STACK + 1);
  localparam int MAX_PACKETS = (1 << (MAX_DEPTH + 1)) - 1;
  localparam int PW = MAX_DEPTH + 2;
  localparam logic [W-1:0] POS_INF = {1'b0, {E{1'b1}}, {M{1'b0}}};
  localparam logic [31:0] NO_HIT = 32'hFFFFFFFF;
  localparam logic [15:0] Q_ONE = 16'd4096, Q_AMBIENT = 16'd614;
  localparam int LREC_WORDS = 16;  // a light's record
  // a task's 4 rays (o, d, Q12 weights) in the stack memory: CH words of CW bits (a block RAM's 32-bit
  // words: 2 SB_RAM40_4K or 1 RAMB18 hold the STACK x CH = 240 words at e7m16)
  localparam int RB = 2 * V + 48;
  localparam int CW = 32;
  localparam int CH = (4 * RB + CW - 1) / CW;
  localparam int TBP = CH * CW;
  localparam int SAW = $clog2(STACK * CH);
  localparam int CHW = $clog2(CH + 2);

  typedef enum logic [4:0] {
    S_IDLE, S_GEN, S_NEXT, S_TRACE, S_HITS, S_SURF, S_LIGHT, S_LREC, S_LCALC, S_STRACE, S_SHITS, S_ADD, S_ACCUM,
    S_DONE
  } state_t;
  state_t st;

  // ---- reads of the control: a light's record, a burst of 16 words (line_reader) ----
  logic [31:0] buf_q [LREC_WORDS];
  logic [32*LREC_WORDS-1:0] rd_words;
  logic burst_done, rd_start;
  // a burst starts in the cycle its address is known: a light's record unless it is the one held
  assign rd_start = st == S_LIGHT && light_q < n_lights_i && !(lrec_ok_q && lrec_at_q == light_q);
  line_reader #(.MAXW(LREC_WORDS), .LW(LW)) u_rd (
    .clk_i, .rst_ni, .start_i(rd_start), .addr_i(light_base_i + 32'd16 * light_q), .n_i(5'(LREC_WORDS)),
    .req_valid_o(mem_req_valid_o), .req_ready_i(mem_req_ready_i), .req_addr_o(mem_addr_o),
    .rsp_valid_i(mem_rsp_valid_i), .rsp_line_i(mem_rdata_i), .done_o(burst_done), .words_o(rd_words));
  for (genvar k = 0; k < LREC_WORDS; k++) begin : g_buf
    assign buf_q[k] = rd_words[32*k +: 32];
  end

  // ---- the frame's profile ----
  logic [2:0] flags_prim, flags_shadow;
  assign flags_prim = {profile_i[0] && profile_i[4], 1'b0, profile_i[0]};
  assign flags_shadow = {profile_i[0] && profile_i[4], profile_i[1], profile_i[0]};

  // ---- the block's state ----
  logic [TAG_BITS-1:0] tag_q;
  logic [31:0] bx_q, by_q;  // the block's corner until rgs_raygen takes it
  logic gen_sent_q;
  // the ray-tree stack: the tasks' rays in u_stack (a task at CH words from CH * its slot), their
  // active bits and depths here
  logic [3:0] sact_q [STACK], sdep_q [STACK];
  logic [SPW-1:0] sp_q;
  logic [PW-1:0] packets_q;
  logic nxt_q;                        // the next task is a child (or the primary packet) in cur_q, not the stack's top
  logic [TBP-1:0] cur_q;              // the current packet's rays (task layout); the stack's top fetched into it
  logic [V-1:0] co_q [4], cd_q [4];   // its fields
  logic [47:0] cw_q [4];
  logic [3:0] cact_q, cdep_q;
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
  logic colour_done_q, colour_sent_q;
  // the children being formed
  logic [V-1:0] ro_q [4], rdir_q [4], to_q [4], tdir_q [4];
  logic [47:0] rw_q [4], tw_q [4];
  logic [3:0] ract_q, tact_q;
  logic [2:0] in_q, out_q;  // rays issued to and collected from the unit of the current step
  logic [1:0] ri;
  assign ri = in_q[1:0];    // the ray offered to the unit of the current step

  // ---- the tasks' rays: ray i at bits RB i as {w, d, o} ----
  logic [TBP-1:0] gen_task, refl_task, trans_task;
  logic [4*RB-1:0] gen_rays, refl_rays, trans_rays;
  for (genvar i = 0; i < 4; i++) begin : g_task
    assign gen_rays[RB*i +: RB] = {{3{Q_ONE}}, gen_d_i[V*i +: V], gen_o_i[V*i +: V]};
    assign refl_rays[RB*i +: RB] = {rw_q[i], rdir_q[i], ro_q[i]};
    assign trans_rays[RB*i +: RB] = {tw_q[i], tdir_q[i], to_q[i]};
    assign co_q[i] = cur_q[RB*i +: V];
    assign cd_q[i] = cur_q[RB*i + V +: V];
    assign cw_q[i] = cur_q[RB*i + 2*V +: 48];
  end
  assign gen_task = TBP'(gen_rays);
  assign refl_task = TBP'(refl_rays);
  assign trans_task = TBP'(trans_rays);

  // ---- the stack memory: a task written a word a cycle (the transmission task pushed under the
  // reflection task, from its children's registers while the next packet is traced and shaded) and
  // the top read into cur_q a word a cycle while rgs_accum computes the packet's last ray (cur_q's
  // rays are then no longer offered): when no child is the next task, the top is there ----
  logic wr_q;                      // the transmission task is being written, word wc_q, into slot wslot_q
  logic [CHW-1:0] wc_q, pc_q;      // pc_q: the top's words asked for (CH + 1: all in cur_q)
  logic [SPW-1:0] wslot_q;
  logic [CW-1:0] trans_words [CH];
  logic [CW-1:0] top_word;
  logic fetch;
  logic [SAW-1:0] waddr, raddr;
  logic [SPW-1:0] top;             // the stack's top slot
  assign top = sp_q - SPW'(1);
  for (genvar c = 0; c < CH; c++) begin : g_words
    assign trans_words[c] = trans_task[CW*c +: CW];
  end
  assign fetch = st == S_ACCUM && in_q == 3'd4 && sp_q != '0 && pc_q <= CHW'(CH);
  assign waddr = SAW'(wslot_q) * SAW'(CH) + SAW'(wc_q);
  assign raddr = SAW'(top) * SAW'(CH) + SAW'(pc_q);
  thread_ram #(.W(CW), .DEPTH(STACK * CH)) u_stack (
    .clk_i, .we_i(wr_q), .waddr_i(waddr), .wdata_i(trans_words[wc_q]),
    .re_i(fetch && pc_q < CHW'(CH)), .raddr_i(raddr), .rdata_o(top_word));

  // ---- the shared units' operands (rgs_units), each held until taken ----
  assign gen_req_o = st == S_GEN && !gen_sent_q;
  assign gen_data_o = {by_q, bx_q};

  // the surfaces: the 4 rays and their hits out, a surface back
  logic [1:0] sf_ray;
  logic sf_sfv, sf_ent, sf_unlit;
  logic [V-1:0] sf_p, sf_d, sf_n;
  logic [W-1:0] sf_that, sf_eta;
  logic [3:0] sf_k;
  logic [12:0] sf_kd, sf_kr, sf_kt, sf_ks;
  logic [47:0] sf_base, sf_emis, sf_tint;
  assign {sf_ray, sf_sfv, sf_p, sf_d, sf_n, sf_that, sf_ent, sf_unlit, sf_k, sf_eta, sf_kd, sf_kr, sf_kt, sf_ks,
          sf_base, sf_emis, sf_tint} = sf_res_i;
  assign sf_req_o = st == S_SURF && in_q < 3'd4;
  assign sf_data_o = {ri, cact_q[ri], co_q[ri], cd_q[ri], hinst_q[ri], htri_q[ri], ht_q[ri], hu_q[ri], hv_q[ri],
                      hcos_q[ri]};

  // a light: the 4 surfaces streamed through rgs_light, its colour beside (once)
  assign li_req_o = st == S_LCALC && in_q < 3'd4;
  assign li_data_o = {ri, lrec_q[0], lrec_q[6][W-1:0], lrec_q[5][W-1:0], lrec_q[4][W-1:0], lrec_q[9][W-1:0],
                      lrec_q[8][W-1:0], lrec_q[7][W-1:0], lrec_q[11][W-1:0], lrec_q[12][W-1:0], sfv_q[ri],
                      unlit_q[ri], sp_p_q[ri], sf_n_q[ri], sf_d_q[ri], k_q[ri]};
  assign lc_req_o = st == S_LCALC && !colour_sent_q;
  assign lc_data_o = {lrec_q[3][W-1:0], lrec_q[2][W-1:0], lrec_q[1][W-1:0]};

  // the visible rays' sums, one ray at a time
  assign al_req_o = st == S_ADD && in_q < 3'd4 && visible_q[ri];
  assign al_data_o = {ri, dif_q[ri], hil_q[ri], diff_q[ri], spec_q[ri], colour_q};

  // the accumulation of the active rays, streamed
  logic children_on;
  logic [4:0] depth1;
  assign depth1 = {1'b0, cdep_q} + 5'd1;
  assign children_on = depth1 <= {1'b0, max_depth_i} && depth1 <= 5'(MAX_DEPTH) && !profile_i[2];
  assign ac_req_o = st == S_ACCUM && in_q < 3'd4 && cact_q[ri];
  // the children's tasks pushed at the packet's end (each dropped on a full stack)
  logic push_t, push_r;
  assign push_t = tact_q != '0 && sp_q < SPW'(STACK);
  assign push_r = ract_q != '0 && sp_q + SPW'(push_t) < SPW'(STACK);
  assign ac_data_o = {ri, eta_q[ri], kd_q[ri], kr_q[ri], kt_q[ri], ks_q[ri], sfv_q[ri], co_q[ri], sf_d_q[ri],
                      sf_n_q[ri], that_q[ri], ent_q[ri], base_q[ri], emis_q[ri], tint_q[ri], cw_q[ri], dif_q[ri],
                      hil_q[ri], acc_q[ri], children_on};

  // ---- outputs ----
  assign blk_ready_o = st == S_IDLE && frame_ok_i;
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
      st <= S_IDLE;
      lrec_ok_q <= 1'b0;
      wr_q <= 1'b0;
    end else begin
      if (wr_q) begin
        wc_q <= wc_q + CHW'(1);
        if (wc_q == CHW'(CH - 1)) wr_q <= 1'b0;
      end
      unique case (st)
        S_IDLE:
          if (blk_valid_i && frame_ok_i) begin
            tag_q <= blk_tag_i;
            bx_q <= blk_x_i;
            by_q <= blk_y_i;
            gen_sent_q <= 1'b0;
            st <= S_GEN;
          end
        S_GEN: begin  // the corner to rgs_raygen (gen_req_o), its packet back
          if (gen_ack_i) gen_sent_q <= 1'b1;
          if (gen_valid_i) begin  // the primary packet, with weights one, is the next task
            for (int i = 0; i < 4; i++) acc_q[i] <= '0;
            cur_q <= gen_task;
            cact_q <= gen_active_i;
            cdep_q <= '0;
            nxt_q <= 1'b1;
            sp_q <= '0;
            packets_q <= '0;
            st <= S_NEXT;
          end
        end
        S_NEXT:  // the next task: a child or the primary packet in cur_q, else the top popped (its rays in cur_q)
          if ((!nxt_q && sp_q == '0) || packets_q >= PW'(MAX_PACKETS)) st <= S_DONE;
          else begin
            if (!nxt_q) begin
              cact_q <= sact_q[top];
              cdep_q <= sdep_q[top];
              sp_q <= top;
            end
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
          if (sf_ack_i) in_q <= in_q + 3'd1;  // the next ray while the last is shaded
          if (sf_valid_i) begin
            sfv_q[sf_ray] <= sf_sfv;
            sp_p_q[sf_ray] <= sf_p;
            sf_d_q[sf_ray] <= sf_d;
            sf_n_q[sf_ray] <= sf_n;
            that_q[sf_ray] <= sf_that;
            ent_q[sf_ray] <= sf_ent;
            unlit_q[sf_ray] <= sf_unlit;
            k_q[sf_ray] <= sf_k;
            eta_q[sf_ray] <= sf_eta;
            kd_q[sf_ray] <= sf_kd;
            kr_q[sf_ray] <= sf_kr;
            kt_q[sf_ray] <= sf_kt;
            ks_q[sf_ray] <= sf_ks;
            base_q[sf_ray] <= sf_base;
            emis_q[sf_ray] <= sf_emis;
            tint_q[sf_ray] <= sf_tint;
            dif_q[sf_ray] <= {3{sf_unlit ? Q_ONE : Q_AMBIENT}};
            hil_q[sf_ray] <= '0;
            out_q <= out_q + 3'd1;
            if (out_q == 3'd3) begin
              light_q <= '0;
              st <= S_LIGHT;
            end
          end
        end
        S_LIGHT:
          if (light_q >= n_lights_i) begin
            if (!wr_q) begin  // the children's registers free: a transmission task pushed is in the stack memory
              pc_q <= '0;
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
            end
          end else if (lrec_ok_q && lrec_at_q == light_q) begin  // held (a scene of one light: always)
            in_q <= '0;
            out_q <= '0;
            colour_done_q <= 1'b0;
            colour_sent_q <= 1'b0;
            st <= S_LCALC;
          end else st <= S_LREC;  // its record (rd_start)
        S_LREC:
          if (burst_done) begin
            for (int k = 0; k < 13; k++) lrec_q[k] <= buf_q[k];
            lrec_at_q <= light_q;
            lrec_ok_q <= 1'b1;
            in_q <= '0;
            out_q <= '0;
            colour_done_q <= 1'b0;
            colour_sent_q <= 1'b0;
            st <= S_LCALC;
          end
        S_LCALC: begin
          if (li_ack_i) in_q <= in_q + 3'd1;
          if (lc_ack_i) colour_sent_q <= 1'b1;
          if (lc_valid_i) begin
            colour_q <= lc_q_i;
            colour_done_q <= 1'b1;
          end
          if (li_valid_i) begin
            sho_q[li_ray_i] <= li_o_i;
            shd_q[li_ray_i] <= li_d_i;
            shmin_q[li_ray_i] <= li_tmin_i;
            shmax_q[li_ray_i] <= li_tmax_i;
            shact_q[li_ray_i] <= li_active_i;
            diff_q[li_ray_i] <= li_diff_i;
            spec_q[li_ray_i] <= li_spec_i;
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
        S_ADD: begin  // the visible rays as rgs_add_light takes them, until their sums are back (the
          // last one's 2 cycles after its ack: the arbiter's register and the unit's)
          if (in_q < 3'd4 && (!visible_q[ri] || al_ack_i)) in_q <= in_q + 3'd1;
          if (al_valid_i) begin
            dif_q[al_ray_i] <= al_dif_i;
            hil_q[al_ray_i] <= al_hil_i;
            out_q <= out_q + 3'd1;
          end
          if (in_q == 3'd4 && out_q == {2'd0, visible_q[0]} + {2'd0, visible_q[1]} + {2'd0, visible_q[2]} +
                                       {2'd0, visible_q[3]}) begin
            light_q <= light_q + 32'd1;
            st <= S_LIGHT;
          end
        end
        S_ACCUM: begin
          if (in_q < 3'd4 && (!cact_q[ri] || ac_ack_i)) in_q <= in_q + 3'd1;
          if (ac_valid_i) begin
            acc_q[ac_ray_i] <= ac_acc_i;
            ro_q[ac_ray_i] <= ac_ro_i;
            rdir_q[ac_ray_i] <= ac_rd_i;
            rw_q[ac_ray_i] <= ac_rw_i;
            ract_q[ac_ray_i] <= ac_ract_i;
            to_q[ac_ray_i] <= ac_to_i;
            tdir_q[ac_ray_i] <= ac_td_i;
            tw_q[ac_ray_i] <= ac_tw_i;
            tact_q[ac_ray_i] <= ac_tact_i;
            out_q <= out_q + 3'd1;
          end
          if (pc_q != '0 && pc_q <= CHW'(CH))  // the top's word asked for in the last cycle
            for (int c = 0; c < CH; c++)
              if (pc_q == CHW'(c + 1)) cur_q[CW*c +: CW] <= top_word;
          if (fetch) pc_q <= pc_q + CHW'(1);
          if (in_q == 3'd4 && out_q == {2'd0, cact_q[0]} + {2'd0, cact_q[1]} + {2'd0, cact_q[2]} + {2'd0, cact_q[3]} &&
              (sp_q == '0 || pc_q == CHW'(CH + 1))) begin
            // the transmission task pushed, then the reflection task: the top, so the next task is the
            // reflection task (a transmission task pushed under it goes into the stack memory), else the
            // transmission task, else the stack's top (in cur_q)
            nxt_q <= push_t || push_r;
            if (push_t || push_r) begin
              cur_q <= push_r ? refl_task : trans_task;
              cact_q <= push_r ? ract_q : tact_q;
              cdep_q <= depth1[3:0];
            end
            if (push_t && push_r) begin
              sact_q[sp_q] <= tact_q;
              sdep_q[sp_q] <= depth1[3:0];
              wslot_q <= sp_q;
              wc_q <= '0;
              wr_q <= 1'b1;
              sp_q <= sp_q + SPW'(1);
            end
            in_q <= '0;
            st <= S_NEXT;
          end
        end
        S_DONE:
          if (px_ready_i) st <= S_IDLE;
        default: st <= S_IDLE;
      endcase
    end
  end
endmodule
