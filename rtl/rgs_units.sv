// rgs_units: the RGS's shared datapaths (paper section 3, Figure 2: ONE ray generation and shading
// unit serving the RGS's threads; hls/units/rgs.c `rgs_block_begin`, `rgs_step`): the frame set-up,
// one each of rgs_raygen, rgs_light, rgs_light_colour, rgs_add_light and rgs_accum, and SURF_UNITS
// rgs_surface for the N block controllers (rgs_ctrl) of the DynRTP. The controllers keep their FSM
// and block state (stack, packet, surfaces, sums) and hand their operands here; per unit an rgs_arb
// picks one controller's operand a cycle round robin, the controller's index travels as the high
// bits of the unit's thread id (beside the ray's index in the packet), and the result comes back to
// that controller only (valid_o bit k). A controller waits in the state of its step for all its
// results and takes each as it comes (the units run with ready_i = 1), so sharing changes when an
// operand enters a unit, never what it computes.
//   frame set-up  once after reset (the C's `rgs_block_begin` constants; each rgs_ctrl did it for
//            itself before): the header's texture and light counts (at most 64 lights), the scene
//            bounds and the region starts (words 9..34), the camera block (loaded into rgs_raygen,
//            its profile word kept); e = max of the bounds' extents / 2^10 (the C's f24_sub,
//            f24_max from 0 and f24_div on one f24_add, f24_cmp, f24_div); then frame_ok_o and the
//            constants held (the light count and records' start, the profile out to the
//            controllers; the other regions' starts and the texture count for the surfaces)
//   gen      a controller's block corner (x0, y0) into rgs_raygen; the packets come out in the
//            order of the blocks, so a FIFO of the controllers' indices (one block per controller
//            at most) routes them back
//   surface  a ray and its hit into rgs_surface s = k mod SURF_UNITS (controller k's), which takes
//            the next ray (any of its controllers') while it reads and shades the ones before and
//            gives the surfaces back in order, on its result bus (sf_res_o at SR_DW s) to its
//            controllers. Not one surface for all: one takes a hit every 40 to 80 cycles (its
//            front's dependent bursts, its back one surface at a time) and bounded 8 controllers
//            (f876e73: cornell 32x24 T8 +14%); its arbiter HOLDs the grant on a controller while
//            it offers its packet's rays, so one controller's 4 surfaces are done before the next
//            one's (round robin would finish both late). Each surface has a line read port
//            (mem_*[s]); port 0 is the set-up's until frame_ok_o, then surface 0's
//   frame    the geometry of a surface unit's hit (d^, n^, t_hat, P: rgs_surface's fr_ ports) into
//            rgs_frame f = s mod FRAME_UNITS (one by default: a frame takes a ray a cycle, a surface
//            unit issues one every 40 to 80 cycles) through an rgs_arb, the unit's index as the
//            frame's thread id; the results come back in order, each to its unit, which takes it
//            as its surface leaves (a result waits at the frame's output, stalling the frame, until
//            its unit takes it: none is lost)
//   normal   the vertex normal of a surface unit's hit (its record's 3 codes, u, v: rgs_surface's nrm_
//            ports) into one `rgs_normal` through an rgs_arb (a unit asks every 40 to 80 cycles, the
//            decoder takes a hit every 3), the unit's index as its thread id; the results come out in
//            order, each into its unit's queue of 2, which has room: a unit asks only then, from
//            registers, and the acknowledge only clears its request (8 LUT6 levels; since
//            2026-11-30; one per surface unit before)
//   texture  the texel coordinates of a surface unit's texture sample (s, t, the entry's width,
//            height, address: rgs_surface's tx_ ports) into one `tex_coords` through an rgs_arb (a
//            unit asks once per texture of a textured hit, it takes a sample a cycle), the unit's
//            index as its thread id; the results (the texel rows' addresses, the columns, the
//            fractions) come out in order, each into its unit's `tex_fetch`, which reads the texels
//            on the unit's line port and blends them: a unit has one sample under way and waits for
//            it, so it takes the result as it comes. Asked from registers, the acknowledge only
//            clearing the request (8 LUT6 levels; since 2026-11-30; a whole bilinear sample,
//            `tex_bilinear`, per surface unit before)
//   light    `rgs_light` on a ray's surface and the controller's light record; `rgs_light_colour`
//            on the light's colour; `rgs_add_light` on a visible ray's sums; `rgs_accum` on an
//            active ray (e and the profile's live bit from the set-up, spawn from the controller)
// Operand layouts (each controller packs its operand in this order, the highest field first):
//   gen {y0, x0}; surface {ray, active, o, d, inst, tri, t, u, v, cos_n}; light {ray, type, L_pos,
//   L_dir, cos_in, cos_out, sf_valid, unlit, P, N^, D^, k}; colour {B, G, R}; add {ray, diffuse,
//   highlight, diff, spec, colour}; accum {ray, eta, kd, kr, kt, ks, sf_valid, o, D^, N^, t_hat,
//   entering, base, emission, tint, weight, diffuse, highlight, acc, spawn}. The surface's result
//   {ray, sf_valid, P, D^, N^, t_hat, entering, unlit, k, eta, kd, kr, kt, ks, base, emission,
//   tint} (SR_DW bits).
// Latency: 1 (the unit's rgs_arb registers the operand) + the units' own (rgs_raygen 30,
// rgs_surface 216 for a packet's first hit with the frame's arbiter register + about 39 a further hit, rgs_light 87,
// rgs_light_colour 27, rgs_add_light 1, rgs_accum 68 cycles) plus the cycles an operand waits for
// other controllers' in the same unit (a surface's front takes a hit after the reads of the one
// before); the set-up about 60 cycles after reset plus its reads (the header's 26 words, the
// camera's 16: 7 + 4 or 5 lines). The registers in the arbiters, f24_from_i32's third segment,
// rgs_accum's operand and rgs_surface's vertex colours keep every path between registers at 8
// LUT6 levels or fewer (synth_xilinx; rtl/README.md "LUT6 levels of the RGS").
// Throughput: per unit one operand per cycle (II = 1) but a surface (a hit per its front's reads:
// SURF_UNITS hits at once) and rgs_raygen (a packet per 4 cycles).
// Resources: one rgs_raygen, rgs_normal (DEPTH 2 SURF_UNITS rounded up to a power of 2) behind an
// rgs_arb of SURF_UNITS requesters (126 + 2 W bits), tex_coords (15,416 SB_LUT4, its two tex_axis nearly all)
// behind one of SURF_UNITS (96 + 2 W bits), rgs_light, rgs_light_colour, rgs_add_light, rgs_accum; SURF_UNITS
// rgs_surface (17,735 SB_LUT4 each with its tex_fetch, rtl/README.md "One tex_coords for the four
// surface units"; about 55,000 LUT6 each with its frame, normal and sample before 2026-11-30); FRAME_UNITS rgs_frame (21,431 LUT6 each), each behind an rgs_arb of
// ceil(SURF_UNITS / FRAME_UNITS) requesters (3 V + 11 W bits, the frame using 3 V + 10 W + 1); 5 rgs_arb of N requesters
// (N-to-1 multiplexers of 64, 448, 72, 178 and 657 bits at e7m16 into as many flip-flops, N of the
// pointer each: 4,407 LUT6 at N = 8 before the output registers) and SURF_UNITS of ceil(N / SURF_UNITS) (307 bits); a FIFO of N controller indices; the set-up's
// line_reader (26 words), f24_add, f24_cmp, f24_div and the frame's constants (7 x 32 + 10 x W + 5
// bits).
module rgs_units #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int N = 8,            // block controllers (RGS_BLOCKS)
  parameter int CVT_STAGES = 3,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int SQRT_STAGES = 9,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2,
  parameter int TOI_STAGES = 2,
  parameter int MOD_STAGES = 16,
  parameter int SURF_UNITS = 4,   // rgs_surface units (1 .. N), unit s serving the controllers k = s mod SURF_UNITS
  parameter int SURF_SLOTS = 16,  // per rgs_surface: surfaces in its frame (its controllers' hits in flight)
  parameter int FRAME_UNITS = 1,  // rgs_frame units (1 .. SURF_UNITS), frame f serving surface units s = f mod F
  parameter int LW = 4,           // words per line of the read port (the shading cache's 16 bytes)
  localparam int NW = N > 1 ? $clog2(N) : 1,
  localparam int S = SURF_UNITS,
  localparam int F = FRAME_UNITS,
  localparam int W = 1 + E + M,
  localparam int V = 3 * W,
  localparam int GEN_DW = 64,
  localparam int SF_DW = 67 + 2 * V + 4 * W,
  localparam int SR_DW = 205 + 3 * V + 2 * W,
  localparam int LI_DW = 40 + 5 * V + 2 * W,
  localparam int LC_DW = V,
  localparam int AL_DW = 178,
  localparam int AC_DW = 393 + 3 * V + 2 * W
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  // S line read ports (port s at bit s, its address at bits 32 s), port s rgs_surface s's, port 0
  // the set-up's before: a request names a line by its first word's address, the answer is the
  // line's LW words, in order; the answers' line is common to the ports
  output logic [S-1:0]         mem_req_valid_o,
  input  logic [S-1:0]         mem_req_ready_i,
  output logic [S*32-1:0]      mem_addr_o,
  input  logic [S-1:0]         mem_rsp_valid_i,
  input  logic [32*LW-1:0]     mem_rdata_i,
  // the frame's constants the controllers need, valid from frame_ok_o on
  output logic                 frame_ok_o,
  output logic [31:0]          n_lights_o,
  output logic [31:0]          light_base_o,
  output logic [4:0]           profile_o,
  // primary packets: operand {y0, x0}
  input  logic [N-1:0]         gen_req_i,
  input  logic [N*GEN_DW-1:0]  gen_data_i,
  output logic [N-1:0]         gen_ack_o,
  output logic [N-1:0]         gen_valid_o,
  output logic [3:0]           gen_active_o,
  output logic [4*V-1:0]       gen_o_o,
  output logic [4*V-1:0]       gen_d_o,
  // a ray's surface at its hit (rgs_surface)
  input  logic [N-1:0]         sf_req_i,
  input  logic [N*SF_DW-1:0]   sf_data_i,
  output logic [N-1:0]         sf_ack_o,
  output logic [N-1:0]         sf_valid_o,
  output logic [S*SR_DW-1:0]   sf_res_o,    // rgs_surface s's result at bits SR_DW s (for controllers s mod S)
  // a light at a ray's surface (rgs_light)
  input  logic [N-1:0]         li_req_i,
  input  logic [N*LI_DW-1:0]   li_data_i,
  output logic [N-1:0]         li_ack_o,
  output logic [N-1:0]         li_valid_o,
  output logic [1:0]           li_ray_o,
  output logic [V-1:0]         li_o_o,
  output logic [V-1:0]         li_d_o,
  output logic [W-1:0]         li_tmin_o,
  output logic [W-1:0]         li_tmax_o,
  output logic                 li_active_o,
  output logic [15:0]          li_diff_o,
  output logic [15:0]          li_spec_o,
  // a light's colour (rgs_light_colour)
  input  logic [N-1:0]         lc_req_i,
  input  logic [N*LC_DW-1:0]   lc_data_i,
  output logic [N-1:0]         lc_ack_o,
  output logic [N-1:0]         lc_valid_o,
  output logic [47:0]          lc_q_o,
  // a visible ray's sums (rgs_add_light)
  input  logic [N-1:0]         al_req_i,
  input  logic [N*AL_DW-1:0]   al_data_i,
  output logic [N-1:0]         al_ack_o,
  output logic [N-1:0]         al_valid_o,
  output logic [1:0]           al_ray_o,
  output logic [47:0]          al_dif_o,
  output logic [47:0]          al_hil_o,
  // an active ray's accumulation and children (rgs_accum)
  input  logic [N-1:0]         ac_req_i,
  input  logic [N*AC_DW-1:0]   ac_data_i,
  output logic [N-1:0]         ac_ack_o,
  output logic [N-1:0]         ac_valid_o,
  output logic [1:0]           ac_ray_o,
  output logic [47:0]          ac_acc_o,
  output logic [V-1:0]         ac_ro_o,
  output logic [V-1:0]         ac_rd_o,
  output logic [47:0]          ac_rw_o,
  output logic                 ac_ract_o,
  output logic [V-1:0]         ac_to_o,
  output logic [V-1:0]         ac_td_o,
  output logic [47:0]          ac_tw_o,
  output logic                 ac_tact_o
);
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [W-1:0] F1024 = {1'b0, E'(BIAS + 10), {M{1'b0}}};
  localparam int SETUP_AT = 9, SETUP_WORDS = 26;  // header words 9..34

  // ---- the frame set-up: header words 9..34, the camera block, e ----
  typedef enum logic [2:0] { F_RESET, F_SETUP, F_CAMERA, F_EXTENT, F_MAX, F_EPS, F_DONE } fstate_t;
  fstate_t fs;
  logic [31:0] buf_q [SETUP_WORDS], rd_at;
  logic [32*SETUP_WORDS-1:0] rd_words;
  logic burst_done, rd_start;
  logic [4:0] cam_q;  // the camera word into rgs_raygen next
  logic cam_valid;
  logic [2:0] in_q, out_q;
  logic [W-1:0] eps_q, ext_q [3], bnd_q [6];  // e; the extents, the scene bounds (lo, hi)
  logic [31:0] n_tex_q, inst_base_q, obj_base_q, mat_base_q, tex_base_q;  // rgs_surface's constants
  logic rd_req, sf_port;
  logic [31:0] rd_addr;
  logic [S-1:0] sf_req;
  logic [S*32-1:0] sf_addr;
  // a burst starts in the cycle its address is known: the header's words after reset, then the
  // camera block (its address among them)
  assign rd_start = fs == F_RESET || (fs == F_SETUP && burst_done);
  assign rd_at = fs == F_RESET ? 32'(SETUP_AT) : buf_q[18 + 2 * 6 - SETUP_AT];
  line_reader #(.MAXW(SETUP_WORDS), .LW(LW)) u_rd (
    .clk_i, .rst_ni, .start_i(rd_start), .addr_i(rd_at), .n_i(fs == F_RESET ? 5'(SETUP_WORDS) : 5'd16),
    .req_valid_o(rd_req), .req_ready_i(!sf_port && mem_req_ready_i[0]), .req_addr_o(rd_addr),
    .rsp_valid_i(!sf_port && mem_rsp_valid_i[0]), .rsp_line_i(mem_rdata_i), .done_o(burst_done), .words_o(rd_words));
  // port 0 is the set-up's until it is done, then rgs_surface 0's (no surface before a block)
  assign sf_port = fs == F_DONE;
  always_comb begin
    mem_req_valid_o = sf_req;
    mem_addr_o = sf_addr;
    if (!sf_port) begin
      mem_req_valid_o[0] = rd_req;
      mem_addr_o[31:0] = rd_addr;
    end
  end
  for (genvar k = 0; k < SETUP_WORDS; k++) begin : g_buf
    assign buf_q[k] = rd_words[32*k +: 32];
  end
  assign frame_ok_o = fs == F_DONE;

  /* verilator lint_off PINCONNECTEMPTY */
  // the extents (f24_sub), their maximum from 0 (f24_max), / 2^10
  logic ad_valid, cm_valid, dv_valid;
  logic [W-1:0] ad_r, cm_max, dv_r;
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_sub (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(fs == F_EXTENT && in_q < 3'd3), .a_i(bnd_q[3 + in_q]), .b_i(bnd_q[in_q]),
    .sub_i(1'b1), .valid_o(ad_valid), .res_o(ad_r));
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_max (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(fs == F_MAX && in_q == out_q), .a_i(eps_q), .b_i(ext_q[out_q[1:0]]), .valid_o(cm_valid), .flags_o(),
    .min_o(), .max_o(cm_max));
  f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_div (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(fs == F_EPS && in_q == 3'd0), .a_i(eps_q), .b_i(F1024), .valid_o(dv_valid), .res_o(dv_r));

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) fs <= F_RESET;
    else begin
      if (cam_valid) cam_q <= cam_q + 5'd1;
      unique case (fs)
        F_RESET: fs <= F_SETUP;  // the header's words (rd_start)
        F_SETUP:  // words 9..34: buf_q[w - 9]
          if (burst_done) begin
            n_tex_q <= buf_q[0];
            n_lights_o <= buf_q[1] < 32'd64 ? buf_q[1] : 32'd64;
            mat_base_q <= buf_q[18 + 2 * 1 - SETUP_AT];
            tex_base_q <= buf_q[18 + 2 * 2 - SETUP_AT];
            obj_base_q <= buf_q[18 + 2 * 5 - SETUP_AT];
            light_base_o <= buf_q[18 + 2 * 7 - SETUP_AT];
            inst_base_q <= buf_q[18 + 2 * 8 - SETUP_AT];
            cam_q <= '0;  // the camera's words (rd_start)
            for (int k = 0; k < 6; k++) bnd_q[k] <= buf_q[12 + k - SETUP_AT][W-1:0];
            fs <= F_CAMERA;
          end
        F_CAMERA:  // into rgs_raygen once read; the profile is word 3
          if (burst_done && cam_q == 5'd16) begin
            profile_o <= buf_q[3][4:0];
            in_q <= '0;
            out_q <= '0;
            fs <= F_EXTENT;
          end
        F_EXTENT: begin
          if (in_q < 3'd3) in_q <= in_q + 3'd1;
          if (ad_valid) begin
            ext_q[out_q[1:0]] <= ad_r;
            out_q <= out_q + 3'd1;
            if (out_q == 3'd2) begin
              eps_q <= '0;
              in_q <= '0;
              out_q <= '0;
              fs <= F_MAX;
            end
          end
        end
        F_MAX: begin
          if (in_q == out_q) in_q <= in_q + 3'd1;
          if (cm_valid) begin
            eps_q <= cm_max;
            out_q <= out_q + 3'd1;
            if (out_q == 3'd2) begin
              in_q <= '0;
              fs <= F_EPS;
            end
          end
        end
        F_EPS: begin
          if (in_q == 3'd0) in_q <= 3'd1;
          if (dv_valid) begin
            eps_q <= dv_r;
            fs <= F_DONE;
          end
        end
        default: fs <= F_DONE;
      endcase
    end
  end

  // ---- primary packets: the blocks' corners round robin into rgs_raygen, the packets back in order ----
  logic gen_valid, rg_blk_ready, rg_valid, who_ready, who_valid;
  logic [NW-1:0] gen_idx, who;
  logic [GEN_DW-1:0] gen_op;
  assign cam_valid = fs == F_CAMERA && burst_done && cam_q < 5'd16;  // from the burst's words, one a cycle
  rgs_arb #(.N(N), .DW(GEN_DW)) u_gen_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(gen_req_i), .data_i(gen_data_i),
    .ack_o(gen_ack_o), .valid_o(gen_valid), .ready_i(rg_blk_ready && who_ready), .index_o(gen_idx), .data_o(gen_op));
  rgs_raygen #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .MUL_STAGES(MUL_STAGES), .CVT_STAGES(CVT_STAGES)) u_gen (
    .clk_i(clk_i), .rst_ni(rst_ni), .cam_valid_i(cam_valid), .cam_ready_o(), .cam_idx_i(cam_q[3:0]),
    .cam_word_i(buf_q[cam_q]), .blk_valid_i(gen_valid && who_ready), .blk_ready_o(rg_blk_ready),
    .blk_x_i(gen_op[31:0]), .blk_y_i(gen_op[63:32]), .pkt_valid_o(rg_valid), .pkt_ready_i(1'b1),
    .pkt_active_o(gen_active_o), .pkt_o_o(gen_o_o), .pkt_d_o(gen_d_o), .pkt_tmin_o(), .pkt_tmax_o());
  // whose block is in rgs_raygen, oldest first (a controller waits for its packet: N entries suffice)
  sync_fifo #(.W(NW), .DEPTH(N > 2 ? 1 << $clog2(N) : 2)) u_who (.clk_i(clk_i), .rst_ni(rst_ni),
    .valid_i(gen_valid && rg_blk_ready), .ready_o(who_ready), .data_i(gen_idx), .valid_o(who_valid),
    .ready_i(rg_valid), .data_o(who));

  // ---- the frames: F rgs_frame, frame f taking the geometry of the surface units s = f mod F round
  // robin (the unit's index in the frame as its thread id) and handing each result to that unit.
  // A unit's results come in the order of its operands (the frame is one in-order pipeline); a
  // result waits at the frame's output (stalling it) until its unit takes it, which it does as the
  // surface's other fields reach its queue's head (rgs_surface, not waiting on the frame for that) ----
  localparam int SF = (S + F - 1) / F;  // surface units per frame, at most
  localparam int SFW = SF > 1 ? $clog2(SF) : 1;
  localparam int FR_DW = 3 * V + 11 * W;  // {o, d, t, cos_n, n, w2o}
  if (F < 1 || F > S) begin : g_fr_check
    $error("rgs_units: FRAME_UNITS 1 .. SURF_UNITS");
  end
  logic [S-1:0] fr_req, fr_ack, fr_out, fr_take;
  logic [S*FR_DW-1:0] fr_ops;
  logic [F-1:0] fr_ent;
  logic [V-1:0] fr_dh [F], fr_nh [F], fr_p [F];
  logic [W-1:0] fr_that [F];
  for (genvar f = 0; f < F; f++) begin : g_fr
    logic [SF-1:0] req, takes;
    /* verilator lint_off UNUSEDSIGNAL */
    logic [SF-1:0] ack;  // a missing unit's (S not a multiple of F) is never set
    /* verilator lint_on UNUSEDSIGNAL */
    logic [SF*FR_DW-1:0] ops;
    for (genvar j = 0; j < SF; j++) begin : g_in  // surface unit j F + f, if there is one
      if (j*F + f < S) begin : g_s
        assign req[j] = fr_req[j*F + f];
        assign ops[j*FR_DW +: FR_DW] = fr_ops[(j*F + f)*FR_DW +: FR_DW];
        assign takes[j] = fr_take[j*F + f];
        assign fr_ack[j*F + f] = ack[j];
      end else begin : g_none
        assign req[j] = 1'b0;
        assign ops[j*FR_DW +: FR_DW] = '0;
        assign takes[j] = 1'b0;
      end
    end
    logic op_valid, en, out;
    logic [SFW-1:0] idx, owner;
    logic [FR_DW-1:0] op;
    rgs_arb #(.N(SF), .DW(FR_DW)) u_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(req), .data_i(ops), .ack_o(ack),
      .valid_o(op_valid), .ready_i(en), .index_o(idx), .data_o(op));
    rgs_frame #(.E(E), .M(M), .TID_BITS(SFW), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
      .SQRT_STAGES(SQRT_STAGES), .DIV_STAGES(DIV_STAGES)) u_frame (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(op_valid),
      .ready_o(en), .tid_i(idx), .o_i(op[2*V + 11*W +: V]), .d_i(op[V + 11*W +: V]), .t_i(op[V + 10*W +: W]),
      .cos_n_i(op[V + 9*W +: W]), .n_i(op[9*W +: V]), .w2o_i(op[0 +: 9*W]), .valid_o(out), .ready_i(takes[owner]),
      .tid_o(owner), .d_o(fr_dh[f]), .n_o(fr_nh[f]), .entering_o(fr_ent[f]), .t_hat_o(fr_that[f]), .p_o(fr_p[f]));
    for (genvar j = 0; j < SF; j++) begin : g_out
      if (j*F + f < S) begin : g_s
        assign fr_out[j*F + f] = out && owner == SFW'(j);
      end
    end
  end

  // ---- the vertex normals: one rgs_normal taking the surface units' hits round robin (the unit's
  // index as its thread id), each result to that unit's queue (which has room: rgs_surface asks only
  // then); 2 under way per unit at most, so 2 S inside keep every unit's going ----
  localparam int SW = S > 1 ? $clog2(S) : 1;
  localparam int NV_DW = 126 + 2 * W;  // {codes, v, u}
  logic [S-1:0] nv_req, nv_ack;
  logic [S*NV_DW-1:0] nv_ops;
  logic nv_valid, nv_ready, nv_out, nv_zero;
  logic [SW-1:0] nv_idx, nv_who;
  logic [NV_DW-1:0] nv_op;
  logic [V-1:0] nv_n;
  rgs_arb #(.N(S), .DW(NV_DW)) u_nrm_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(nv_req), .data_i(nv_ops),
    .ack_o(nv_ack), .valid_o(nv_valid), .ready_i(nv_ready), .index_o(nv_idx), .data_o(nv_op));
  rgs_normal #(.E(E), .M(M), .CVT_STAGES(CVT_STAGES), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
    .SQRT_STAGES(SQRT_STAGES), .DIV_STAGES(DIV_STAGES), .TID_BITS(SW), .DEPTH(1 << $clog2(2 * S))) u_nrm (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(nv_valid), .ready_o(nv_ready), .tid_i(nv_idx),
    .codes_i(nv_op[2*W +: 126]), .u_i(nv_op[0 +: W]), .v_i(nv_op[W +: W]), .valid_o(nv_out), .tid_o(nv_who),
    .n_o(nv_n), .zero_o(nv_zero));

  // ---- the texture samples' coordinates: one tex_coords taking the surface units' samples round
  // robin (the unit's index as its thread id), each result to that unit's tex_fetch (which takes it:
  // a unit has one sample under way and waits for it, so the unit never stalls) ----
  localparam int TX_DW = 2 * W + 96;  // {s, t, width, height, addr}
  logic [S-1:0] tx_req, tx_ack;
  logic [S*TX_DW-1:0] tx_ops;
  logic tx_valid, tx_ready, tx_out;
  logic [SW-1:0] tx_idx, tx_who;
  logic [TX_DW-1:0] tx_op;
  logic [31:0] tx_row0, tx_row1, tx_x0, tx_x1;
  logic [8:0] tx_fx, tx_fy;
  rgs_arb #(.N(S), .DW(TX_DW)) u_tex_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(tx_req), .data_i(tx_ops),
    .ack_o(tx_ack), .valid_o(tx_valid), .ready_i(tx_ready), .index_o(tx_idx), .data_o(tx_op));
  tex_coords #(.E(E), .M(M), .TID_BITS(SW), .CVT_STAGES(CVT_STAGES), .MUL_STAGES(MUL_STAGES),
    .ADD_STAGES(ADD_STAGES), .CMP_STAGES(CMP_STAGES), .TOI_STAGES(TOI_STAGES), .MOD_STAGES(MOD_STAGES)) u_tex (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(tx_valid), .ready_o(tx_ready), .tid_i(tx_idx),
    .s_i(tx_op[W + 96 +: W]), .t_i(tx_op[96 +: W]), .width_i(tx_op[64 +: 32]), .height_i(tx_op[32 +: 32]),
    .addr_i(tx_op[0 +: 32]), .valid_o(tx_out), .ready_i(1'b1), .tid_o(tx_who), .row0_o(tx_row0), .row1_o(tx_row1),
    .x0_o(tx_x0), .x1_o(tx_x1), .fx_o(tx_fx), .fy_o(tx_fy));

  // ---- the surfaces: S rgs_surface units, unit s taking the rays and hits of the controllers k = s
  // mod S round robin; each takes the next ray while it reads and shades the ones before (several
  // controllers' rays in flight, in order) and gives a surface back to the controller in its id ----
  localparam int NS = (N + S - 1) / S;  // controllers per surface unit, at most
  localparam int NSW = NS > 1 ? $clog2(NS) : 1;
  if (S < 1 || S > N) begin : g_check
    $error("rgs_units: SURF_UNITS 1 .. N");
  end
  logic [S-1:0] sf_out;
  logic [NW-1:0] sf_who [S];
  for (genvar s = 0; s < S; s++) begin : g_sf
    logic [NS-1:0] req;
    /* verilator lint_off UNUSEDSIGNAL */
    logic [NS-1:0] ack;  // a missing controller's (N not a multiple of S) is never set
    /* verilator lint_on UNUSEDSIGNAL */
    logic [NS*SF_DW-1:0] ops;
    for (genvar j = 0; j < NS; j++) begin : g_in  // controller j S + s, if there is one
      if (j*S + s < N) begin : g_k
        assign req[j] = sf_req_i[j*S + s];
        assign ops[j*SF_DW +: SF_DW] = sf_data_i[(j*S + s)*SF_DW +: SF_DW];
        assign sf_ack_o[j*S + s] = ack[j];
      end else begin : g_none
        assign req[j] = 1'b0;
        assign ops[j*SF_DW +: SF_DW] = '0;
      end
    end
    logic op_valid, take;
    logic [NSW-1:0] idx;
    logic [NW-1:0] owner;
    logic [SF_DW-1:0] op;
    /* verilator lint_off UNUSEDSIGNAL */
    logic [31:0] mat;  // the accumulation takes the material's fields from the surface
    /* verilator lint_on UNUSEDSIGNAL */
    logic [1:0] ray;
    logic sfv, ent, unlit;
    logic [V-1:0] p, d, n;
    logic [W-1:0] that, eta;
    logic [3:0] kexp;
    logic [12:0] kd, kr, kt, ks;
    logic [47:0] base, emis, tint;
    rgs_arb #(.N(NS), .DW(SF_DW), .HOLD(1'b1)) u_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(req), .data_i(ops),
      .ack_o(ack), .valid_o(op_valid), .ready_i(take), .index_o(idx), .data_o(op));
    assign owner = NW'(32'(idx) * S + s);
    // the operand from the top: ray, active, o, d, inst, tri, t, u, v, cos_n
    rgs_surface #(.E(E), .M(M), .TID_BITS(NW + 2), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
      .TOI_STAGES(TOI_STAGES), .SLOTS(SURF_SLOTS), .LW(LW)) u_surface (
      .clk_i(clk_i), .rst_ni(rst_ni), .inst_base_i(inst_base_q), .obj_base_i(obj_base_q), .mat_base_i(mat_base_q),
      .tex_base_i(tex_base_q), .n_tex_i(n_tex_q), .valid_i(op_valid), .ready_o(take),
      .tid_i({owner, op[SF_DW-1 -: 2]}), .active_i(op[SF_DW-3]), .o_i(op[SF_DW-4 -: V]),
      .d_i(op[SF_DW-4-V -: V]), .inst_i(op[4*W + 32 +: 32]), .tri_i(op[4*W +: 32]), .t_i(op[3*W +: W]),
      .u_i(op[2*W +: W]), .v_i(op[W +: W]), .cos_n_i(op[0 +: W]), .fr_valid_o(fr_req[s]), .fr_ready_i(fr_ack[s]),
      .fr_o_o(fr_ops[s*FR_DW + 2*V + 11*W +: V]), .fr_d_o(fr_ops[s*FR_DW + V + 11*W +: V]),
      .fr_t_o(fr_ops[s*FR_DW + V + 10*W +: W]), .fr_cos_n_o(fr_ops[s*FR_DW + V + 9*W +: W]),
      .fr_n_o(fr_ops[s*FR_DW + 9*W +: V]), .fr_w2o_o(fr_ops[s*FR_DW +: 9*W]), .fr_valid_i(fr_out[s]),
      .fr_ready_o(fr_take[s]), .fr_d_i(fr_dh[s % F]), .fr_n_i(fr_nh[s % F]), .fr_entering_i(fr_ent[s % F]),
      .fr_t_hat_i(fr_that[s % F]), .fr_p_i(fr_p[s % F]), .nrm_valid_o(nv_req[s]), .nrm_ready_i(nv_ack[s]),
      .nrm_codes_o(nv_ops[s*NV_DW + 2*W +: 126]), .nrm_u_o(nv_ops[s*NV_DW +: W]), .nrm_v_o(nv_ops[s*NV_DW + W +: W]),
      .nrm_valid_i(nv_out && nv_who == SW'(s)), .nrm_n_i(nv_n), .nrm_zero_i(nv_zero), .tx_valid_o(tx_req[s]),
      .tx_ready_i(tx_ack[s]), .tx_s_o(tx_ops[s*TX_DW + W + 96 +: W]), .tx_t_o(tx_ops[s*TX_DW + 96 +: W]),
      .tx_width_o(tx_ops[s*TX_DW + 64 +: 32]), .tx_height_o(tx_ops[s*TX_DW + 32 +: 32]),
      .tx_addr_o(tx_ops[s*TX_DW +: 32]), .tx_valid_i(tx_out && tx_who == SW'(s)), .tx_row0_i(tx_row0),
      .tx_row1_i(tx_row1), .tx_x0_i(tx_x0), .tx_x1_i(tx_x1), .tx_fx_i(tx_fx), .tx_fy_i(tx_fy),
      .mem_req_valid_o(sf_req[s]),
      .mem_req_ready_i((s != 0 || sf_port) && mem_req_ready_i[s]), .mem_addr_o(sf_addr[s*32 +: 32]),
      .mem_rsp_valid_i((s != 0 || sf_port) && mem_rsp_valid_i[s]), .mem_rdata_i(mem_rdata_i), .valid_o(sf_out[s]),
      .ready_i(1'b1), .tid_o({sf_who[s], ray}), .sf_valid_o(sfv), .p_o(p), .d_o(d), .n_o(n), .t_hat_o(that),
      .entering_o(ent), .mat_o(mat), .unlit_o(unlit), .k_o(kexp), .eta_o(eta), .kd_o(kd), .kr_o(kr), .kt_o(kt),
      .ks_o(ks), .base_o(base), .emission_o(emis), .tint_o(tint));
    assign sf_res_o[s*SR_DW +: SR_DW] = {ray, sfv, p, d, n, that, ent, unlit, kexp, eta, kd, kr, kt, ks, base, emis,
                                         tint};
  end

  // ---- a light at the rays' surfaces, its colour, the visible rays' sums, the accumulation ----
  logic li_in, lc_in, al_in, ac_in;
  logic [NW-1:0] li_idx, lc_idx, al_idx, ac_idx, li_who, lc_who, al_who, ac_who;
  logic [LI_DW-1:0] li_op;
  logic [LC_DW-1:0] lc_op;
  logic [AL_DW-1:0] al_op;
  logic [AC_DW-1:0] ac_op;
  logic li_out, lc_out, al_out, ac_out;
  rgs_arb #(.N(N), .DW(LI_DW)) u_li_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(li_req_i), .data_i(li_data_i),
    .ack_o(li_ack_o), .valid_o(li_in), .ready_i(1'b1), .index_o(li_idx), .data_o(li_op));
  rgs_light #(.E(E), .M(M), .TID_BITS(NW + 2), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
    .SQRT_STAGES(SQRT_STAGES), .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES), .TOI_STAGES(TOI_STAGES)) u_light (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(li_in), .ready_o(), .tid_i({li_idx, li_op[LI_DW-1 -: 2]}),
    .type_i(li_op[LI_DW-3 -: 32]), .lpos_i(li_op[LI_DW-35 -: V]), .ldir_i(li_op[LI_DW-35-V -: V]),
    .cos_in_i(li_op[LI_DW-35-2*V -: W]), .cos_out_i(li_op[LI_DW-35-2*V-W -: W]), .eps_i(eps_q),
    .sf_valid_i(li_op[4 + 3*V + 1]), .unlit_i(li_op[4 + 3*V]), .p_i(li_op[4 + 2*V +: V]), .n_i(li_op[4 + V +: V]),
    .d_i(li_op[4 +: V]), .k_i(li_op[3:0]), .valid_o(li_out), .ready_i(1'b1), .tid_o({li_who, li_ray_o}),
    .o_o(li_o_o), .d_o(li_d_o), .tmin_o(li_tmin_o), .tmax_o(li_tmax_o), .active_o(li_active_o), .diff_o(li_diff_o),
    .spec_o(li_spec_o));

  rgs_arb #(.N(N), .DW(LC_DW)) u_lc_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(lc_req_i), .data_i(lc_data_i),
    .ack_o(lc_ack_o), .valid_o(lc_in), .ready_i(1'b1), .index_o(lc_idx), .data_o(lc_op));
  rgs_light_colour #(.E(E), .M(M), .TID_BITS(NW), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
    .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES), .TOI_STAGES(TOI_STAGES)) u_colour (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(lc_in), .ready_o(), .tid_i(lc_idx), .colour_i(lc_op),
    .valid_o(lc_out), .ready_i(1'b1), .tid_o(lc_who), .q_o(lc_q_o));

  rgs_arb #(.N(N), .DW(AL_DW)) u_al_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(al_req_i), .data_i(al_data_i),
    .ack_o(al_ack_o), .valid_o(al_in), .ready_i(1'b1), .index_o(al_idx), .data_o(al_op));
  rgs_add_light #(.TID_BITS(NW + 2)) u_add (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(al_in), .ready_o(),
    .tid_i({al_idx, al_op[177:176]}), .diffuse_i(al_op[175:128]), .highlight_i(al_op[127:80]),
    .diff_i(al_op[79:64]), .spec_i(al_op[63:48]), .colour_i(al_op[47:0]), .valid_o(al_out), .ready_i(1'b1),
    .tid_o({al_who, al_ray_o}), .diffuse_o(al_dif_o), .highlight_o(al_hil_o));

  // the accumulation's operand from the top: ray, eta, the 4 shader fields, sf_valid, o, D^, N^,
  // t_hat, entering, then 7 sums of 48 bits and the spawn bit
  localparam int AC_S = 1 + 7 * 48;  // the sums and spawn, at the bottom
  rgs_arb #(.N(N), .DW(AC_DW)) u_ac_arb (.clk_i(clk_i), .rst_ni(rst_ni), .req_i(ac_req_i), .data_i(ac_data_i),
    .ack_o(ac_ack_o), .valid_o(ac_in), .ready_i(1'b1), .index_o(ac_idx), .data_o(ac_op));
  rgs_accum #(.E(E), .M(M), .TID_BITS(NW + 2), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
    .SQRT_STAGES(SQRT_STAGES), .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES)) u_accum (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(ac_in), .ready_o(), .tid_i({ac_idx, ac_op[AC_DW-1 -: 2]}),
    .eta_i(ac_op[AC_DW-3 -: W]), .kd_i(ac_op[AC_DW-3-W -: 13]), .kr_i(ac_op[AC_DW-16-W -: 13]),
    .kt_i(ac_op[AC_DW-29-W -: 13]), .ks_i(ac_op[AC_DW-42-W -: 13]), .sf_valid_i(ac_op[AC_DW-55-W]),
    .o_i(ac_op[AC_S + W + 1 + 2*V +: V]), .d_i(ac_op[AC_S + W + 1 + V +: V]), .n_i(ac_op[AC_S + W + 1 +: V]),
    .t_hat_i(ac_op[AC_S + 1 +: W]), .entering_i(ac_op[AC_S]), .base_i(ac_op[1 + 6*48 +: 48]),
    .emission_i(ac_op[1 + 5*48 +: 48]), .tint_i(ac_op[1 + 4*48 +: 48]), .weight_i(ac_op[1 + 3*48 +: 48]),
    .diffuse_i(ac_op[1 + 2*48 +: 48]), .highlight_i(ac_op[1 + 48 +: 48]), .acc_i(ac_op[1 +: 48]), .eps_i(eps_q),
    .spawn_i(ac_op[0]), .live_i(profile_o[3]), .valid_o(ac_out), .ready_i(1'b1), .tid_o({ac_who, ac_ray_o}),
    .acc_o(ac_acc_o), .r_o_o(ac_ro_o), .r_d_o(ac_rd_o), .r_w_o(ac_rw_o), .r_active_o(ac_ract_o), .t_o_o(ac_to_o),
    .t_d_o(ac_td_o), .t_w_o(ac_tw_o), .t_active_o(ac_tact_o), .steps_o());
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- each result to the controller whose index it carries ----
  for (genvar k = 0; k < N; k++) begin : g_back
    assign gen_valid_o[k] = rg_valid && who_valid && who == NW'(k);
    assign sf_valid_o[k] = sf_out[k % S] && sf_who[k % S] == NW'(k);
    assign li_valid_o[k] = li_out && li_who == NW'(k);
    assign lc_valid_o[k] = lc_out && lc_who == NW'(k);
    assign al_valid_o[k] = al_out && al_who == NW'(k);
    assign ac_valid_o[k] = ac_out && ac_who == NW'(k);
  end
endmodule
