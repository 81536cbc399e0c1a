// dynrtp: one DynRTP (paper section 3, Figure 2): the tile controller (tile_ctrl) deals the
// frame's 2x2 blocks to the RGS, RGS_BLOCKS block controllers (rgs_ctrl: the control of ray
// generation, surfaces, lights and shadow rays, accumulation and secondary rays of hls/units/rgs.c
// rgs_step / rgs_block_finish) around one set of shared datapaths (rgs_units: the frame set-up of
// rgs_block_begin, rgs_raygen, SURF_UNITS rgs_surface, rgs_light, rgs_light_colour, rgs_add_light, rgs_accum,
// each taking the controllers' operands round robin), whose packets the ray tracing core (trace_core:
// THREADS threads, the traversal, list, rebase, transformation and intersection units,
// thread_sched) traces, and the memory side: the core's three ports read through the paper's
// direct-mapped caches (cache_read around cache_dm, the cycle model's default configuration
// tb/cycle/cycle_sim.c cycle_config_default: kd nodes NODE_KB KB in lines of one node (8 bytes),
// lists LIST_KB KB in lines of one entry (4 bytes), matrices MAT_KB KB in lines of one packed
// triangle record) and the RGS's reads (header, camera, instances, shading records,
// materials, lights, texels) through the shading cache (SHADE_KB KB in lines of 16 bytes, the
// cycle model's MEM_SHADING cache; a request names a line, its answer is the line's 4 words), all four on one memory port (mem_port) to an external memory
// with valid/ready and in-order answers.
// The RGS: one rgs_ctrl holds one block (its ray-tree stack in block RAM), so RGS_BLOCKS of them
// give RGS_BLOCKS blocks in flight, each with at most one packet in the core: rgs_ctrl k traces on
// the core's thread k (its tag), so the core's hits go back to the controller of thread_o. A block
// goes to the lowest idle controller below blocks_i (--threads-per-pipe: the blocks the harness
// lets run); the controllers' packets enter the core round robin (rr_pick), the controllers' light
// record reads and rgs_units' (the set-up's, then its surfaces', a port each) line reads are merged
// round robin by a second mem_port (N = RGS_BLOCKS + SURF_UNITS, the answers routed back in order) onto the shading
// cache, their pixels leave round robin on the px_* port with the block's corner. rgs_units reads
// the frame's header and camera once after reset; the controllers take blocks from then on.
// The core's packet input and its hits are also outputs (tr_*, valid_o ...) for the harness, which
// checks every packet against the C core.
// Where the memory interface differs from the cycle model (docs/cycle-model.md): the core's
// descriptor word port reads the header once per image (4 responses at e7m16; the cycle model:
// not at all) and a record in one or two responses of a matrix cache line's RW words each (a
// read across two lines takes two lookups; the cycle model looks the lines up at once); list_unit's entries wait in its queue for their list words, up to 9 reads in flight (the cycle
// model parks the thread before the unit, any number); every cache has OUTSTANDING reads in flight (the cycle model: no
// limit); the caches answer a hit after 2 cycles (3 with the matrix cache's index stage, the
// cycle model: at once); the RGS's reads are line by line, a burst's lines one a cycle on the
// controllers' one port (the cycle model: the same lines on its shading port).
// Counters (the usage counted inside the RTL): cycles_o counts the cycles from the frame taken at
// frame_valid_i until frame_done_o (the last block's pixels taken); issues_o per unit of
// trace_core the operations issued in that time (thread_sched: trav, list, rebase, wide, isect
// (isect_rebased: a triangle's transformation and test), add, 64 bits each); packets_o the packets traced; reads_o per cache the reads it
// took (kd nodes, list entries, descriptor responses of RW words, shading lines).
// Latency and throughput: tile_ctrl 1 block per cycle; rgs_ctrl a block per its sequence
// (rtl/README.md), RGS_BLOCKS at once; a packet from the controllers' pick into the core 1 cycle
// (a 2-entry queue: no combinational path from a controller's request to its ready); the core's;
// the memory port 1 transfer per cycle.
// Resources: trace_core's, rgs_units (one set of the RGS's datapaths, SURF_UNITS surfaces), RGS_BLOCKS x rgs_ctrl (the
// control, its block's state in registers and its stack's rays in 2 SB_RAM40_4K each), 4 x cache_read
// (NODE_KB + LIST_KB + MAT_KB + SHADE_KB KB of data arrays and their tags), 2 x mem_port,
// 2 x rr_pick, tile_ctrl, RGS_BLOCKS x 64 bits of block corners, 14 x 64-bit counters.
module dynrtp #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int THREADS = 32,
  parameter int RGS_BLOCKS = 8,     // block controllers (rgs_ctrl), at most THREADS
  parameter int SURF_UNITS = 4,     // rgs_surface units shared by the controllers (at most RGS_BLOCKS used)
  parameter int NODE_KB = 4,
  parameter int LIST_KB = 2,
  parameter int MAT_KB = 6,
  parameter int SHADE_KB = 4,
  parameter int OUTSTANDING = 16,   // reads in flight per cache
  localparam int W = 1 + E + M,
  localparam int TW = $clog2(THREADS),
  localparam int RW = (12 * W + 27 + 3 + 31) / 32,         // F24_TRIANGLE_RECORD_WORDS
  localparam int MAT_LINE = 4 * RW,                         // bytes: one packed triangle record
  localparam int DW = 8 * MAT_LINE                          // the widest line
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  input  logic                   flush_i,     // a new memory image: the caches are emptied
  // the frame (tile_ctrl) and the RGS's configuration (rgs_config)
  input  logic                   frame_valid_i,
  output logic                   frame_ready_o,
  input  logic [31:0]            x0_i,
  input  logic [31:0]            y0_i,
  input  logic [31:0]            x1_i,
  input  logic [31:0]            y1_i,
  input  logic [12:0]            tile_i,
  input  logic [3:0]             max_depth_i,
  input  logic                   shadows_i,
  input  logic [7:0]             blocks_i,    // blocks in flight: 1 .. RGS_BLOCKS
  output logic                   frame_done_o, // the frame's last block's pixels were taken
  // the blocks' pixels (0xRRGGBB of pixel i = (x + (i & 1), y + (i >> 1)) at bits 24 i) and
  // primary hits
  output logic                   px_valid_o,
  input  logic                   px_ready_i,
  output logic [31:0]            px_x_o,
  output logic [31:0]            px_y_o,
  output logic [4*24-1:0]        px_rgb_o,
  output logic [4*32-1:0]        px_inst_o,
  output logic [4*32-1:0]        px_tri_o,
  output logic [4*W-1:0]         px_t_o,
  output logic [4*W-1:0]         px_u_o,
  output logic [4*W-1:0]         px_v_o,
  output logic [4*W-1:0]         px_cos_o,
  // observed: the packets the core takes (trace_begin) on thread tr_thread_o
  output logic                   tr_valid_o,
  output logic [TW-1:0]          tr_thread_o,
  output logic [2:0]             tr_flags_o,
  output logic [3:0]             tr_active_o,
  output logic [4*3*W-1:0]       tr_o_o,
  output logic [4*3*W-1:0]       tr_d_o,
  output logic [4*W-1:0]         tr_tmin_o,
  output logic [4*W-1:0]         tr_tmax_o,
  // observed: the hits the core gives back (TP_DONE)
  output logic                   valid_o,
  output logic [TW-1:0]          thread_o,
  output logic [4*32-1:0]        inst_o,
  output logic [4*32-1:0]        tri_o,
  output logic [4*W-1:0]         t_o,
  output logic [4*W-1:0]         u_o,
  output logic [4*W-1:0]         v_o,
  output logic [4*W-1:0]         cos_o,
  output logic [10*32-1:0]       count_o,
  // the external memory: byte address and byte count, answers in request order
  output logic                   mem_req_valid_o,
  input  logic                   mem_req_ready_i,
  output logic [31:0]            mem_req_addr_o,
  output logic [7:0]             mem_req_bytes_o,
  output logic [1:0]             mem_req_src_o,  // 0 kd nodes, 1 lists, 2 matrices, 3 shading
  input  logic                   mem_rsp_valid_i,
  input  logic [DW-1:0]          mem_rsp_data_i,
  // counters
  output logic [63:0]            cycles_o,
  output logic [6*64-1:0]        issues_o,
  output logic [63:0]            packets_o,
  output logic [4*64-1:0]        reads_o
);
  localparam int B = RGS_BLOCKS;
  localparam int BW = B > 1 ? $clog2(B) : 1;
  if (B < 1 || B > THREADS) begin : g_check
    $error("dynrtp: RGS_BLOCKS 1 .. THREADS (one core thread per block controller)");
  end

  // ---- tile controller: a block to the lowest idle controller below blocks_i ----
  logic blk_valid, blk_ready, blk_done;
  logic [31:0] blk_x, blk_y;
  tile_ctrl u_tiles (
    .clk_i(clk_i), .rst_ni(rst_ni), .frame_valid_i(frame_valid_i), .frame_ready_o(frame_ready_o), .x0_i(x0_i),
    .y0_i(y0_i), .x1_i(x1_i), .y1_i(y1_i), .tile_i(tile_i), .blk_valid_o(blk_valid), .blk_ready_i(blk_ready),
    .blk_x_o(blk_x), .blk_y_o(blk_y), .done_o(blk_done));

  logic [B-1:0] rb_ready /*verilator public_flat_rd*/, free;
  logic [BW-1:0] dealt;
  always_comb begin
    dealt = '0;
    for (int k = B - 1; k >= 0; k--) begin
      free[k] = rb_ready[k] && 8'(k) < blocks_i;
      if (free[k]) dealt = BW'(k);
    end
  end
  assign blk_ready = |free;

  // ---- the RGS: RGS_BLOCKS block controllers around one set of shared units (rgs_units) ----
  logic [B-1:0] tr_ready, px_valid, px_ready;
  localparam int S = SURF_UNITS < B ? SURF_UNITS : B;  // a surface unit has a controller at least
  logic [B+S-1:0] rd_valid, rd_ready, rd_rsp;  // the controllers' read ports, then the set-up's
  // public_flat_rd (these, rb_ready, busy_q, the caches' ports): read by tb_dynrtp for --mode rtl --vcd
  logic [B-1:0] tr_valid /*verilator public_flat_rd*/, hit_ready /*verilator public_flat_rd*/;
  // per controller: unpacked arrays (Yosys 0.23 reads no packed arrays of more than one dimension)
  logic [TW-1:0] tr_tag [B], px_tag [B];
  logic [2:0] tr_flags [B];
  logic [3:0] tr_active [B];
  logic [4*3*W-1:0] tr_o [B], tr_d [B];
  logic [4*W-1:0] tr_tmin [B], tr_tmax [B], px_t [B], px_u [B], px_v [B], px_cos [B];
  logic [(B+S)*32-1:0] rd_addr;  // the read ports' mem_port takes the B + S addresses side by side
  logic [4*24-1:0] px_rgb [B];
  logic [4*32-1:0] px_inst [B], px_tri [B];
  logic [127:0] rd_line;  // the shading cache's line (4 words) to every controller
  logic [31:0] bx_q [THREADS], by_q [THREADS];  // the corner of thread k's block
  logic core_ready;
  // the shared units' ports: per controller k its operand at bits k x the operand's width, its
  // valid bit k; the results on one bus to all (rgs_units)
  localparam int V = 3 * W;
  localparam int SF_DW = 67 + 2 * V + 4 * W, SR_DW = 205 + 3 * V + 2 * W, LI_DW = 40 + 5 * V + 2 * W, AL_DW = 178, AC_DW = 393 + 3 * V + 2 * W;
  logic frame_ok;
  logic [31:0] n_lights, light_base;
  logic [4:0] profile;
  logic [B-1:0] gen_req, gen_ack, gen_valid, li_req, li_ack, li_valid, lc_req, lc_ack, lc_valid;
  logic [B-1:0] al_req, al_ack, al_valid, ac_req, ac_ack, ac_valid;
  logic [B*64-1:0] gen_data;
  logic [B*LI_DW-1:0] li_data;
  logic [B*V-1:0] lc_data;
  logic [B*AL_DW-1:0] al_data;
  logic [B*AC_DW-1:0] ac_data;
  logic [3:0] gen_active;
  logic [4*V-1:0] gen_o, gen_d;
  logic [1:0] li_ray, al_ray, ac_ray;
  logic [V-1:0] li_o, li_d, ac_ro, ac_rd, ac_to, ac_td;
  logic [W-1:0] li_tmin, li_tmax;
  logic [15:0] li_diff, li_spec;
  logic [47:0] lc_q, al_dif, al_hil, ac_acc, ac_rw, ac_tw;
  logic li_active, ac_ract, ac_tact;
  logic [B-1:0] sf_req, sf_ack, sf_valid;
  logic [B*SF_DW-1:0] sf_data;
  logic [S*SR_DW-1:0] sf_res;
  rgs_units #(.E(E), .M(M), .N(B), .SURF_UNITS(S)) u_units (
    .clk_i(clk_i), .rst_ni(rst_ni), .mem_req_valid_o(rd_valid[B +: S]), .mem_req_ready_i(rd_ready[B +: S]),
    .mem_addr_o(rd_addr[B*32 +: S*32]), .mem_rsp_valid_i(rd_rsp[B +: S]), .mem_rdata_i(rd_line), .frame_ok_o(frame_ok),
    .n_lights_o(n_lights), .light_base_o(light_base), .profile_o(profile),
    .sf_req_i(sf_req), .sf_data_i(sf_data), .sf_ack_o(sf_ack), .sf_valid_o(sf_valid), .sf_res_o(sf_res),
    .gen_req_i(gen_req), .gen_data_i(gen_data), .gen_ack_o(gen_ack), .gen_valid_o(gen_valid),
    .gen_active_o(gen_active), .gen_o_o(gen_o), .gen_d_o(gen_d),
    .li_req_i(li_req), .li_data_i(li_data), .li_ack_o(li_ack), .li_valid_o(li_valid), .li_ray_o(li_ray),
    .li_o_o(li_o), .li_d_o(li_d), .li_tmin_o(li_tmin), .li_tmax_o(li_tmax), .li_active_o(li_active),
    .li_diff_o(li_diff), .li_spec_o(li_spec),
    .lc_req_i(lc_req), .lc_data_i(lc_data), .lc_ack_o(lc_ack), .lc_valid_o(lc_valid), .lc_q_o(lc_q),
    .al_req_i(al_req), .al_data_i(al_data), .al_ack_o(al_ack), .al_valid_o(al_valid), .al_ray_o(al_ray),
    .al_dif_o(al_dif), .al_hil_o(al_hil),
    .ac_req_i(ac_req), .ac_data_i(ac_data), .ac_ack_o(ac_ack), .ac_valid_o(ac_valid), .ac_ray_o(ac_ray),
    .ac_acc_o(ac_acc), .ac_ro_o(ac_ro), .ac_rd_o(ac_rd), .ac_rw_o(ac_rw), .ac_ract_o(ac_ract), .ac_to_o(ac_to),
    .ac_td_o(ac_td), .ac_tw_o(ac_tw), .ac_tact_o(ac_tact));
  for (genvar k = 0; k < B; k++) begin : g_rgs
    rgs_ctrl #(.E(E), .M(M), .TAG_BITS(TW)) u_rgs (
      .clk_i(clk_i), .rst_ni(rst_ni), .max_depth_i(max_depth_i), .shadows_i(shadows_i),
      .frame_ok_i(frame_ok), .n_lights_i(n_lights), .light_base_i(light_base), .profile_i(profile),
      .sf_req_o(sf_req[k]), .sf_ack_i(sf_ack[k]), .sf_data_o(sf_data[k*SF_DW +: SF_DW]), .sf_valid_i(sf_valid[k]),
      .sf_res_i(sf_res[(k % S)*SR_DW +: SR_DW]),
      .gen_req_o(gen_req[k]), .gen_ack_i(gen_ack[k]), .gen_data_o(gen_data[k*64 +: 64]), .gen_valid_i(gen_valid[k]),
      .gen_active_i(gen_active), .gen_o_i(gen_o), .gen_d_i(gen_d),
      .li_req_o(li_req[k]), .li_ack_i(li_ack[k]), .li_data_o(li_data[k*LI_DW +: LI_DW]), .li_valid_i(li_valid[k]),
      .li_ray_i(li_ray), .li_o_i(li_o), .li_d_i(li_d), .li_tmin_i(li_tmin), .li_tmax_i(li_tmax),
      .li_active_i(li_active), .li_diff_i(li_diff), .li_spec_i(li_spec),
      .lc_req_o(lc_req[k]), .lc_ack_i(lc_ack[k]), .lc_data_o(lc_data[k*V +: V]), .lc_valid_i(lc_valid[k]),
      .lc_q_i(lc_q),
      .al_req_o(al_req[k]), .al_ack_i(al_ack[k]), .al_data_o(al_data[k*AL_DW +: AL_DW]), .al_valid_i(al_valid[k]),
      .al_ray_i(al_ray), .al_dif_i(al_dif), .al_hil_i(al_hil),
      .ac_req_o(ac_req[k]), .ac_ack_i(ac_ack[k]), .ac_data_o(ac_data[k*AC_DW +: AC_DW]), .ac_valid_i(ac_valid[k]),
      .ac_ray_i(ac_ray), .ac_acc_i(ac_acc), .ac_ro_i(ac_ro), .ac_rd_i(ac_rd), .ac_rw_i(ac_rw), .ac_ract_i(ac_ract),
      .ac_to_i(ac_to), .ac_td_i(ac_td), .ac_tw_i(ac_tw), .ac_tact_i(ac_tact),
      .blk_valid_i(blk_valid && free[k] && dealt == BW'(k)), .blk_ready_o(rb_ready[k]), .blk_tag_i(TW'(k)),
      .blk_x_i(blk_x), .blk_y_i(blk_y), .tr_valid_o(tr_valid[k]), .tr_ready_i(tr_ready[k]), .tr_tag_o(tr_tag[k]),
      .tr_flags_o(tr_flags[k]), .tr_active_o(tr_active[k]), .tr_o_o(tr_o[k]), .tr_d_o(tr_d[k]),
      .tr_tmin_o(tr_tmin[k]), .tr_tmax_o(tr_tmax[k]), .hit_valid_i(valid_o && thread_o == TW'(k)),
      .hit_ready_o(hit_ready[k]), .hit_inst_i(inst_o), .hit_tri_i(tri_o), .hit_t_i(t_o), .hit_u_i(u_o),
      .hit_v_i(v_o), .hit_cos_i(cos_o), .mem_req_valid_o(rd_valid[k]), .mem_req_ready_i(rd_ready[k]),
      .mem_addr_o(rd_addr[k*32 +: 32]), .mem_rsp_valid_i(rd_rsp[k]), .mem_rdata_i(rd_line), .px_valid_o(px_valid[k]),
      .px_ready_i(px_ready[k]), .px_tag_o(px_tag[k]), .px_rgb_o(px_rgb[k]), .px_inst_o(px_inst[k]),
      .px_tri_o(px_tri[k]), .px_t_o(px_t[k]), .px_u_o(px_u[k]), .px_v_o(px_v[k]), .px_cos_o(px_cos[k]));
  end
  always_ff @(posedge clk_i) begin
    if (blk_valid && blk_ready) begin
      bx_q[TW'(dealt)] <= blk_x;
      by_q[TW'(dealt)] <= blk_y;
    end
  end

  // the packets into the core, round robin, through a queue of 2 (LUT RAM): the controllers' ready
  // comes from its register, so no path runs from a controller's request through the pick and the
  // core's check that the packet's thread is free back into the controllers (17 LUT6 levels
  // before, `synth.py --dynrtp-path`); a packet enters the core a cycle later (the cycle model's
  // raygen, shadow and children latencies count it). The core's hits go back to the controller
  // of their thread.
  localparam int PKW = TW + 3 + 4 + 2 * 4 * 3 * W + 2 * 4 * W;
  logic [B-1:0] tr_after_q, tr_after, tr_grant, px_after_q, px_after, px_grant;
  logic [BW-1:0] tr_pick, px_pick;
  logic tr_any, px_any, pk_ready, pk_valid;
  logic [PKW-1:0] pk_head;
  rr_pick #(.N(B)) u_tr_pick (.req_i(tr_valid), .after_i(tr_after_q), .any_o(tr_any), .grant_o(tr_grant),
    .index_o(tr_pick), .after_o(tr_after));
  assign tr_ready = pk_ready ? tr_grant : '0;
  sync_fifo #(.W(PKW), .DEPTH(2)) u_tr_q (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(tr_any), .ready_o(pk_ready),
    .data_i({tr_tag[tr_pick], tr_flags[tr_pick], tr_active[tr_pick], tr_o[tr_pick], tr_d[tr_pick],
             tr_tmin[tr_pick], tr_tmax[tr_pick]}),
    .valid_o(pk_valid), .ready_i(core_ready), .data_o(pk_head));
  assign {tr_thread_o, tr_flags_o, tr_active_o, tr_o_o, tr_d_o, tr_tmin_o, tr_tmax_o} = pk_head;
  assign tr_valid_o = pk_valid && core_ready;

  // the pixels out, round robin
  rr_pick #(.N(B)) u_px_pick (.req_i(px_valid), .after_i(px_after_q), .any_o(px_any), .grant_o(px_grant),
    .index_o(px_pick), .after_o(px_after));
  assign px_ready = px_ready_i ? px_grant : '0;
  assign px_valid_o = px_any;
  assign px_x_o = bx_q[px_tag[px_pick]];
  assign px_y_o = by_q[px_tag[px_pick]];
  assign px_rgb_o = px_rgb[px_pick];
  assign px_inst_o = px_inst[px_pick];
  assign px_tri_o = px_tri[px_pick];
  assign px_t_o = px_t[px_pick];
  assign px_u_o = px_u[px_pick];
  assign px_v_o = px_v[px_pick];
  assign px_cos_o = px_cos[px_pick];
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tr_after_q <= '0;
      px_after_q <= '0;
    end else begin
      if (tr_any && pk_ready) tr_after_q <= tr_after;
      if (px_valid_o && px_ready_i) px_after_q <= px_after;
    end
  end

  // ---- the core ----
  logic word_rsp, node_rsp, list_req /*verilator public_flat_rd*/, list_ready /*verilator public_flat_rd*/, list_rsp;
  logic word_req /*verilator public_flat_rd*/, word_ready /*verilator public_flat_rd*/;
  logic node_req /*verilator public_flat_rd*/, node_ready /*verilator public_flat_rd*/;
  logic [31:0] word_addr, node_addr, list_addr, list_data;
  logic [32*RW-1:0] word_data;
  logic [63:0] node_data;
  logic [5:0] issue /*verilator public_flat_rd*/;
  logic hits_taken;
  always_comb begin
    hits_taken = 1'b0;
    for (int k = 0; k < B; k++)
      if (thread_o == TW'(k)) hits_taken = hit_ready[k];
  end
  /* verilator lint_off PINCONNECTEMPTY */
  trace_core #(.E(E), .M(M), .THREADS(THREADS)) u_core (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .valid_i(pk_valid), .ready_o(core_ready), .thread_i(tr_thread_o),
    .flags_i(tr_flags_o), .active_i(tr_active_o), .o_i(tr_o_o), .d_i(tr_d_o), .tmin_i(tr_tmin_o),
    .tmax_i(tr_tmax_o), .valid_o(valid_o), .ready_i(hits_taken), .thread_o(thread_o), .inst_o(inst_o),
    .tri_o(tri_o), .t_o(t_o), .u_o(u_o), .v_o(v_o),
    .cos_o(cos_o), .count_o(count_o), .inflight_o(), .mem_req_valid_o(word_req), .mem_req_ready_i(word_ready),
    .mem_addr_o(word_addr), .mem_rsp_valid_i(word_rsp), .mem_rdata_i(word_data), .node_req_valid_o(node_req),
    .node_req_ready_i(node_ready), .node_addr_o(node_addr), .node_rsp_valid_i(node_rsp),
    .node_w0_i(node_data[31:0]), .node_w1_i(node_data[63:32]), .list_req_o(list_req), .list_req_ready_i(list_ready),
    .list_addr_o(list_addr), .list_rsp_valid_i(list_rsp), .list_rdata_i(list_data), .issue_o(issue));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- the caches ----
  logic [3:0] mreq_valid /*verilator public_flat_rd*/, mreq_ready /*verilator public_flat_rd*/;
  logic [3:0] mrsp_valid /*verilator public_flat_rd*/;
  logic [4*32-1:0] mreq_addr;
  logic [DW-1:0] mrsp_data;
  cache_read #(.LINE_BYTES(8), .SIZE_BYTES(1024 * NODE_KB), .WORDS(2), .OUTSTANDING(OUTSTANDING)) u_nodes (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .req_valid_i(node_req), .req_ready_o(node_ready),
    .req_addr_i(node_addr), .rsp_valid_o(node_rsp), .rsp_data_o(node_data), .mem_req_valid_o(mreq_valid[0]),
    .mem_req_ready_i(mreq_ready[0]), .mem_req_addr_o(mreq_addr[0 +: 32]), .mem_rsp_valid_i(mrsp_valid[0]),
    .mem_rsp_data_i(mrsp_data[0 +: 64]));
  // list_unit's read port: its request register into the cache, the answers (in request order)
  // into its word queue
  cache_read #(.LINE_BYTES(4), .SIZE_BYTES(1024 * LIST_KB), .WORDS(1), .OUTSTANDING(OUTSTANDING)) u_lists (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .req_valid_i(list_req), .req_ready_o(list_ready),
    .req_addr_i(list_addr), .rsp_valid_o(list_rsp), .rsp_data_o(list_data), .mem_req_valid_o(mreq_valid[1]),
    .mem_req_ready_i(mreq_ready[1]), .mem_req_addr_o(mreq_addr[32 +: 32]), .mem_rsp_valid_i(mrsp_valid[1]),
    .mem_rsp_data_i(mrsp_data[0 +: 32]));

  cache_read #(.LINE_BYTES(MAT_LINE), .SIZE_BYTES(1024 * MAT_KB), .WORDS(RW), .OUTSTANDING(OUTSTANDING)) u_matrices (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .req_valid_i(word_req), .req_ready_o(word_ready),
    .req_addr_i(word_addr), .rsp_valid_o(word_rsp), .rsp_data_o(word_data), .mem_req_valid_o(mreq_valid[2]),
    .mem_req_ready_i(mreq_ready[2]), .mem_req_addr_o(mreq_addr[64 +: 32]), .mem_rsp_valid_i(mrsp_valid[2]),
    .mem_rsp_data_i(mrsp_data));

  // the RGS's line reads: the controllers' ports merged round robin, answers routed back in order,
  // through the shading cache, a whole 16-byte line a request (the controllers ask for lines by
  // their first word's address and take the words they need)
  logic sh_req /*verilator public_flat_rd*/, sh_ready /*verilator public_flat_rd*/, sh_rsp;
  logic [31:0] sh_addr;
  logic [127:0] sh_line;
  /* verilator lint_off PINCONNECTEMPTY */
  // the lines back to the RGS's readers a cycle later, registered: the shading cache's answer
  // through the port's routing into a surface's line reader was 12 LUT6 levels (synth.py
  // --dynrtp-path; the cycle model's shading hit counts the cycle)
  logic [B+S-1:0] rd_rsp_n;
  logic [127:0] rd_line_n;
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) rd_rsp <= '0;
    else rd_rsp <= rd_rsp_n;
  always_ff @(posedge clk_i) rd_line <= rd_line_n;
  mem_port #(.N(B + S), .DW(128), .DEPTH(OUTSTANDING)) u_rgs_reads (
    .clk_i(clk_i), .rst_ni(rst_ni), .req_valid_i(rd_valid), .req_ready_o(rd_ready), .req_addr_i(rd_addr),
    .req_bytes_i({(B + S){8'd16}}), .rsp_valid_o(rd_rsp_n), .rsp_data_o(rd_line_n), .mem_req_valid_o(sh_req),
    .mem_req_ready_i(sh_ready), .mem_req_addr_o(sh_addr), .mem_req_bytes_o(), .mem_req_src_o(),
    .mem_rsp_valid_i(sh_rsp), .mem_rsp_data_i(sh_line));
  /* verilator lint_on PINCONNECTEMPTY */
  
  cache_read #(.LINE_BYTES(16), .SIZE_BYTES(1024 * SHADE_KB), .WORDS(4), .OUTSTANDING(OUTSTANDING)) u_shading (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .req_valid_i(sh_req), .req_ready_o(sh_ready),
    .req_addr_i(sh_addr), .rsp_valid_o(sh_rsp), .rsp_data_o(sh_line), .mem_req_valid_o(mreq_valid[3]),
    .mem_req_ready_i(mreq_ready[3]), .mem_req_addr_o(mreq_addr[96 +: 32]), .mem_rsp_valid_i(mrsp_valid[3]),
    .mem_rsp_data_i(mrsp_data[0 +: 128]));

  // ---- the memory port ----
  mem_port #(.N(4), .DW(DW)) u_port (
    .clk_i(clk_i), .rst_ni(rst_ni), .req_valid_i(mreq_valid), .req_ready_o(mreq_ready), .req_addr_i(mreq_addr),
    .req_bytes_i({8'd16, 8'(MAT_LINE), 8'd4, 8'd8}), .rsp_valid_o(mrsp_valid), .rsp_data_o(mrsp_data),
    .mem_req_valid_o(mem_req_valid_o), .mem_req_ready_i(mem_req_ready_i), .mem_req_addr_o(mem_req_addr_o),
    .mem_req_bytes_o(mem_req_bytes_o), .mem_req_src_o(mem_req_src_o), .mem_rsp_valid_i(mem_rsp_valid_i),
    .mem_rsp_data_i(mem_rsp_data_i));

  // ---- the frame's end: every block dealt and its pixels taken ----
  logic running, dealt_all_q;
  logic [BW:0] busy_q /*verilator public_flat_rd*/;  // blocks in the controllers
  assign frame_done_o = running && dealt_all_q && busy_q == '0;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      dealt_all_q <= 1'b0;
      busy_q <= '0;
    end else begin
      if (frame_valid_i && frame_ready_o) dealt_all_q <= 1'b0;
      else if (blk_done) dealt_all_q <= 1'b1;
      busy_q <= busy_q + (BW + 1)'(blk_valid && blk_ready) - (BW + 1)'(px_valid_o && px_ready_i);
    end
  end

  // ---- counters: from the frame taken to its end ----
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      running <= 1'b0;
      cycles_o <= '0;
      issues_o <= '0;
      packets_o <= '0;
      reads_o <= '0;
    end else begin
      if (frame_valid_i && frame_ready_o) begin
        running <= 1'b1;
        cycles_o <= '0;
        issues_o <= '0;
        packets_o <= '0;
        reads_o <= '0;
      end else if (running) begin
        running <= !frame_done_o;
        cycles_o <= cycles_o + 64'd1;
        for (int u = 0; u < 6; u++) issues_o[64*u +: 64] <= issues_o[64*u +: 64] + 64'(issue[u]);
        packets_o <= packets_o + 64'(valid_o && hits_taken);
        reads_o[0 +: 64] <= reads_o[0 +: 64] + 64'(node_req && node_ready);
        reads_o[64 +: 64] <= reads_o[64 +: 64] + 64'(list_req && list_ready);
        reads_o[128 +: 64] <= reads_o[128 +: 64] + 64'(word_req && word_ready);
        reads_o[192 +: 64] <= reads_o[192 +: 64] + 64'(sh_req && sh_ready);
      end
    end
  end
endmodule
