// trace_core: the ray tracing core of a DynRTP (paper section 3, Figure 2 paths b..f): THREADS
// threads (trace_thread: each one packet's state and the FSM of hls/units/trace.c's trace_step)
// share the units that have RTL: trav_unit (clips, walk start, walk steps; the stacks of every
// thread and level), list_unit (the mailboxes), rebase_unit, xform_wide (instances, path d),
// isect_rebased (a triangle's transformation, origin path, intersection and best_t = t0 + t, path
// e) and 2 f24_add (the relative distances). A packet of 4 rays enters a free
// thread with its TRACE_* flags (TRACE_SKIP_TOP, TRACE_ANY_HIT for shadow packets,
// TRACE_IDENTITY) and leaves with its 4 closest (or any) hits and its trace_counters, bit for bit
// those of trace_begin + trace_step to TP_DONE. The traversal algorithm is TRAV_STACK only (the
// algorithm trav_unit has; the others of the C unit have no RTL).
// Issue: thread_sched (one ready set per unit, round robin): a thread raises its bit of a unit as
// it decides its next operation there, with the operation's issue slots (trace_thread's slots_o:
// 1 for the traversal and list units, the ray steps of a batch for the per-ray units); an issued
// thread that cannot go (no room in its unit's issue FIFO, a per-ray unit not ready or feeding)
// raises it again. An issue of s slots holds the unit for its thread s cycles, one ray step a
// cycle (feed_left, feed_thread), as the cycle model charges an operation of n rays n issue
// slots. Every unit's operands are registered after the multiplexer over the threads (the issue
// stage: a cycle): the traversal and list units' in a two-entry FIFO each, from which the unit
// takes its operation when it is ready (trav_unit refuses while its slots are full, list_unit
// while its queue is full or its read request waits for the list cache),
// the per-ray units' in registers the unit always takes. A thread's grant is the scheduler's
// one-hot pick (or the feeding thread's, registered) and the room in the FIFO (its count) or the
// per-ray unit's ready, neither of which looks at the offered operation (trav_unit's
// ONE_PER_THREAD: a thread waits for its result), so no operand multiplexer lies between a
// thread's state and its grant (10 LUT6 levels at 2 threads before 5aed4d4, docs/synth.md), nor
// the units' refusals (the traversal and list operands 10 levels or more at 64 threads before
// the FIFOs, 7 since, composed from measured parts: rtl/README.md). Each unit takes one step per
// cycle, so steps of different threads are in flight in every unit at once; the units without a
// thread id of their own (rebase, wide transformation, the triangle test, adders) carry the issued thread beside their pipeline in an f24_pipe of their latency
// (their outputs are always taken, so the latency is fixed). Results go to their thread alone, in
// the order its steps went in.
// Memory: the header's fields (the instance count, the region table's addresses, the scene bounds)
// read once per memory image (after reset or flush_i) on the first packet's use and held here for
// all threads, HDR_RSP responses; the instance, object and triangle records through the wide word
// port, RW consecutive words per response (one matrix cache line: a triangle record in one, an
// instance or object record in two), shared request by request: each cycle the header's load or
// else the lowest thread with a request sends one, at the address computed here from the thread's
// record, index and response (trace_thread's ld_rec_o, ld_ix_o, tris_o, ld_sent_o: the records'
// sizes and regions once here instead of an address adder and multiplier in each thread), its
// requester goes into a FIFO (the port
// answers in request order) and the response goes to the FIFO's oldest; trav_unit's node port (whose
// responses, in request order, are counted for their thread through a FIFO of thread ids) and
// list_unit's read port are the core's.
// Latency: per packet the sum of its operations' unit latencies, waits and reads (rtl/tb/tb_core.cpp
// reports cycles per packet and the operations in flight; a record read is one or two responses,
// the header's read once per image HDR_RSP); measured (tb_core --capture of cornell 32x24's 327
// packets, 2 shared AMD EPYC cores, 2026-11-25): 8 threads 52,844 cycles, 161.6 per packet
// (58,491 and 178.9 with the triangle as six batches on shared operators and the traversal
// unit's starts down its pipeline, 55,684 and 170.3 with the starts bypassing it), 1 thread
// (--threads 1) 415,578, 1270.9 per packet (459,070 and 1403.9; 436,985 and 1336.3); since
// 2026-11-29 a per-ray unit's step goes through the issue stage (a cycle: the operands from
// thread_ram) and a packet's hits through the output register (a cycle), and a traversal or list
// operation through its issue FIFO (a cycle; cornell 32x24 at 8 threads in the DynRTP: 51,938
// cycles before, 52,872 after). Throughput: up to one
// ray step per unit and cycle, one word port request per cycle, THREADS packets in flight.
// Resources: the units' (rtl/README.md), thread_sched (6 units, 4-bit slot counters), per unit a
// 4-bit feed counter and a thread id, THREADS trace_thread (its control and the fields the
// traversal unit or the FSM read, in registers), thread_ram per field group and reader: THREADS
// words per ray for the traversal unit's world rays (6 W) and object-space rays (so, sd 3 W each),
// 4 THREADS words for the per-ray units' world rays (6 W + 12 for the rebase unit: o and d with
// their identity flags id_flags, 6 bits each; 3 W (d) for the wide transformation, 3 W + 6 for
// the triangle test; written from a queue of 2 packets of 4 x 6 W bits), p
// (6 W, the wide transformation and the triangle test), te (W), so and sd (6 W each, high and low
// words, the rebase unit), sd's high words (3 W, the triangle test), t0 (W, the adders and the
// triangle test), 2 THREADS words of the leaves' te (4 W: a thread's per level, the rebase unit),
// THREADS words of the packets' tmin (4 W, the adders), THREADS words for the records' operands
// (the instance's matrix and translation's low words 15 W, the object's bounds 6 W, the
// triangle's record 15 W + 3) and 4 x THREADS words of 64 + 3 W bits for the hits' records; the
// per-ray units' issue stage (their other operands, a few W bits, registered once), the traversal
// and list units' issue FIFOs (two entries of TW + 12 W + 42 and TW + 106 bits) and the traversal's
// rays and box beside its FIFO (two entries of 30 W), the registered response (RW words) and one
// f24_vertex_lo per vertex component, the output register, the header's fields (5 words and the
// 6 W-bit bounds, once), the packets' trace_counters in 6 thread_count (one per event source:
// walk results, list results, kd-node answers, the adders', triangle test's and wide
// transformation's batches; 2 memories of THREADS x 32 or 64 bits each; synth_ice40 at 64 threads,
// python3 scripts/synth.py --ice40 thread_count THREADS=64 F=1 or F=2, 2026-11-30: 410 or 506
// SB_LUT4, 143 or 207 flip-flops, 4 or 8 SB_RAM40_4K: 2,748 SB_LUT4 and 36 SB_RAM40_4K for the 6,
// where the 64 threads' counters were 456 SB_LUT4 and 288 flip-flops each), the word port's FIFO
// of 2 THREADS requesters of TW + 1 bits and its address (a choice over the threads of 69 bits, the
// records' sizes times the index, two adders: this module's own cells at 64 threads 44,418 ->
// 46,442 SB_LUT4 and 0 -> 2 SB_MAC16 against 16,064 SB_LUT4 and 128 SB_MAC16 less in the threads,
// python3 scripts/synth.py --ice40 trace_core THREADS=64, 2026-11-30), two rr_pick
// without a pointer (the word port's and the output's lowest thread), the operand multiplexers
// (THREADS to 1 per unit, now mostly over the threads' flags, masks and distances).
// synth_ice40 -dsp -noflatten at the paper's 64 threads, e7m16, this module's own cells (its
// submodules black boxes: mapped as python3 scripts/synth.py --dynrtp ice40 maps each module,
// 2026-11-29): 61,586 SB_LUT4 and 4,715 flip-flops, its thread_ram 290
// SB_RAM40_4K (233 since the per-ray units' world rays are one memory each, 2026-11-30: 76 -> 19
// blocks, their queue 593 SB_LUT4 and 1,168 flip-flops as sync_fifo alone; not mapped again);
// with the rays' o and d in the threads' registers 133,921, 3,897 and 70 (the traversal's issue
// FIFO 1,064 SB_LUT4 and 2,110 flip-flops then, 344 and 670 now); trace_thread 2,989 SB_LUT4,
// 1,905 flip-flops (5,871 and 3,437), on 2026-11-30 (python3 scripts/synth.py --ice40
// trace_thread) 1,845 and 1,234 with its counters, tmin and the leaves' te here (the two memories
// 6 SB_RAM40_4K each) and t_o's +Inf for a miss at the output. At THREADS = 2 (synth_xilinx, e7m16, python3
// scripts/synth.py --levels trace_core THREADS=2 --hier, 2026-11-29) 147,530 LUT6, 126,641
// flip-flops, 11 LUT6 levels (137,189, 126,945 and 8 before the rays and the records' words
// moved here; the 11: a world ray's read through a shifter into xform_wide, a 4-to-1 choice
// since, now a memory's read of the step's ray; not re-synthesized: rtl/README.md).
// At THREADS = 64 (scripts/synth.py's per-module netlists, deepest_path on trace_core's subtree,
// 2026-11-30): 11 LUT6 levels, trace_thread's waiting_o through inflight_o's count; 10 between
// its own registers (10 on 391e0f0's RTL too, before the identity flags; rtl/README.md). Since
// the step's ray by the one-hot grant, the word request stage and the waiting threads' count
// registered (`python3 scripts/synth.py --dynrtp xilinx`, then `--dynrtp-path trace_core`,
// 2026-11-30): 10, thread_sched's pick index (4) through the triangle test's operand
// multiplexers over the threads (t_is_*[sel[U_IS]], 6) into their registers; left to do: those
// operands chosen by the one-hot grant as the step's ray is.
// Handshake: valid/ready at the packet input (into thread thread_i: ready_o when it is free and
// the world rays' queue has room) and at the result output (registered; the lowest finished
// thread first); word port valid/ready with responses in request order; trav_unit's node port
// and list_unit's read port as those units define them (a list request held until
// list_req_ready_i, the answers in request order, always taken: the list cache's). issue_o: the
// steps each unit took in this cycle (a batch counts its rays: the DynRTP's usage counters).
module trace_core #(
  parameter int E = 7,
  parameter int M = 16,
  localparam int RW = (12 * (1 + E + M) + 27 + 3 + 31) / 32,  // words per response (a triangle record)
  parameter int THREADS = 4,
  parameter int ADD_STAGES = 6,
  parameter int MUL_STAGES = 4,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2,
  parameter int SUM_STAGES = 25
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  input  logic                        flush_i,    // a new memory image (the core empty): read the header again
  // packet in (trace_begin) to thread thread_i
  input  logic                        valid_i,
  output logic                        ready_o,
  input  logic [$clog2(THREADS)-1:0]  thread_i,
  input  logic [2:0]                  flags_i,    // TRACE_SKIP_TOP, TRACE_ANY_HIT, TRACE_IDENTITY
  input  logic [3:0]                  active_i,
  input  logic [4*3*(E+M+1)-1:0]      o_i,        // ray i: words 3i .. 3i+2 (x, y, z)
  input  logic [4*3*(E+M+1)-1:0]      d_i,
  input  logic [4*(E+M+1)-1:0]        tmin_i,
  input  logic [4*(E+M+1)-1:0]        tmax_i,
  // hits out (TP_DONE)
  output logic                        valid_o,
  input  logic                        ready_i,
  output logic [$clog2(THREADS)-1:0]  thread_o,
  output logic [4*32-1:0]             inst_o,     // TRACE_NO_HIT for a miss
  output logic [4*32-1:0]             tri_o,
  output logic [4*(E+M+1)-1:0]        t_o,
  output logic [4*(E+M+1)-1:0]        u_o,
  output logic [4*(E+M+1)-1:0]        v_o,
  output logic [4*(E+M+1)-1:0]        cos_o,
  output logic [10*32-1:0]            count_o,    // trace_counters in its order (words: 4 kinds)
  output logic [$clog2(THREADS):0]    inflight_o, // threads with an operation in a unit
  // word read port (descriptors): RW words from the word address per response
  output logic                        mem_req_valid_o,
  input  logic                        mem_req_ready_i,
  output logic [31:0]                 mem_addr_o,
  input  logic                        mem_rsp_valid_i,
  input  logic [32*RW-1:0]            mem_rdata_i,
  // trav_unit's node port
  output logic                        node_req_valid_o,
  input  logic                        node_req_ready_i,
  output logic [31:0]                 node_addr_o,
  input  logic                        node_rsp_valid_i,
  input  logic [31:0]                 node_w0_i,
  input  logic [31:0]                 node_w1_i,
  // list_unit's read port
  output logic                        list_req_o,
  input  logic                        list_req_ready_i,
  output logic [31:0]                 list_addr_o,
  input  logic                        list_rsp_valid_i, // the answers in request order, always taken
  input  logic [31:0]                 list_rdata_i,
  // the units' issues this cycle (thread_sched: trav, list, rebase, wide, xform, isect, add, sum)
  output logic [5:0]                  issue_o
);
  localparam int W = 1 + E + M;
  localparam logic [E-1:0] EXP_MAX = '1;
  localparam logic [W-1:0] DNAN = {1'b0, EXP_MAX, 1'b1, {(M-1){1'b0}}};
  localparam logic [W-1:0] POS_INF = {1'b0, EXP_MAX, {M{1'b0}}};
  localparam int TW = $clog2(THREADS);
  localparam int UNITS = 6;
  localparam int U_TRAV = 0, U_LIST = 1, U_RB = 2, U_XW = 3, U_IS = 4, U_ADD = 5;
  localparam int XF_LATENCY = MUL_STAGES + 3 * ADD_STAGES;
  localparam int IS_LATENCY = DIV_STAGES + MUL_STAGES + 2 * ADD_STAGES + CMP_STAGES;
  // isect_rebased's (its header): the origin's rows and plane distance meet, then the test, t0 + t
  localparam int TRI_JOIN = 2 * ADD_STAGES + XF_LATENCY > ADD_STAGES + SUM_STAGES ?
                            2 * ADD_STAGES + XF_LATENCY : ADD_STAGES + SUM_STAGES;
  localparam int TRI_LATENCY = TRI_JOIN + IS_LATENCY + ADD_STAGES;
  if (THREADS < 2) begin : g_threads_check
    $error("trace_core: THREADS >= 2 (the units index their state by a thread id of $clog2(THREADS) bits)");
  end

  // ---- the threads' requests, operands and results ----
  logic [THREADS-1:0] t_ready, t_valid, t_out_ready, t_mem_req, t_waiting, t_node_rsp, t_hdr_want, t_walk_read;
  logic [THREADS*4-1:0] t_slots;
  logic [2:0] t_ld_rec [THREADS];
  logic [31:0] t_ld_ix [THREADS], t_tris [THREADS];
  logic [1:0] t_ld_sent [THREADS];
  logic [31:0] t_is_inst [THREADS], t_is_tri [THREADS];
  logic [3:0] t_hit [THREADS];
  logic [4*W-1:0] t_t [THREADS];
  logic [THREADS-1:0] req [UNITS], req_q [UNITS], grant [UNITS], done [UNITS];
  logic [UNITS-1:0] unit_ready, issue_valid;
  logic [UNITS*TW-1:0] issue_thread;
  // public_flat_rd (sel, unit_valid): read by tb_dynrtp for render --mode rtl --vcd
  logic [TW-1:0] sel [UNITS] /*verilator public_flat_rd*/;
  logic [UNITS*THREADS-1:0] set;
  // operands per thread
  logic [1:0] t_trav_kind [THREADS];
  logic [THREADS-1:0] t_trav_level, t_trav_obj, t_list_level, t_list_clear, t_xw_point;
  logic [3:0] t_trav_lo_zero [THREADS];
  logic [4*12-1:0] t_trav_id_sg [THREADS];
  logic [4*W-1:0] t_trav_tn [THREADS], t_trav_tf [THREADS], t_trav_best [THREADS];
  logic [3:0] t_trav_mask [THREADS], t_list_leaf_mask [THREADS], t_list_alive [THREADS];
  logic [31:0] t_trav_nodes [THREADS], t_list_lists [THREADS], t_list_first [THREADS], t_list_k [THREADS];
  logic [W-1:0] t_is_tmin [THREADS], t_is_tmax [THREADS];
  logic [W-1:0] t_add_a [THREADS];
  logic [1:0] t_ld_got [THREADS];
  logic [1:0] t_ray [THREADS];
  logic [11:0] t_id_sg [THREADS];
  logic [THREADS-1:0] t_rb_leaf, t_lo_zero, t_t0_zero;
  // the units' results (to every thread; done says whose)
  logic [3:0] trav_mask, trav_leaf_mask, list_need, list_skip;
  logic [4*W-1:0] trav_tn, trav_tf, trav_leaf_tn;
  logic trav_have_cur, trav_leaf, is_hit;
  logic [31:0] trav_leaf_first, trav_leaf_count, list_key, list_k;
  logic [3*W-1:0] rb_p_hi, rb_p_lo, xw_hi, xw_lo;
  logic [2*W-1:0] add_r;
  logic [W-1:0] rb_te, is_t, is_u, is_v, is_cos, is_t_world;
  // the word port: this cycle's request (the header's load, hdr_req, or thread word_sel), the
  // requester of the oldest response (word_head; its top bit the header's load)
  logic hdr_req, word_take, w_accept;
  logic [TW-1:0] word_sel;
  logic [THREADS-1:0] word_grant;  // one-hot word_sel
  logic [TW:0] word_head;
  // the header's fields, shared by all threads
  logic hdr_ok;
  logic [31:0] hdr_instances, hdr_objects, hdr_inst, hdr_top_nodes, hdr_top_lists;
  logic [6*W-1:0] scene_box;
  logic wq_ready;                         // the world rays' queue takes a packet (below)

  /* verilator lint_off PINCONNECTEMPTY */
  for (genvar t = 0; t < THREADS; t++) begin : g_thread
    trace_thread #(.E(E), .M(M)) u_thread (
      .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(valid_i && wq_ready && thread_i == TW'(t)), .ready_o(t_ready[t]),
      .flags_i(flags_i), .active_i(active_i), .tmin_i(tmin_i), .tmax_i(tmax_i),
      .valid_o(t_valid[t]), .ready_i(t_out_ready[t]), .hit_o(t_hit[t]), .t_o(t_t[t]),
      .hdr_want_o(t_hdr_want[t]), .hdr_ok_i(hdr_ok), .hdr_instances_i(hdr_instances),
      .hdr_top_nodes_i(hdr_top_nodes), .hdr_top_lists_i(hdr_top_lists),
      .mem_req_valid_o(t_mem_req[t]), .mem_req_ready_i(!hdr_req && word_grant[t] && w_accept),
      .ld_rec_o(t_ld_rec[t]), .ld_ix_o(t_ld_ix[t]), .tris_o(t_tris[t]), .ld_sent_o(t_ld_sent[t]), .mem_rsp_valid_i(mem_rsp_valid_i && word_head == {1'b0, TW'(t)}), .ld_got_o(t_ld_got[t]),
      .mem_rdata_i(mem_rdata_i), .node_rsp_i(t_node_rsp[t]), .walk_read_o(t_walk_read[t]),
      .waiting_o(t_waiting[t]),
      .slots_o(t_slots[t*4 +: 4]), .step_ray_o(t_ray[t]), .lo_zero_o(t_lo_zero[t]), .id_sg_o(t_id_sg[t]),
      .trav_req_o(req[U_TRAV][t]), .trav_grant_i(grant[U_TRAV][t]), .trav_kind_o(t_trav_kind[t]),
      .trav_level_o(t_trav_level[t]), .trav_obj_o(t_trav_obj[t]), .trav_lo_zero_o(t_trav_lo_zero[t]),
      .trav_id_sg_o(t_trav_id_sg[t]), .trav_tn_o(t_trav_tn[t]),
      .trav_tf_o(t_trav_tf[t]), .trav_best_o(t_trav_best[t]), .trav_mask_o(t_trav_mask[t]),
      .trav_nodes_o(t_trav_nodes[t]), .trav_done_i(done[U_TRAV][t]),
      .trav_mask_i(trav_mask), .trav_tn_i(trav_tn), .trav_tf_i(trav_tf), .trav_have_cur_i(trav_have_cur),
      .trav_leaf_i(trav_leaf), .trav_leaf_first_i(trav_leaf_first), .trav_leaf_count_i(trav_leaf_count),
      .trav_leaf_mask_i(trav_leaf_mask),
      .list_req_o(req[U_LIST][t]), .list_grant_i(grant[U_LIST][t]), .list_level_o(t_list_level[t]),
      .list_clear_o(t_list_clear[t]), .list_lists_o(t_list_lists[t]), .list_first_o(t_list_first[t]),
      .list_k_o(t_list_k[t]), .list_leaf_mask_o(t_list_leaf_mask[t]), .list_alive_o(t_list_alive[t]),
      .list_done_i(done[U_LIST][t]), .list_key_i(list_key), .list_need_i(list_need),
      .list_k_i(list_k),
      .rb_req_o(req[U_RB][t]), .rb_grant_i(grant[U_RB][t]), .t0_zero_o(t_t0_zero[t]),
      .rb_leaf_o(t_rb_leaf[t]),
      .rb_done_i(done[U_RB][t]),
      .xw_req_o(req[U_XW][t]), .xw_grant_i(grant[U_XW][t]), 
      .xw_point_o(t_xw_point[t]), .xw_done_i(done[U_XW][t]),
      .is_req_o(req[U_IS][t]), .is_grant_i(grant[U_IS][t]), 
     
      .is_tmin_o(t_is_tmin[t]), .is_tmax_o(t_is_tmax[t]),
      .is_done_i(done[U_IS][t]), .is_hit_i(is_hit), .is_t_i(is_t), .is_inst_o(t_is_inst[t]), .is_tri_o(t_is_tri[t]),
      .is_t_world_i(is_t_world),
      .add_req_o(req[U_ADD][t]), .add_grant_i(grant[U_ADD][t]), .add_a_o(t_add_a[t]),
      .add_done_i(done[U_ADD][t]), .add_r_i(add_r));
  end

  // ---- issue: a thread's request raises its ready bit once; a refused issue raises it again ----
  // An issue of s slots (a batch of s ray steps) holds the unit for its thread s cycles: the issue
  // takes the first step, the next s - 1 cycles feed the others (feed_left, feed_thread), one per
  // cycle that the unit takes, while thread_sched keeps the unit busy (its slots). Only the units
  // that are always ready get batches (s > 1); an issue that meets a refusal or a feed is refused
  // and raised again.
  logic [THREADS-1:0] one [THREADS];
  logic [3:0] issue_slots [UNITS], feed_left [UNITS];
  logic [TW-1:0] feed_thread [UNITS];
  // sel one-hot: the feeding thread's (registered) or the scheduler's pick, so that a thread's
  // grant is a few LUT6 levels from registers (a decoder after the pick's index was 2 more)
  logic [THREADS-1:0] feed_grant [UNITS], sel_grant [UNITS];
  logic [UNITS*THREADS-1:0] issue_grant;
  logic [UNITS-1:0] feeding, accept, unit_valid /*verilator public_flat_rd*/;
  logic [UNITS-1:0] issue_ready;  // the issue can go: the unit's ready, or room in its issue stage
  logic [UNITS*4-1:0] issue_slots_v;
  always_comb
    for (int t = 0; t < THREADS; t++) one[t] = THREADS'(1) << t;
  for (genvar u = 0; u < UNITS; u++) begin : g_issue
    assign issue_slots[u] = issue_slots_v[u*4 +: 4];
    // the traversal and list units take one slot per operation (trace_thread's slots_o is 1 but in
    // S_BATCH), so they never feed: their sel is the scheduler's pick alone
    assign feeding[u] = u >= U_RB && feed_left[u] != '0;
    assign accept[u] = issue_valid[u] && issue_ready[u] && !feeding[u];
    assign unit_valid[u] = issue_valid[u] || feeding[u];
    // the thread whose operands go into the unit: the feeding one, else the issued one
    assign sel[u] = feeding[u] ? feed_thread[u] : issue_thread[u*TW +: TW];
    assign sel_grant[u] = feeding[u] ? feed_grant[u] : issue_grant[u*THREADS +: THREADS];
    assign grant[u] = issue_ready[u] ? sel_grant[u] : '0;
    assign set[u*THREADS +: THREADS] = (req[u] & ~req_q[u]) |
                                       (issue_valid[u] && !accept[u] ? issue_grant[u*THREADS +: THREADS] : '0);
    always_ff @(posedge clk_i or negedge rst_ni)
      if (!rst_ni) begin
        req_q[u] <= '0;
        feed_left[u] <= '0;
      end else begin
        req_q[u] <= req[u];
        if (accept[u]) begin
          feed_left[u] <= issue_slots[u] - 4'd1;
          feed_thread[u] <= sel[u];
          feed_grant[u] <= sel_grant[u];
        end else if (feeding[u] && issue_ready[u]) feed_left[u] <= feed_left[u] - 4'd1;
      end
  end
  thread_sched #(.THREADS(THREADS), .UNITS(UNITS), .SLOT_BITS(4)) u_sched (
    .clk_i(clk_i), .rst_ni(rst_ni), .set_i(set), .slots_i(t_slots), .issue_valid_o(issue_valid),
    .issue_thread_o(issue_thread), .issue_grant_o(issue_grant), .issue_slots_o(issue_slots_v));

  // the steps the units took this cycle (a batch counts its rays; the traversal and list units'
  // operations as they enter their issue stage)
  assign issue_o = unit_valid & issue_ready;

  // ---- the traversal and list units' issue stage ----
  // An operation granted in cycle s is written from the operand multiplexers into its unit's
  // two-entry FIFO (sync_fifo: the multiplexers end at a register) at the end of s; the unit takes
  // the FIFO's head from s + 1 on, when it is ready (trav_unit refuses while its slots are full,
  // list_unit while its queue is full or its read request waits). The grant waits for room in
  // the FIFO (its count, from registers), not for the unit's ready: the unit's refusal does not
  // lie on the grant path, and one
  // operation per cycle goes in while the unit takes one per cycle. A result comes a cycle later
  // than an issue straight into the unit would give it. The traversal's rays are read from
  // thread_ram (below) in s and come a cycle after the rest of their entry: see trav_rays.
  localparam int TRAV_OPW = TW + 1 + 2 + 12 * W + 4 + 32;
  localparam int LIST_OPW = TW + 2 + 3 * 32 + 8;
  logic [TRAV_OPW-1:0] trav_op;
  logic [LIST_OPW-1:0] list_op;
  logic [U_LIST:U_TRAV] op_valid;
  logic [TW-1:0] trav_op_thread, list_op_thread;
  logic trav_op_level, list_op_level, list_op_clear;
  logic [1:0] trav_op_kind;
  logic [4*3*W-1:0] trav_op_o, trav_op_d;
  logic [4*W-1:0] trav_op_tn, trav_op_tf, trav_op_best;
  logic [3:0] trav_op_mask, list_op_leaf_mask, list_op_alive;
  logic [6*W-1:0] trav_op_box;
  logic [31:0] trav_op_nodes, list_op_lists, list_op_first, list_op_k;
  sync_fifo #(.W(TRAV_OPW), .DEPTH(2)) u_trav_issue (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(accept[U_TRAV]), .ready_o(issue_ready[U_TRAV]),
    .data_i({sel[U_TRAV], t_trav_level[sel[U_TRAV]], t_trav_kind[sel[U_TRAV]],
             t_trav_tn[sel[U_TRAV]], t_trav_tf[sel[U_TRAV]], t_trav_best[sel[U_TRAV]],
             t_trav_mask[sel[U_TRAV]], t_trav_nodes[sel[U_TRAV]]}),
    .valid_o(op_valid[U_TRAV]), .ready_i(unit_ready[U_TRAV]),
    .data_o(trav_op));
  assign {trav_op_thread, trav_op_level, trav_op_kind, trav_op_tn, trav_op_tf, trav_op_best,
          trav_op_mask, trav_op_nodes} = trav_op;
  sync_fifo #(.W(LIST_OPW), .DEPTH(2)) u_list_issue (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(accept[U_LIST]), .ready_o(issue_ready[U_LIST]),
    .data_i({sel[U_LIST], t_list_level[sel[U_LIST]], t_list_clear[sel[U_LIST]], t_list_lists[sel[U_LIST]],
             t_list_first[sel[U_LIST]], t_list_k[sel[U_LIST]], t_list_leaf_mask[sel[U_LIST]],
             t_list_alive[sel[U_LIST]]}),
    .valid_o(op_valid[U_LIST]), .ready_i(unit_ready[U_LIST]),
    .data_o(list_op));
  assign {list_op_thread, list_op_level, list_op_clear, list_op_lists, list_op_first, list_op_k, list_op_leaf_mask,
          list_op_alive} = list_op;

  // ---- the units ----
  logic trav_valid_o, trav_level;
  logic [1:0] trav_kind;
  logic [TW-1:0] trav_thread, node_thread;
  trav_unit #(.E(E), .M(M), .THREADS(THREADS), .ONE_PER_THREAD(1'b1), .ADD_STAGES(ADD_STAGES),
              .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES)) u_trav (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(op_valid[U_TRAV]), .ready_o(unit_ready[U_TRAV]),
    .thread_i(trav_op_thread), .level_i(trav_op_level), .kind_i(trav_op_kind), .o_i(trav_op_o), .d_i(trav_op_d),
    .tn_i(trav_op_tn), .tf_i(trav_op_tf), .best_i(trav_op_best), .mask_i(trav_op_mask), .box_i(trav_op_box),
    .nodes_i(trav_op_nodes),
    .node_req_valid_o(node_req_valid_o), .node_req_ready_i(node_req_ready_i), .node_addr_o(node_addr_o),
    .node_thread_o(node_thread), .node_level_o(), .node_rsp_valid_i(node_rsp_valid_i), .node_w0_i(node_w0_i),
    .node_w1_i(node_w1_i), .valid_o(trav_valid_o), .ready_i(1'b1), .thread_o(trav_thread), .level_o(trav_level), .kind_o(trav_kind),
    .mask_o(trav_mask), .tn_o(trav_tn), .tf_o(trav_tf), .node_o(), .have_cur_o(trav_have_cur), .leaf_o(trav_leaf),
    .list_o(), .leaf_first_o(trav_leaf_first), .leaf_count_o(trav_leaf_count), .leaf_mask_o(trav_leaf_mask),
    .leaf_tn_o(trav_leaf_tn), .sp_o(), .lost_o(), .restarted_o());
  assign done[U_TRAV] = trav_valid_o ? one[trav_thread] : '0;

  logic list_valid_o;
  logic [TW-1:0] list_thread;
  list_unit #(.THREADS(THREADS)) u_list (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(op_valid[U_LIST]), .ready_o(unit_ready[U_LIST]),
    .thread_i(list_op_thread), .level_i(list_op_level), .clear_i(list_op_clear), .lists_i(list_op_lists),
    .first_i(list_op_first), .k_i(list_op_k), .leaf_mask_i(list_op_leaf_mask), .alive_i(list_op_alive),
    .mem_req_o(list_req_o), .mem_req_ready_i(list_req_ready_i), .mem_addr_o(list_addr_o),
    .mem_rsp_valid_i(list_rsp_valid_i), .mem_rdata_i(list_rdata_i),
    .valid_o(list_valid_o),
    .ready_i(1'b1), .thread_o(list_thread), .level_o(), .key_o(list_key), .need_o(list_need), .skip_o(list_skip),
    .k_o(list_k));
  assign done[U_LIST] = list_valid_o ? one[list_thread] : '0;

  // ---- the per-ray units' issue stage ----
  // A step of a per-ray unit chosen in cycle s (sel, the thread's grant, its ray t_ray) reads the
  // fields that trace_core keeps in thread_ram (per thread and ray: the rays' o and d, the rebased
  // origins p, te, t0; per thread: the records' words) and registers its other operands from the
  // threads' multiplexers at the end of s; the unit takes it in s + 1. So each multiplexer ends at a register, and a batch's
  // results come a cycle later than an issue straight into the unit would give them.
  logic [UNITS-1:U_RB] step_q;            // the unit's step this cycle (the issue of the cycle before)
  logic [TW-1:0] sel_q [UNITS];
  logic [1:0] ray_q [UNITS];
  logic rb_leaf_q, rb_lo_zero_q, is_lo_zero_q, xw_point_q;
  logic [11:0] rb_id_sg_q, is_id_sg_q;
  logic [W-1:0] is_tmin_q, is_tmax_q;
  logic is_t0_zero_q, add_t0_zero_q;
  logic [W-1:0] add_a_q;
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) step_q <= '0;
    else
      for (int u = U_RB; u < UNITS; u++) step_q[u] <= unit_valid[u] && unit_ready[u];
  // the step's ray by the one-hot grant (an AND-OR over the threads): an index multiplexer after
  // the scheduler's index was 10 LUT6 levels into the read address (below) and ray_q
  logic [1:0] step_ray [U_RB:UNITS-1];
  always_comb
    for (int u = U_RB; u < UNITS; u++) begin
      step_ray[u] = '0;
      for (int t = 0; t < THREADS; t++) step_ray[u] = step_ray[u] | (t_ray[t] & {2{sel_grant[u][t]}});
    end
  always_ff @(posedge clk_i) begin
    for (int u = U_RB; u < UNITS; u++) begin
      sel_q[u] <= sel[u];
      ray_q[u] <= step_ray[u];
    end
    rb_leaf_q <= t_rb_leaf[sel[U_RB]];
    rb_lo_zero_q <= t_lo_zero[sel[U_RB]];
    rb_id_sg_q <= t_id_sg[sel[U_RB]];
    xw_point_q <= t_xw_point[sel[U_XW]];
    is_lo_zero_q <= t_lo_zero[sel[U_IS]];
    is_id_sg_q <= t_id_sg[sel[U_IS]];
    is_tmin_q <= t_is_tmin[sel[U_IS]];
    is_tmax_q <= t_is_tmax[sel[U_IS]];
    is_t0_zero_q <= t_t0_zero[sel[U_IS]];
    add_a_q <= t_add_a[sel[U_ADD]];
    add_t0_zero_q <= t_t0_zero[sel[U_ADD]];
  end

  assign issue_ready[UNITS-1:U_RB] = unit_ready[UNITS-1:U_RB];  // no FIFO: each unit takes its step

  // the units without a thread id: their outputs are always taken, so the step's thread (and for
  // the rebase and wide units its ray and kind, where their results go) travels beside them in a
  // delay line of their latency
  logic [UNITS-1:U_RB] out_valid;
  logic [TW-1:0] out_thread [UNITS];
  logic [TW+2:0] rb_tag, xw_tag;          // {leaf, ray, thread}, {pass, ray, thread} of their results
  logic [1:0] is_ray;                     // the triangle test's result's ray
  for (genvar u = U_RB; u < UNITS; u++) begin : g_tag
    localparam int LAT = u == U_IS ? TRI_LATENCY : u == U_ADD ? ADD_STAGES : SUM_STAGES;  // rebase, wide: SUM
    localparam int TAGW = u == U_ADD ? TW : u == U_IS ? TW + 2 : TW + 3;
    logic [TAGW-1:0] tag;
    f24_pipe #(.W(TAGW), .STAGES(LAT)) u_tag (
      .clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(step_q[u]),
      .data_i(TAGW'({u == U_XW ? !xw_point_q : rb_leaf_q, ray_q[u], sel_q[u]})), .valid_o(), .data_o(tag));
    assign out_thread[u] = tag[TW-1:0];
    if (u == U_RB) begin : g_rb
      assign rb_tag = tag;
    end else if (u == U_XW) begin : g_xw
      assign xw_tag = tag;
    end else if (u == U_IS) begin : g_is
      assign is_ray = tag[TW +: 2];
    end
    assign done[u] = out_valid[u] ? one[out_thread[u]] : '0;
  end

  // the rebased origins p (rebase_leaf, op_inst_xform) and a leaf's te, per thread and ray:
  // written by the rebase unit's results, read by the wide transformation's origins (pass 0) and
  // by the triangle test
  localparam int RAYS = 4 * THREADS;
  logic [TW+1:0] raddr [U_RB:UNITS-1];   // {thread, ray} of each per-ray unit's issue: its operands' word
  // ray r's word of the 4 rays' words v read from a memory of a thread's (a 4-to-1 choice)
  function automatic logic [W-1:0] ray_word(input logic [4*W-1:0] v, input logic [1:0] r);
    unique case (r)
      2'd0: ray_word = v[0 +: W];
      2'd1: ray_word = v[W +: W];
      2'd2: ray_word = v[2*W +: W];
      default: ray_word = v[3*W +: W];
    endcase
  endfunction
  for (genvar u = U_RB; u < UNITS; u++) begin : g_raddr
    assign raddr[u] = {sel[u], step_ray[u]};
  end
  logic [6*W-1:0] p_xw, p_is;
  logic [W-1:0] te_is;
  logic rb_we;
  logic [TW+1:0] rb_waddr;
  assign rb_we = out_valid[U_RB];
  assign rb_waddr = {rb_tag[TW-1:0], rb_tag[TW +: 2]};  // {thread, ray}
  thread_ram #(.W(6 * W), .DEPTH(RAYS)) u_p_xw (
    .clk_i(clk_i), .we_i(rb_we), .waddr_i(rb_waddr), .wdata_i({rb_p_hi, rb_p_lo}),
    .re_i(1'b1), .raddr_i(raddr[U_XW]), .rdata_o(p_xw));
  thread_ram #(.W(6 * W), .DEPTH(RAYS)) u_p_is (
    .clk_i(clk_i), .we_i(rb_we), .waddr_i(rb_waddr), .wdata_i({rb_p_hi, rb_p_lo}),
    .re_i(1'b1), .raddr_i(raddr[U_IS]), .rdata_o(p_is));
  thread_ram #(.W(W), .DEPTH(RAYS)) u_te_is (
    .clk_i(clk_i), .we_i(rb_we && rb_tag[TW+2]), .waddr_i(rb_waddr), .wdata_i(rb_te),
    .re_i(1'b1), .raddr_i(raddr[U_IS]), .rdata_o(te_is));

  // the object-space rays so, sd (op_inst_xform: high and low words) per thread and ray: written
  // by the wide transformation's results (pass 0 the origin's, pass 1 the direction's), read by a
  // leaf's rebase (both words) and the triangle test (the direction's high words); an identity
  // instance's rays are its thread's lo_zero and id_sg instead (obj_ray)
  logic [6*W-1:0] so_rb, sd_rb;
  logic [3*W-1:0] sd_is;
  logic [TW+1:0] xw_waddr;
  assign xw_waddr = {xw_tag[TW-1:0], xw_tag[TW +: 2]};
  thread_ram #(.W(6 * W), .DEPTH(RAYS)) u_so_rb (
    .clk_i(clk_i), .we_i(out_valid[U_XW] && !xw_tag[TW+2]), .waddr_i(xw_waddr), .wdata_i({xw_hi, xw_lo}),
    .re_i(1'b1), .raddr_i(raddr[U_RB]), .rdata_o(so_rb));
  thread_ram #(.W(6 * W), .DEPTH(RAYS)) u_sd_rb (
    .clk_i(clk_i), .we_i(out_valid[U_XW] && xw_tag[TW+2]), .waddr_i(xw_waddr), .wdata_i({xw_hi, xw_lo}),
    .re_i(1'b1), .raddr_i(raddr[U_RB]), .rdata_o(sd_rb));
  thread_ram #(.W(3 * W), .DEPTH(RAYS)) u_sd_is (
    .clk_i(clk_i), .we_i(out_valid[U_XW] && xw_tag[TW+2]), .waddr_i(xw_waddr), .wdata_i(xw_hi),
    .re_i(1'b1), .raddr_i(raddr[U_IS]), .rdata_o(sd_is));
  // t0 (op_inst_xform: the world ray's distance to the top-level leaf) per thread and ray: written
  // by the rebase unit's results of an instance (not a leaf), read by the adders (the relative
  // distances) and the triangle test (best_t = t0 + t); a new packet's and an identity instance's
  // +0 are its thread's t0_zero instead
  logic [W-1:0] t0_add, t0_is;
  thread_ram #(.W(W), .DEPTH(RAYS)) u_t0_add (
    .clk_i(clk_i), .we_i(rb_we && !rb_tag[TW+2]), .waddr_i(rb_waddr), .wdata_i(rb_te),
    .re_i(1'b1), .raddr_i(raddr[U_ADD]), .rdata_o(t0_add));
  thread_ram #(.W(W), .DEPTH(RAYS)) u_t0_is (
    .clk_i(clk_i), .we_i(rb_we && !rb_tag[TW+2]), .waddr_i(rb_waddr), .wdata_i(rb_te),
    .re_i(1'b1), .raddr_i(raddr[U_IS]), .rdata_o(t0_is));
  logic [W-1:0] add_t0, is_t0;
  assign add_t0 = add_t0_zero_q ? '0 : t0_add;
  assign is_t0 = is_t0_zero_q ? '0 : t0_is;

  // the records' words the units take, per thread (the instance's matrix and translation's low
  // words for the wide transformation, the object's bounds for the traversal unit, the triangle's
  // record for the triangle test): written from the word port's responses to a thread (the words
  // its lbuf takes, which it keeps for its FSM) a cycle late (rsp_*: the response registered, then
  // the vertices' low parts decoded from it), read in the issue cycle; a thread's batch or
  // operation that reads them issues at least two cycles after the response (its request, the
  // scheduler's set, the issue)
  logic rsp_we;
  logic [TW-1:0] rsp_thread;
  logic [1:0] rsp_ix;                     // the response's index in its record
  logic [32*RW-1:0] rsp_q;
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) rsp_we <= 1'b0;
    else rsp_we <= mem_rsp_valid_i && !word_head[TW];
  always_ff @(posedge clk_i) begin
    rsp_thread <= word_head[TW-1:0];
    rsp_ix <= t_ld_got[word_head[TW-1:0]];
    rsp_q <= mem_rdata_i;
  end
  // ranges g of a record's words, W bits each: 0 the instance's matrix (words 0 .. 11), 1 its
  // translation's low words (14 .. 16), 2 the object's bounds (8 .. 13); per response r a memory
  // of the range's words in it, read by the wide transformation (g < 2) or the traversal unit
  function automatic int rec_first(input int g);
    rec_first = g == 0 ? 0 : g == 1 ? 14 : 8;
  endfunction
  function automatic int rec_words(input int g);
    rec_words = g == 0 ? 12 : g == 1 ? 3 : 6;
  endfunction
  logic [21*W-1:0] rec_rd;                // the ranges' words side by side (12, 3, 6 words)
  for (genvar g = 0; g < 3; g++) begin : g_rec
    localparam int A = rec_first(g), N = rec_words(g), OFF = g == 0 ? 0 : g == 1 ? 12 : 15;
    for (genvar r = 0; r < 2; r++) begin : g_rsp
      localparam int LO = A > r * RW ? A : r * RW;
      localparam int HI = A + N < (r + 1) * RW ? A + N : (r + 1) * RW;
      if (HI > LO) begin : g_ram
        logic [(HI-LO)*W-1:0] wdata, rdata;
        for (genvar i = 0; i < HI - LO; i++) begin : g_word
          assign wdata[i*W +: W] = rsp_q[32 * (LO + i - r * RW) +: W];
        end
        thread_ram #(.W((HI - LO) * W), .DEPTH(THREADS)) u_w (
          .clk_i(clk_i), .we_i(rsp_we && rsp_ix == 2'(r)), .waddr_i(rsp_thread), .wdata_i(wdata),
          .re_i(1'b1), .raddr_i(sel[g < 2 ? U_XW : U_TRAV]), .rdata_o(rdata));
        assign rec_rd[(OFF + LO - A)*W +: (HI-LO)*W] = rdata;
      end
    end
  end
  // f24_vertex_lo: the low part k 2^-8 ulp(hi) of a vertex component from its 9-bit field
  if (M < 8) begin : g_m_check
    $error("trace_core: M >= 8 (the vertex's low part, 9-bit multiples, converts exactly)");
  end
  function automatic logic [W-1:0] vertex_lo(input logic [8:0] field, input logic [E-1:0] he);
    logic [8:0] mag;
    logic [M-1:0] frac;
    int p, e;
    mag = field[8] ? 9'(-field) : field;
    p = 0;
    for (int i = 0; i < 9; i++)
      if (mag[i]) p = i;
    frac = M'({{(M-1){1'b0}}, mag} << (M - p));
    e = {{(32-E){1'b0}}, he};
    e = e + p - M - 8;
    if (field == 0 || he == 0 || he == EXP_MAX) vertex_lo = '0;
    else if (e <= 0) vertex_lo = {field[8], {(E+M){1'b0}}};
    else vertex_lo = {field[8], e[E-1:0], frac};
  endfunction
  // the triangle's record (one response): the matrix, C's low parts, the shared-edge flags
  localparam int TRIW = 15 * W + 3;
  logic [TRIW-1:0] tri_wdata, tri_rd;
  always_comb begin
    tri_wdata[0 +: 12*W] = rsp_q[0 +: 12*W];
    for (int j = 0; j < 3; j++)  // C_hi's exponent: the matrix's word 4 j + 3
      tri_wdata[12*W + j*W +: W] = vertex_lo(rsp_q[12*W + 9*j +: 9], rsp_q[(4*j+3)*W + M +: E]);
    tri_wdata[15*W +: 3] = rsp_q[12*W + 27 +: 3];
  end
  thread_ram #(.W(TRIW), .DEPTH(THREADS)) u_tri (
    .clk_i(clk_i), .we_i(rsp_we && rsp_ix == 2'd0), .waddr_i(rsp_thread), .wdata_i(tri_wdata),
    .re_i(1'b1), .raddr_i(sel[U_IS]), .rdata_o(tri_rd));

  // the world rays o, d: the traversal unit's per thread, one memory per ray (it reads a packet's 4
  // rays at once, written as the packet enters), w_rd[r] = {o, d}; each per-ray unit's (the rebase
  // unit: o, d; the wide transformation and the triangle test: d) one memory per thread and ray,
  // {thread, ray} as p's, read as its step's ray: 4 THREADS words fill block RAM's 256 rows where
  // one memory per ray used a quarter of them (64 threads: 19 SB_RAM40_4K instead of 76). Its one
  // write port takes a ray a cycle: the packets wait in a queue of WQ_DEPTH (LUT RAM: flip-flops
  // on the iCE40) and ready_o is low while it is full (more than WQ_DEPTH packets in a row each
  // less than 4 cycles after the last; cycles unchanged in the frames of rtl/README.md). A
  // packet's rays are written within 4 WQ_DEPTH cycles of its entry, long before its first per-ray
  // step reads one: that follows its scene clip's result from the traversal unit (41 cycles or
  // more).
  localparam int WRD = 6 * W, WQ_DEPTH = 2;
  logic in_take, wq_valid;
  logic [TW+4*WRD-1:0] wq_in, wq_head;    // {thread, ray 3's {o, d}, .. ray 0's}
  logic [1:0] wq_ray;                     // the head's ray written in this cycle
  logic [WRD-1:0] wq_word;
  logic [TW+1:0] wq_addr;
  logic [4*WRD-1:0] w_rd;
  assign in_take = valid_i && ready_o;
  always_comb begin
    wq_in[4*WRD +: TW] = thread_i;
    for (int r = 0; r < 4; r++) wq_in[r*WRD +: WRD] = {o_i[r*3*W +: 3*W], d_i[r*3*W +: 3*W]};
  end
  sync_fifo #(.W(TW + 4 * WRD), .DEPTH(WQ_DEPTH)) u_world_q (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(in_take), .ready_o(wq_ready), .data_i(wq_in),
    .valid_o(wq_valid), .ready_i(wq_ray == 2'd3), .data_o(wq_head));
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) wq_ray <= '0;
    else if (wq_valid) wq_ray <= wq_ray + 2'd1;
  always_comb  // a 4-to-1 choice (an index into all of wq_head would be a shifter)
    unique case (wq_ray)
      2'd0: wq_word = wq_head[0 +: WRD];
      2'd1: wq_word = wq_head[WRD +: WRD];
      2'd2: wq_word = wq_head[2*WRD +: WRD];
      default: wq_word = wq_head[3*WRD +: WRD];
    endcase
  assign wq_addr = {wq_head[4*WRD +: TW], wq_ray};
  for (genvar r = 0; r < 4; r++) begin : g_world
    thread_ram #(.W(WRD), .DEPTH(THREADS)) u_w (
      .clk_i(clk_i), .we_i(in_take), .waddr_i(thread_i), .wdata_i(wq_in[r*WRD +: WRD]),
      .re_i(1'b1), .raddr_i(sel[U_TRAV]), .rdata_o(w_rd[r*WRD +: WRD]));
  end
  // the rebase unit's o and d and the triangle test's d with their id_flags (rb_w = {o and its
  // flags, d and its}), computed from the queue's word as it is written
  localparam int VF = 3 * W + FLW;
  logic [2*VF-1:0] rb_w;
  logic [VF-1:0] is_w;
  logic [3*W-1:0] xw_w;
  thread_ram #(.W(2 * VF), .DEPTH(RAYS)) u_world_rb (
    .clk_i(clk_i), .we_i(wq_valid), .waddr_i(wq_addr),
    .wdata_i({with_flags(wq_word[3*W +: 3*W]), with_flags(wq_word[0 +: 3*W])}),
    .re_i(1'b1), .raddr_i(raddr[U_RB]), .rdata_o(rb_w));
  thread_ram #(.W(3 * W), .DEPTH(RAYS)) u_world_xw (
    .clk_i(clk_i), .we_i(wq_valid), .waddr_i(wq_addr), .wdata_i(wq_word[0 +: 3*W]),
    .re_i(1'b1), .raddr_i(raddr[U_XW]), .rdata_o(xw_w));
  thread_ram #(.W(VF), .DEPTH(RAYS)) u_world_is (
    .clk_i(clk_i), .we_i(wq_valid), .waddr_i(wq_addr), .wdata_i(with_flags(wq_word[0 +: 3*W])),
    .re_i(1'b1), .raddr_i(raddr[U_IS]), .rdata_o(is_w));
  // the object-space rays' high words per thread for the traversal unit, one memory per ray and
  // pass (so, sd)
  logic [8*3*W-1:0] obj_trav;             // ray r's so at 3W r, its sd at 3W (4 + r)
  for (genvar k = 0; k < 8; k++) begin : g_obj_trav
    thread_ram #(.W(3 * W), .DEPTH(THREADS)) u_obj (
      .clk_i(clk_i), .we_i(out_valid[U_XW] && xw_tag[TW+2] == (k >= 4) && xw_tag[TW +: 2] == 2'(k % 4)),
      .waddr_i(xw_tag[TW-1:0]), .wdata_i(xw_hi), .re_i(1'b1), .raddr_i(sel[U_TRAV]),
      .rdata_o(obj_trav[k*3*W +: 3*W]));
  end
  // xform_identity (op_inst_xform of an identity instance): the bits xform_point/xform_vector give
  // for an identity with signed zeros, from the matrix's signs sg and the flags id_flags of the
  // world vector v: computed where v is written into memory, so that a result bit other than
  // the sign needs 6 bits after the read with the choice of the memory's word (one LUT6) where
  // the exponent tests after the read made the rebase unit's operands 6 levels (trace_core's 10
  // between registers with f24_sum_exact's first segment, rtl/README.md)
  localparam int FLW = 6;                 // id_flags' bits per vector
  // per component k: bit k its result is the default NaN (a NaN in it, or an Inf or NaN in
  // another component), bit 3 + k its exponent is 0 (the result a signed zero)
  function automatic logic [FLW-1:0] id_flags(input logic [3*W-1:0] v);
    logic [2:0] inf_nan, nan, zero;
    for (int k = 0; k < 3; k++) begin
      inf_nan[k] = v[k*W + M +: E] == EXP_MAX;
      nan[k] = inf_nan[k] && v[k*W +: M] != 0;
      zero[k] = v[k*W + M +: E] == 0;
    end
    for (int k = 0; k < 3; k++)
      for (int j = 0; j < 3; j++)
        if (j != k && inf_nan[j]) nan[k] = 1'b1;
    id_flags = {zero, nan};
  endfunction
  function automatic logic [3*W-1:0] identity(input logic [11:0] sg, input logic [3*W-1:0] v,
                                              input logic [FLW-1:0] fl, input logic point);
    logic [3*W-1:0] r;
    for (int kk = 0; kk < 3; kk++) begin
      logic neg;
      neg = point ? sg[4*kk+3] : 1'b1;
      for (int j = 0; j < 3; j++)
        neg &= j == kk ? v[j*W + W-1] : sg[4*kk+j] ^ v[j*W + W-1];
      r[kk*W +: W] = fl[kk] ? DNAN : !fl[3+kk] ? v[kk*W +: W] : {neg, {(W-1){1'b0}}};
    end
    identity = r;
  endfunction
  // an object-space ray's high words: the memory's, or an identity instance's from the world ray
  // (world: a vector and its id_flags)
  function automatic logic [3*W-1:0] obj_ray(input logic lo_zero, input logic [11:0] sg,
                                             input logic [3*W+FLW-1:0] world, input logic [3*W-1:0] obj,
                                             input logic point);
    obj_ray = lo_zero ? identity(sg, world[FLW +: 3*W], world[0 +: FLW], point) : obj;
  endfunction
  // a world vector with its id_flags (the memories' words of a vector)
  function automatic logic [3*W+FLW-1:0] with_flags(input logic [3*W-1:0] v);
    with_flags = {v, id_flags(v)};
  endfunction

  // the traversal unit's rays: read in the cycle s its operation enters the issue FIFO, they come
  // in s + 1, when they are written into their entry's place beside the FIFO (trav_rays, the same
  // slots in the same order) and, if that entry is the FIFO's head, go to the unit directly: no
  // cycle added
  logic trav_obj_q, trav_scene_q, trav_wr_q, trav_slot_q, trav_head, trav_tail;
  logic [3:0] trav_lo_zero_q;
  logic [4*12-1:0] trav_id_sg_q;
  logic [30*W-1:0] trav_rd, trav_rays [2];  // {o, d} of the 4 rays, the box
  always_ff @(posedge clk_i) begin
    trav_obj_q <= t_trav_obj[sel[U_TRAV]];
    trav_scene_q <= t_trav_kind[sel[U_TRAV]] == 2'd0;  // the scene clip: the scene's bounds
    trav_lo_zero_q <= t_trav_lo_zero[sel[U_TRAV]];
    trav_id_sg_q <= t_trav_id_sg[sel[U_TRAV]];
    trav_slot_q <= trav_tail;
    if (trav_wr_q) trav_rays[trav_slot_q] <= trav_rd;
  end
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      trav_wr_q <= 1'b0;
      trav_head <= 1'b0;
      trav_tail <= 1'b0;
    end else begin
      trav_wr_q <= accept[U_TRAV];
      if (accept[U_TRAV]) trav_tail <= !trav_tail;
      if (op_valid[U_TRAV] && unit_ready[U_TRAV]) trav_head <= !trav_head;
    end
  always_comb
    for (int r = 0; r < 4; r++) begin
      logic [3*W-1:0] wo, wd;
      wo = w_rd[r*WRD + 3*W +: 3*W];
      wd = w_rd[r*WRD +: 3*W];
      trav_rd[18*W + r*3*W +: 3*W] = !trav_obj_q ? wo :
        obj_ray(trav_lo_zero_q[r], trav_id_sg_q[r*12 +: 12], with_flags(wo), obj_trav[r*3*W +: 3*W], 1'b1);
      trav_rd[6*W + r*3*W +: 3*W] = !trav_obj_q ? wd :
        obj_ray(trav_lo_zero_q[r], trav_id_sg_q[r*12 +: 12], with_flags(wd), obj_trav[(4+r)*3*W +: 3*W], 1'b0);
    end
  assign trav_rd[0 +: 6*W] = trav_scene_q ? scene_box : rec_rd[15*W +: 6*W];
  assign {trav_op_o, trav_op_d, trav_op_box} = trav_wr_q && trav_slot_q == trav_head ? trav_rd : trav_rays[trav_head];

  // the per-ray units' rays (their memories' words of the step's thread and ray)
  logic [3*W-1:0] rb_o_hi, rb_d_hi, xw_d, is_d;
  assign rb_o_hi = rb_leaf_q ? obj_ray(rb_lo_zero_q, rb_id_sg_q, rb_w[VF +: VF], so_rb[3*W +: 3*W], 1'b1)
                             : rb_w[VF + FLW +: 3*W];
  assign rb_d_hi = rb_leaf_q ? obj_ray(rb_lo_zero_q, rb_id_sg_q, rb_w[0 +: VF], sd_rb[3*W +: 3*W], 1'b0)
                             : rb_w[FLW +: 3*W];
  assign xw_d = xw_w;
  assign is_d = obj_ray(is_lo_zero_q, is_id_sg_q, is_w, sd_is, 1'b0);

  // the leaves' entry distances te per thread and level (rebase_leaf's t, and op_inst_xform's: the
  // top-level leaf's): written by the traversal unit's results, a walk's leaf at its level and
  // the scene clip's tn at level 0 (enter_single_object's one-leaf list; where a walk follows, its
  // leaf writes over it before a rebase reads it), read by the rebase unit's step at the level of
  // its kind and its ray's word chosen from the 4 (a choice of 8 per thread before: 24 W
  // flip-flops and about 300 SB_LUT4 in each trace_thread)
  logic [4*W-1:0] leaf_tn_rd;
  thread_ram #(.W(4 * W), .DEPTH(2 * THREADS)) u_leaf_tn (
    .clk_i(clk_i), .we_i(trav_valid_o && (trav_kind == 2'd0 || (trav_kind == 2'd3 && trav_leaf))),
    .waddr_i({trav_thread, trav_level}), .wdata_i(trav_kind == 2'd0 ? trav_tn : trav_leaf_tn),
    .re_i(1'b1), .raddr_i({sel[U_RB], t_rb_leaf[sel[U_RB]]}), .rdata_o(leaf_tn_rd));

  logic rb_lo;                            // a leaf's rebase of an instance's rays in double words
  assign rb_lo = rb_leaf_q && !rb_lo_zero_q;

  rebase_unit #(.E(E), .M(M), .SUM_STAGES(SUM_STAGES)) u_rebase (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(step_q[U_RB]), .ready_o(unit_ready[U_RB]),
    .o_hi_i(rb_o_hi), .o_lo_i(rb_lo ? so_rb[0 +: 3*W] : '0), .d_hi_i(rb_d_hi), .d_lo_i(rb_lo ? sd_rb[0 +: 3*W] : '0),
    .t_i(ray_word(leaf_tn_rd, ray_q[U_RB])),
    .valid_o(out_valid[U_RB]), .ready_i(1'b1), .p_hi_o(rb_p_hi), .p_lo_o(rb_p_lo), .te_o(rb_te));

  // pass 0 of an instance's rays transforms the rebased origin, pass 1 the direction
  xform_wide #(.E(E), .M(M), .SUM_STAGES(SUM_STAGES)) u_wide (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(step_q[U_XW]), .ready_o(unit_ready[U_XW]),
    .m_i(rec_rd[0 +: 12*W]), .tlo_i(rec_rd[12*W +: 3*W]), .p_hi_i(xw_point_q ? p_xw[3*W +: 3*W] : xw_d), .p_lo_i(p_xw[0 +: 3*W]),
    .point_i(xw_point_q), .valid_o(out_valid[U_XW]), .ready_i(1'b1), .r_hi_o(xw_hi), .r_lo_o(xw_lo));

  assign unit_ready[U_IS] = 1'b1;  // no stall
  isect_rebased #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .MUL_STAGES(MUL_STAGES), .DIV_STAGES(DIV_STAGES),
                  .CMP_STAGES(CMP_STAGES), .SUM_STAGES(SUM_STAGES)) u_isect (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(step_q[U_IS]), .m_i(tri_rd[0 +: 12*W]), .c_lo_i(tri_rd[12*W +: 3*W]),
    .shared_i(tri_rd[15*W +: 3]), .p_hi_i(p_is[3*W +: 3*W]), .p_lo_i(p_is[0 +: 3*W]), .d_i(is_d), .te_i(te_is),
    .tmin_i(is_tmin_q), .tmax_i(is_tmax_q), .t0_i(is_t0),
    .valid_o(out_valid[U_IS]), .hit_o(is_hit), .t_o(is_t), .u_o(is_u), .v_o(is_v), .cos_o(is_cos),
    .t_world_o(is_t_world));

  // the packets' tmin per thread (the 4 rays' words), written as a packet enters, read by the
  // subtractors' step (tmin_rel = tmin - t0; 4 W flip-flops and a choice of 4 in each thread
  // before)
  logic [4*W-1:0] tmin_rd;
  thread_ram #(.W(4 * W), .DEPTH(THREADS)) u_tmin (
    .clk_i(clk_i), .we_i(in_take), .waddr_i(thread_i), .wdata_i(tmin_i),
    .re_i(1'b1), .raddr_i(sel[U_ADD]), .rdata_o(tmin_rd));
  logic [2*W-1:0] add_a;                  // {tmin, best_t} of the step's ray
  assign add_a = {ray_word(tmin_rd, ray_q[U_ADD]), add_a_q};
  logic [1:0] add_valid;
  assign unit_ready[U_ADD] = 1'b1;  // the operators have no stall
  for (genvar j = 0; j < 2; j++) begin : g_add
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_add (
      .clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(step_q[U_ADD]),
      .a_i(add_a[j*W +: W]), .b_i(add_t0), .sub_i(1'b1),
      .valid_o(add_valid[j]), .res_o(add_r[j*W +: W]));
  end
  assign out_valid[U_ADD] = &add_valid;
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- kd-node reads: whose they are, in request order ----
  logic [TW-1:0] node_q [2**TW];
  logic [TW:0] node_wr, node_rd;
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      node_wr <= '0;
      node_rd <= '0;
    end else begin
      if (node_req_valid_o && node_req_ready_i) begin
        node_q[node_wr[TW-1:0]] <= node_thread;
        node_wr <= node_wr + 1'b1;
      end
      if (node_rsp_valid_i) node_rd <= node_rd + 1'b1;
    end
  assign t_node_rsp = node_rsp_valid_i ? one[node_q[node_rd[TW-1:0]]] : '0;

  // ---- the header: read once per image when a thread first waits for it ----
  // memory image layout (docs/memory-image.md; hls/units/trace.c): the fields' word addresses
  localparam int H_INSTANCES = 7, H_BOUNDS = 12, H_OBJECTS_AT = 18 + 2 * 5, H_INST_AT = 18 + 2 * 8;
  localparam int H_TOP_NODES_AT = 18 + 2 * 9, H_TOP_LISTS_AT = 18 + 2 * 10;
  localparam int HDR_RSP = (H_TOP_LISTS_AT + 1 + RW - 1) / RW;
  localparam int HB = $clog2(HDR_RSP + 1);
  logic hdr_load;
  logic [HB-1:0] hdr_sent, hdr_got;
  // the word at address a from the response that holds it
  function automatic logic [31:0] hdr_word(input logic [32*RW-1:0] rsp, input int a);
    hdr_word = rsp[32 * (a % RW) +: 32];
  endfunction
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      hdr_ok <= 1'b0;
      hdr_load <= 1'b0;
    end else if (flush_i) hdr_ok <= 1'b0;
    else if (!hdr_ok && !hdr_load && |t_hdr_want) begin
      hdr_load <= 1'b1;
      hdr_sent <= '0;
      hdr_got <= '0;
    end else if (hdr_load) begin
      if (hdr_req && w_accept) hdr_sent <= hdr_sent + 1'b1;
      if (mem_rsp_valid_i && word_head[TW]) begin
        if (hdr_got == HB'(H_INSTANCES / RW)) hdr_instances <= hdr_word(mem_rdata_i, H_INSTANCES);
        if (hdr_got == HB'(H_OBJECTS_AT / RW)) hdr_objects <= hdr_word(mem_rdata_i, H_OBJECTS_AT);
        if (hdr_got == HB'(H_INST_AT / RW)) hdr_inst <= hdr_word(mem_rdata_i, H_INST_AT);
        if (hdr_got == HB'(H_TOP_NODES_AT / RW)) hdr_top_nodes <= hdr_word(mem_rdata_i, H_TOP_NODES_AT);
        if (hdr_got == HB'(H_TOP_LISTS_AT / RW)) hdr_top_lists <= hdr_word(mem_rdata_i, H_TOP_LISTS_AT);
        for (int j = 0; j < 6; j++)
          if (hdr_got == HB'((H_BOUNDS + j) / RW)) scene_box[j*W +: W] <= W'(hdr_word(mem_rdata_i, H_BOUNDS + j));
        hdr_got <= hdr_got + 1'b1;
        if (hdr_got == HB'(HDR_RSP - 1)) begin
          hdr_load <= 1'b0;
          hdr_ok <= 1'b1;
        end
      end
    end

  // ---- the word port: one request per cycle, the header's load first, else the lowest thread ----
  // The FIFO of requesters holds 2 THREADS (a thread has at most INST_RSP responses outstanding,
  // 2 at e7m16); a request waits while it is full.
  localparam int QB = TW + 1;
  logic [TW:0] word_q [2**QB];
  logic [QB:0] word_wr, word_rd;
  assign hdr_req = hdr_load && hdr_sent != HB'(HDR_RSP);
  // the lowest requesting thread, one-hot on a carry chain and its index by OR trees (rr_pick with
  // no pointer): a priority loop over 64 threads was 8 LUT6 levels in front of each thread's ready
  /* verilator lint_off PINCONNECTEMPTY */
  rr_pick #(.N(THREADS)) u_word_pick (.req_i(t_mem_req), .after_i('0), .any_o(), .grant_o(word_grant),
                                      .index_o(word_sel), .after_o());
  /* verilator lint_on PINCONNECTEMPTY */
  // a thread's request: its record's address (the region + the record's size x its index; the
  // records' layout: docs/memory-image.md, hls/units/trace.c) + RW words per response before it,
  // computed here once for the thread picked instead of in each of the THREADS threads. A request
  // stage: the pick's fields (an AND-OR over the threads by the one-hot grant) are registered as
  // the thread's request is taken (w_*), the address is computed from them in the next cycle,
  // when the request leaves: the pick, its choice and the address in one cycle were 9 to 10 LUT6
  // levels before the matrix cache's index (a read leaves a cycle later; the cycle model counts it).
  localparam int TRI_WORDS = RW;                            // F24_TRIANGLE_RECORD_WORDS
  localparam int INST_WORDS = TRI_WORDS * ((17 + TRI_WORDS - 1) / TRI_WORDS);
  localparam int OBJ_WORDS = 16;
  localparam logic [2:0] REC_NODE = 3'd0, REC_LIST = 3'd1, REC_INST = 3'd2, REC_OBJ = 3'd3;  // trace_thread's ld_rec_o
  logic [2:0] rec_kind, w_kind;
  localparam int SB = HB > 2 ? HB : 2;
  logic [SB-1:0] rec_sent, w_sent;        // responses before this one (the header's or the thread's)
  logic [31:0] rec_ix, rec_tris, w_ix, w_tris, w_base, w_off;
  logic w_valid, w_hdr;
  logic [TW-1:0] w_sel;
  always_comb begin
    rec_kind = '0;
    rec_sent = hdr_req ? SB'(hdr_sent) : '0;
    rec_ix = '0;
    rec_tris = '0;
    for (int t = 0; t < THREADS; t++) begin
      rec_kind = rec_kind | (t_ld_rec[t] & {3{word_grant[t]}});
      rec_sent = rec_sent | (SB'(t_ld_sent[t]) & {SB{word_grant[t] && !hdr_req}});
      rec_ix = rec_ix | (t_ld_ix[t] & {32{word_grant[t]}});
      rec_tris = rec_tris | (t_tris[t] & {32{word_grant[t]}});
    end
  end
  assign w_accept = !w_valid || word_take;
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) w_valid <= 1'b0;
    else if (w_accept) w_valid <= hdr_req || |t_mem_req;
  always_ff @(posedge clk_i)
    if (w_accept) begin
      w_hdr <= hdr_req;
      w_sel <= word_sel;
      w_kind <= rec_kind;
      w_sent <= rec_sent;
      w_ix <= rec_ix;
      w_tris <= rec_tris;
    end
  always_comb begin
    w_off = 32'(RW) * 32'(w_sent);
    unique case (w_kind)
      REC_NODE: begin w_base = hdr_top_nodes; w_off = 32'd1; end  // the top node's word 1
      REC_LIST: w_base = hdr_top_lists + w_ix;
      REC_INST: w_base = hdr_inst + 32'(INST_WORDS) * w_ix;
      REC_OBJ: w_base = hdr_objects + 32'(OBJ_WORDS) * w_ix;
      default: w_base = w_tris + 32'(TRI_WORDS) * w_ix;  // REC_TRI
    endcase
    if (w_hdr) begin  // the header's load: its responses from address 0
      w_base = '0;
      w_off = 32'(RW) * 32'(w_sent);
    end
  end
  assign mem_req_valid_o = w_valid && word_wr - word_rd != (QB + 1)'(2**QB);
  assign mem_addr_o = w_base + w_off;
  assign word_take = mem_req_valid_o && mem_req_ready_i;
  assign word_head = word_q[word_rd[QB-1:0]];
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      word_wr <= '0;
      word_rd <= '0;
    end else begin
      if (word_take) begin
        word_q[word_wr[QB-1:0]] <= w_hdr ? {1'b1, TW'(0)} : {1'b0, w_sel};
        word_wr <= word_wr + 1'b1;
      end
      if (mem_rsp_valid_i) word_rd <= word_rd + 1'b1;
    end

  // ---- packets in and out ----
  // A finished packet leaves its thread into the output register (out_full) when that is free or
  // being taken (the lowest finished thread first), and its thread is free from the next cycle;
  // the register holds the thread's hit flags and t, and its hits' records and counters come from
  // memories read in the same cycle: a packet's hits leave a cycle after its thread finished.
  logic [TW-1:0] out_sel;
  logic [THREADS-1:0] out_grant;
  logic out_any, out_take, out_full;
  /* verilator lint_off PINCONNECTEMPTY */
  rr_pick #(.N(THREADS)) u_out_pick (.req_i(t_valid), .after_i('0), .any_o(out_any), .grant_o(out_grant),
                                     .index_o(out_sel), .after_o());
  /* verilator lint_on PINCONNECTEMPTY */
  assign ready_o = t_ready[thread_i] && wq_ready;
  assign out_take = !out_full || ready_i;
  assign t_out_ready = out_take ? out_grant : '0;
  logic [3:0] out_hit;
  logic [4*W-1:0] out_t;                  // the thread's best_t, a hit's t where out_hit
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) out_full <= 1'b0;
    else if (out_take) out_full <= out_any;
  always_ff @(posedge clk_i)
    if (out_take) begin
      thread_o <= out_sel;
      out_hit <= t_hit[out_sel];
      out_t <= t_t[out_sel];
    end
  assign valid_o = out_full;
  // a hit's record per thread, one memory per ray: written by the triangle test's hits (the
  // instance and triangle from the thread the result is for), read as the packet leaves
  logic [31:0] is_inst, is_tri;
  assign is_inst = t_is_inst[out_thread[U_IS]];
  assign is_tri = t_is_tri[out_thread[U_IS]];
  localparam logic [31:0] NO_HIT = '1;
  for (genvar r = 0; r < 4; r++) begin : g_hit
    logic [64+3*W-1:0] rec;
    thread_ram #(.W(64 + 3 * W), .DEPTH(THREADS)) u_hit (
      .clk_i(clk_i), .we_i(out_valid[U_IS] && is_hit && is_ray == 2'(r)), .waddr_i(out_thread[U_IS]),
      .wdata_i({is_inst, is_tri, is_u, is_v, is_cos}), .re_i(out_take), .raddr_i(out_sel), .rdata_o(rec));
    assign inst_o[r*32 +: 32] = out_hit[r] ? rec[3*W+32 +: 32] : NO_HIT;
    assign tri_o[r*32 +: 32] = out_hit[r] ? rec[3*W +: 32] : NO_HIT;
    assign u_o[r*W +: W] = out_hit[r] ? rec[2*W +: W] : '0;
    assign v_o[r*W +: W] = out_hit[r] ? rec[W +: W] : '0;
    assign cos_o[r*W +: W] = out_hit[r] ? rec[0 +: W] : '0;
    assign t_o[r*W +: W] = out_hit[r] ? out_t[r*W +: W] : POS_INF;  // +Inf for a miss (one choice, not one per thread)
  end

  // ---- the packets' trace_counters (hls/units/trace.c), per thread in memories (thread_count) ----
  // Each count is kept where the units report it, one memory per event source (they come in the
  // same cycle for different threads), zeroed as a packet enters its thread and read as it leaves
  // (beside its hits' records): a walk step's result (C_LEAVES, or C_STEPS if it read a kd node:
  // its thread's walk_read or a node's answer in this cycle), a list entry (C_ENTRIES, the same
  // C_LISTS words, C_SKIPS), a kd node's answer (C_NODES: 2 words), an instance's relative
  // distances' batch (once per instance: C_MATRICES its 17 + 14 words read), a triangle's batch
  // (C_ISECTS, and C_XFORMS, its rays; C_MATRICES its record's RW words), an instance's wide
  // batch (C_XFORMS: its steps, 2 per ray). Sums of two memories' counts are formed as they leave.
  localparam int INST_OBJ_WORDS = 17 + 14;  // trace.c's op_inst_xform: the instance's and object's words
  logic [63:0] cnt_walk, cnt_list, cnt_tri;
  logic [31:0] cnt_node, cnt_inst, cnt_xw;
  thread_count #(.THREADS(THREADS), .F(2)) u_cnt_walk (
    .clk_i(clk_i), .rst_ni(rst_ni), .clear_i(in_take), .clear_thread_i(thread_i),
    .add_i(trav_valid_o && trav_kind == 2'd3), .thread_i(trav_thread),
    .inc_i({32'(trav_leaf), 32'(!trav_leaf && (t_walk_read[trav_thread] || t_node_rsp[trav_thread]))}),
    .re_i(out_take), .rthread_i(out_sel), .count_o(cnt_walk));
  thread_count #(.THREADS(THREADS), .F(2)) u_cnt_list (
    .clk_i(clk_i), .rst_ni(rst_ni), .clear_i(in_take), .clear_thread_i(thread_i),
    .add_i(list_valid_o), .thread_i(list_thread),
    .inc_i({32'(list_skip[0]) + 32'(list_skip[1]) + 32'(list_skip[2]) + 32'(list_skip[3]), 32'd1}),
    .re_i(out_take), .rthread_i(out_sel), .count_o(cnt_list));
  thread_count #(.THREADS(THREADS), .F(1)) u_cnt_node (
    .clk_i(clk_i), .rst_ni(rst_ni), .clear_i(in_take), .clear_thread_i(thread_i),
    .add_i(node_rsp_valid_i), .thread_i(node_q[node_rd[TW-1:0]]), .inc_i(32'd2),
    .re_i(out_take), .rthread_i(out_sel), .count_o(cnt_node));
  thread_count #(.THREADS(THREADS), .F(1)) u_cnt_inst (
    .clk_i(clk_i), .rst_ni(rst_ni), .clear_i(in_take), .clear_thread_i(thread_i),
    .add_i(accept[U_ADD]), .thread_i(sel[U_ADD]), .inc_i(32'(INST_OBJ_WORDS)),
    .re_i(out_take), .rthread_i(out_sel), .count_o(cnt_inst));
  thread_count #(.THREADS(THREADS), .F(2)) u_cnt_tri (
    .clk_i(clk_i), .rst_ni(rst_ni), .clear_i(in_take), .clear_thread_i(thread_i),
    .add_i(accept[U_IS]), .thread_i(sel[U_IS]), .inc_i({32'(RW), 32'(issue_slots[U_IS])}),
    .re_i(out_take), .rthread_i(out_sel), .count_o(cnt_tri));
  thread_count #(.THREADS(THREADS), .F(1)) u_cnt_xw (
    .clk_i(clk_i), .rst_ni(rst_ni), .clear_i(in_take), .clear_thread_i(thread_i),
    .add_i(accept[U_XW]), .thread_i(sel[U_XW]), .inc_i(32'(issue_slots[U_XW])),
    .re_i(out_take), .rthread_i(out_sel), .count_o(cnt_xw));
  // trace_counters' order: steps, leaves, entries, skips, transformations, intersections, words
  // (nodes, lists, matrices, shading: none here)
  assign count_o = {32'd0, cnt_inst + cnt_tri[63:32], cnt_list[31:0], cnt_node, cnt_tri[31:0],
                    cnt_xw + cnt_tri[31:0], cnt_list[63:32], cnt_list[31:0], cnt_walk[63:32], cnt_walk[31:0]};

  // the count of waiting threads from their waiting_o registered, itself registered: the adder
  // tree over 64 threads after their waiting_o was 11 LUT6 levels to the port, 10 into one
  // register (tb_core's average counts it 2 cycles late)
  logic [THREADS-1:0] waiting_q;
  logic [TW:0] waiting_n;
  always_ff @(posedge clk_i) waiting_q <= t_waiting;
  always_comb begin
    waiting_n = '0;
    for (int t = 0; t < THREADS; t++) waiting_n = waiting_n + (TW+1)'(waiting_q[t]);
  end
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) inflight_o <= '0;
    else inflight_o <= waiting_n;
endmodule
