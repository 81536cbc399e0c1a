// trav_unit: the traversal unit's control with the per-thread stacks (paper section 3, Figure 2
// paths b and f; section 4: the stacks of 64 entries per thread in block RAM), the algorithm
// TRAV_STACK of hls/units/trav_unit.c (trav_scene_clip, trav_object_clip, trav_start, trav_walk)
// and hls/units/trav_stack.c (trav_stack_step, walker_split, walker_push, entry_rays) with the
// overflow path of hls/units/trav_restart.c, bit for bit. The other algorithms of the C unit
// (short stack, kd-restart, push-down, ropes, grids) have no RTL. One operation per transaction:
//   * kind 0, scene clip (trav_scene_clip): [tn_i, tf_i] = [tmin, tmax] of every ray against the
//     box box_i (6 words: lo x y z, hi x y z); the rays of mask_i (active) whose interval is not
//     empty leave in mask_o, their [tn, tf] in tn_o/tf_o (the other rays keep tn_i/tf_i).
//   * kind 1, object clip (trav_object_clip): the same from [tmin, best_t] = [tn_i, tf_i] for the
//     rays of mask_i (need); the others get [+Inf, 0].
//   * kind 2, start (trav_start): the walk of (thread_i, level_i) begins at node 0 of the tree at
//     word address nodes_i with the rays mask_i and intervals [tn_i, tf_i].
//   * kind 3, walk (trav_walk): one kd-tree entry of (thread_i, level_i) with the rays' o_i, d_i,
//     closest hits best_i and the rays still traced mask_i (alive): prune the rays whose hit lies
//     before the entry (the second read port of trav_stack_step: an entry left without rays is
//     dropped and the next popped and pruned in the same step), read the node's two words
//     (node_addr_o = nodes + 2 node), at a leaf report it (leaf_o; list_o when it has entries;
//     leaf_first_o, leaf_count_o, leaf_mask_o, leaf_tn_o), at an inner node split the rays
//     (trav_node) and push the far child of the packet's first ray; an entry used up is replaced
//     by the top of the stack; have_cur_o = 0 when the level is done. The walker state after the
//     step leaves with it: the current entry (node_o, mask_o, tn_o, tf_o), sp_o, lost_o,
//     restarted_o.
// Overflow (walker_push, trav_restart): a push onto a full stack drops its oldest entry and sets
// lost; the stack is circular (a top pointer modulo DEPTH and a count sp saturating at DEPTH), so
// dropping the oldest entry is overwriting it. A level that runs dry after a drop restarts from
// its root entry with each ray's interval from max(tn, t_exit) (trav_restart) and walks the
// restarted pass's rules (trav_restart_drop_done, the lead ray of walker_split). With TRAV_STACK
// t_exit stays where the walk started (trav_restart_leaf extends it for the short stacks only).
// State per thread and level (index {thread, level}): the current entry, sp, top, have_cur, lost,
// restarted, the tree's address, the root entry and t_exit in one memory of 2 THREADS words (one
// synchronous read, one write port); the stacks in two banks (even and odd slots) of THREADS
// DEPTH entries {node, mask, 4 tn, 4 tf} (AW + 4 + 8 W bits) each, one read and one write port
// each (block RAM): 2 x 64 x 64 x 228 bits of stack at the defaults (the prototype's 64 entries
// per thread). A step pops at most twice (the pruned entry's successor, the entry at the end),
// always the two entries below top: both are read at once, one from each bank.
// Structure: a linear pipeline, one operation entering per cycle, no per-operation state machine;
// each operation's context (operands, walker state, step results) flows down it:
//   A  input: taken unless an operation of the same thread and level is in flight (a bit per
//      {thread, level}; in the DynRTP a thread has one operation in flight anyway, and trace_core
//      sets ONE_PER_THREAD so that this is not checked) or SLOTS are;
//      a start's state is walker_init's, a clip's intervals trav_object_clip's. A start leaves
//      here: it reads no node and compares nothing, so its state and result are written from a
//      one-entry buffer in the next cycle in which Z writes none (nothing enters while that buffer
//      is full, so the pipeline drains and the start cannot starve)
//   B  walker state read; C  the stack's top two entries; the prune comparators of the current
//      entry and of the top one (best_t < tn), the restart's max(tn, t_exit), tn < tf and
//      best_t < tn, computed ahead in case the step ends in a restart (2 CMP stages, 20
//      comparators)
//   D  the prune's outcome (pop and the popped entry's prune), the node address; E into the
//      queue of operations and, if it reads a node, the queue of node requests (SLOTS each; the
//      responses, taken when they come, in a third)
//   N  into trav_node: the queue's head once its node's words are there (in request order); a
//      leaf ends its entry here. A clip takes 6 slots in a row, its 6 slab planes back to back
//      (a plane's distances depend only on the ray); trav_clip narrows its [n, f] from them in
//      hls/units order, an axis's step per 2 slots, the result beside trav_node's last slot's;
//      every other operation passes beside trav_node in one slot
//   X  a clip ends with its last plane (the rays outside its mask keep their interval); an
//      inner node's children; Y  the restarted pass's drop of done cells (8 comparators)
//   Z  walker_split's choice; the push (stack write) and the new current entry; the end: the
//      top of the stack (the first or second entry read in C), or the restart; the state written
//      back, the result into the output queue
// Results leave in the order they are made: different threads overtake each other where a node
// read waits or a start bypasses the pipeline. No stage stalls: the queues
// hold every operation in flight.
// Latency at the defaults (trav_node NODE = 21, CMP = 2), memory answering in the cycle after the
// request, nothing competing: walk step 38 (leaf, inner node or none), start 2 (36 when it went
// down the pipeline), clip 41: the walk step's path and its 5 more slots (151 when its planes came
// round through trav_node one after another; build/rtl/e7m16/tb_trav -n 0 on a room 16x12 capture
// at --threads-per-pipe 1, one operation in flight, 2026-11-28). Throughput: one operation per
// cycle at the input; trav_node takes one slot per cycle, a clip 6 of them: on the captured room
// frame (48x32, 64 threads, rtl/tb/tb_trav.cpp; make build/rtl/e7m16/tb_trav;
// build/rtl/e7m16/tb_trav -n 0 --capture DIR, 2026-11-25) 1.72 cycles per operation (1.71 with
// trav_clip, the same capture, 2026-11-28), a start 3.9 from offer to result (1.77 and 62.8 when starts went
// down the pipeline; bound from trav_node's slots: 1.50; the operation contexts it
// replaced: 10.28 with 4 of them, 1.56 with 32).
// Resources (synth_xilinx at e7m16, THREADS = 64, DEPTH = 64, SLOTS = 64; scripts/synth.py's
// flow, python3 scripts/synth.py --redo x:trav_unit:e7m16, 2026-11-25; with the start's bypass
// scripts/synth.py's xilinx('trav_unit', 7, 16)): 16144 LUT6 (+ 849 RAM64M of LUT RAM: the
// queues, 3396 LUTs), 3961 SRL, 25204 flip-flops, 0 DSP48E1, 120 RAMB18 (the walker states and
// the two stack banks), 1283 CARRY4; 8 LUT6 levels (the goal: at most 8; before the bypass 15839
// LUT6 and 24873 flip-flops, 8 levels; a bypass writing the start in the cycle it is taken had
// 11, the write enables then depending on the input's handshake; the unit of CTX = 4 contexts it
// replaced: 31180 LUT6, 18725 flip-flops, 11)
// Not synthesized again since trav_clip (2026-11-28: 12 comparators more; the round trip's
// register and its mux in front of N gone) but as below.
// The queues in block RAM (sync_fifo BLOCK_RAM = 1; 2026-11-29, THREADS = 64, ONE_PER_THREAD = 1,
// module by module as the DynRTP's: python3 scripts/synth.py --levels trav_unit THREADS=64
// ONE_PER_THREAD=1 --hier; python3 scripts/synth.py --ice40 trav_unit THREADS=64 ONE_PER_THREAD=1):
// 7-series 28,938 LUT6, 45,626 flip-flops, 195 RAMB18 (59 RAMB18E1, 68 RAMB36E1), no LUT RAM,
// 6 LUT6 levels; with the queues in LUT RAM (3c2e061) 26,134 LUT6 + 881 RAM64M (3,524 LUTs),
// 42,982 flip-flops, 120 RAMB18, 6 levels. iCE40 (synth_ice40 -dsp) 35,765 SB_LUT4, 95,785
// flip-flops, 658 SB_RAM40_4K (the queues 2,809, 2,720 and 166 of them; the f24_pipe delay lines
// 58,641 flip-flops); with the queues in LUT RAM, which the iCE40 builds from flip-flops and a
// 64-to-1 multiplexer per bit, about 165,000 SB_LUT4 and 262,000 flip-flops (the queues measured
// alone, the operations' 2124 bits from 64 and 413: sync_fifo.sv).
// Handshake: valid/ready at the operation input, the result output and the node read request
// (node_thread_o, node_level_o: whose node); the node response (node_rsp_valid_i with w0, w1) is
// taken when it comes, in request order.
module trav_unit #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int THREADS = 64,
  parameter int DEPTH = 64,       // TRACE_STACK: stack entries per thread and level (a power of 2)
  parameter int SLOTS = 64,       // operations in flight at most (a power of 2): the queues' depth
  // 1: the caller never offers an operation of a thread and level while one of them is in flight
  // (trace_core: a thread waits for its result), so ready_o does not look at thread_i and level_i;
  // their operand multiplexer stays off the path from the unit's ready to the caller's grant
  parameter bit ONE_PER_THREAD = 0,
  parameter int AW = 32,          // word addresses and node indices
  parameter int ADD_STAGES = 6,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  input  logic                        valid_i,
  output logic                        ready_o,
  input  logic [$clog2(THREADS)-1:0]  thread_i,
  input  logic                        level_i,
  input  logic [1:0]                  kind_i,     // 0 scene clip, 1 object clip, 2 start, 3 walk
  input  logic [4*3*(E+M+1)-1:0]      o_i,        // ray i: words 3i .. 3i+2 (x, y, z)
  input  logic [4*3*(E+M+1)-1:0]      d_i,
  input  logic [4*(E+M+1)-1:0]        tn_i,
  input  logic [4*(E+M+1)-1:0]        tf_i,
  input  logic [4*(E+M+1)-1:0]        best_i,
  input  logic [3:0]                  mask_i,
  input  logic [6*(E+M+1)-1:0]        box_i,
  input  logic [AW-1:0]               nodes_i,
  output logic                        node_req_valid_o,
  input  logic                        node_req_ready_i,
  output logic [AW-1:0]               node_addr_o,
  output logic [$clog2(THREADS)-1:0]  node_thread_o,  // whose node: routing, statistics
  output logic                        node_level_o,
  input  logic                        node_rsp_valid_i,
  input  logic [31:0]                 node_w0_i,
  input  logic [31:0]                 node_w1_i,
  output logic                        valid_o,
  input  logic                        ready_i,
  output logic [$clog2(THREADS)-1:0]  thread_o,
  output logic                        level_o,
  output logic [1:0]                  kind_o,
  output logic [3:0]                  mask_o,
  output logic [4*(E+M+1)-1:0]        tn_o,
  output logic [4*(E+M+1)-1:0]        tf_o,
  output logic [AW-1:0]               node_o,
  output logic                        have_cur_o,
  output logic                        leaf_o,
  output logic                        list_o,
  output logic [31:0]                 leaf_first_o,
  output logic [31:0]                 leaf_count_o,
  output logic [3:0]                  leaf_mask_o,
  output logic [4*(E+M+1)-1:0]        leaf_tn_o,
  output logic [$clog2(DEPTH+1)-1:0]  sp_o,
  output logic                        lost_o,
  output logic                        restarted_o
);
  localparam int W = 1 + E + M;
  localparam int TW = $clog2(THREADS);
  localparam int IW = TW + 1;                 // state index {thread, level}
  localparam int SPW = $clog2(DEPTH + 1);
  localparam int TPW = $clog2(DEPTH);
  localparam int ENW = AW + 4 + 8 * W;        // a stack entry {node, mask, tn, tf}
  localparam int STW = ENW + 3 + SPW + TPW + AW + 4 + 12 * W;
  localparam int NW = $clog2(SLOTS + 1);
  localparam int NODE_LATENCY = ADD_STAGES + DIV_STAGES + 2 * CMP_STAGES; // trav_node's
  localparam logic [1:0] K_OBJECT = 2'd1, K_START = 2'd2, K_WALK = 2'd3;
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] POS_INF = {1'b0, EMAX, {M{1'b0}}};
  if (DEPTH < 4 || (DEPTH & (DEPTH - 1)) != 0) begin : g_depth_check
    $error("trav_unit: DEPTH is a power of 2 and at least 4 (the circular stack's top pointer wraps; two banks)");
  end

  // An operation's context, the word that flows down the pipeline (fields LSB first). A clip keeps
  // its running interval [n, f] in the current entry's tn, tf and its interval before the box in
  // the root's (the walker state is unused by a clip); its result mask in the current entry's mask.
  localparam int O_LEAF_TN = 0;                 // at a leaf: the entry's tn, mask
  localparam int O_LEAF_MASK = O_LEAF_TN + 4 * W;
  localparam int O_W1 = O_LEAF_MASK + 4;         // the node's words
  localparam int O_W0 = O_W1 + 32;
  localparam int O_LIST = O_W0 + 32;             // a leaf with entries
  localparam int O_LEAF = O_LIST + 1;
  localparam int O_PASS = O_LEAF + 1;            // a clip's slab plane (0 .. 5)
  localparam int O_RST_MASK = O_PASS + 3;        // the restart's mask and tn, computed ahead
  localparam int O_RST_TN = O_RST_MASK + 4;
  localparam int O_NEED = O_RST_TN + 4 * W;      // the step reads a node
  localparam int O_POPPED = O_NEED + 1;          // the pruned entry was dropped and the next popped
  localparam int O_E2 = O_POPPED + 1;            // the stack's two top entries
  localparam int O_E1 = O_E2 + ENW;
  localparam int O_ST = O_E1 + ENW;              // the walker state (a word of the state memory)
  localparam int O_BOX = O_ST + STW;
  localparam int O_AMASK = O_BOX + 6 * W;        // mask_i: active, need or alive rays
  localparam int O_BEST = O_AMASK + 4;
  localparam int O_D = O_BEST + 4 * W;
  localparam int O_O = O_D + 12 * W;
  localparam int O_KIND = O_O + 12 * W;
  localparam int O_IDX = O_KIND + 2;
  localparam int CXW = O_IDX + IW;
  // the walker state's fields (as laid out in the state memory's word)
  localparam int S_TEXIT = O_ST;
  localparam int S_RTF = S_TEXIT + 4 * W;        // the root entry's tf, tn, mask
  localparam int S_RTN = S_RTF + 4 * W;
  localparam int S_RMASK = S_RTN + 4 * W;
  localparam int S_NODES = S_RMASK + 4;          // the tree's word address
  localparam int S_TOP = S_NODES + AW;
  localparam int S_SP = S_TOP + TPW;
  localparam int S_RESTARTED = S_SP + SPW;
  localparam int S_LOST = S_RESTARTED + 1;
  localparam int S_HAVE = S_LOST + 1;
  localparam int S_CUR = S_HAVE + 1;             // the current entry
  localparam int S_CTF = S_CUR;
  localparam int S_CTN = S_CUR + 4 * W;
  localparam int S_CMASK = S_CUR + 8 * W;
  localparam int S_CNODE = S_CUR + 8 * W + 4;
  // a stack entry's fields
  localparam int E_TN = 4 * W, E_MASK = 8 * W, E_NODE = 8 * W + 4;

  function automatic logic [W-1:0] lane(input logic [4*W-1:0] v, input int i);
    lane = v[i*W +: W];
  endfunction

  // ---- A: the input. An operation enters unless one of its thread and level is in flight (its
  // walker state is read here and written as its result is made; not checked with ONE_PER_THREAD)
  // or SLOTS operations are.
  logic [2*THREADS-1:0] busy;
  logic [NW-1:0] in_flight;
  logic take, out_pop;
  logic [IW-1:0] out_idx;
  // sb_valid: a start waits for the state memory's write port and the output queue (below); no
  // operation enters meanwhile, so the pipeline drains and the start cannot wait forever
  logic sb_valid;
  assign ready_o = (ONE_PER_THREAD || !busy[{thread_i, level_i}]) && in_flight != NW'(SLOTS) && !sb_valid;
  assign take = valid_i && ready_o;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      busy <= '0;
      in_flight <= '0;
    end else begin
      if (take) busy[{thread_i, level_i}] <= 1'b1;
      if (out_pop) busy[out_idx] <= 1'b0;
      in_flight <= in_flight + NW'(take) - NW'(out_pop);
    end
  end

  // the context as it enters: a start's walker state is walker_init's, a clip's intervals are
  // trav_object_clip's (the rays outside need get [+Inf, 0]); a walk's state comes from memory
  logic [4*W-1:0] cl_tn, cl_tf;
  logic [CXW-1:0] a_cx;
  always_comb begin
    for (int i = 0; i < 4; i++) begin
      cl_tn[i*W +: W] = kind_i == K_OBJECT && !mask_i[i] ? POS_INF : lane(tn_i, i);
      cl_tf[i*W +: W] = kind_i == K_OBJECT && !mask_i[i] ? '0 : lane(tf_i, i);
    end
    a_cx = '0;
    a_cx[O_IDX +: IW] = {thread_i, level_i};
    a_cx[O_KIND +: 2] = kind_i;
    a_cx[O_O +: 12 * W] = o_i;
    a_cx[O_D +: 12 * W] = d_i;
    a_cx[O_BEST +: 4 * W] = best_i;
    a_cx[O_AMASK +: 4] = mask_i;
    a_cx[O_BOX +: 6 * W] = box_i;
    if (kind_i == K_START)
      a_cx[O_ST +: STW] = {AW'(0), mask_i, tn_i, tf_i, 3'b100, SPW'(0), TPW'(0), nodes_i, mask_i, tn_i, tf_i, tn_i};
    else
      a_cx[O_ST +: STW] = {AW'(0), 4'h0, cl_tn, cl_tf, 3'b000, SPW'(0), TPW'(0), AW'(0), 4'h0, cl_tn, cl_tf, {(4*W){1'b0}}};
  end

  // ---- B: the walker state read (block RAM, one read and one write port); the stack's two top
  // entries are read from its two banks (even and odd slots), whichever the step will pop
  logic [STW-1:0] st_mem [2*THREADS];
  logic [STW-1:0] st_rd;
  logic st_we;
  logic [IW-1:0] st_wa;
  logic [STW-1:0] st_wd;
  logic b_valid;
  logic [CXW-1:0] b_cx, bx;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) b_valid <= 1'b0;
    else b_valid <= take && kind_i != K_START;
  end
  always_ff @(posedge clk_i) begin
    if (take) b_cx <= a_cx;
    if (take) st_rd <= st_mem[{thread_i, level_i}];
    if (st_we) st_mem[st_wa] <= st_wd;
  end
  always_comb begin
    bx = b_cx;
    if (b_cx[O_KIND +: 2] == K_WALK) bx[O_ST +: STW] = st_rd;
  end

  logic [ENW-1:0] stk_even [THREADS*DEPTH], stk_odd [THREADS*DEPTH];
  logic [ENW-1:0] stk_rd_even, stk_rd_odd;
  logic stk_we;
  logic [IW-1:0] stk_widx;
  logic [TPW-1:0] stk_wslot;
  logic [ENW-1:0] stk_wd;
  logic [TPW-1:0] b_s1;           // the slot of the top entry
  logic [TPW-2:0] b_s2;           // the bank address of the one below it (in the other bank)
  logic c_odd;                    // the top entry is in the odd bank
  assign b_s1 = bx[S_TOP +: TPW] - TPW'(1);
  assign b_s2 = b_s1[TPW-1:1] - (TPW - 1)'(!b_s1[0]);
  always_ff @(posedge clk_i) begin
    if (b_valid) begin
      stk_rd_even <= stk_even[{bx[O_IDX +: IW], b_s1[0] ? b_s2 : b_s1[TPW-1:1]}];
      stk_rd_odd <= stk_odd[{bx[O_IDX +: IW], b_s1[0] ? b_s1[TPW-1:1] : b_s2}];
      c_odd <= b_s1[0];
    end
    if (stk_we && !stk_wslot[0]) stk_even[{stk_widx, stk_wslot[TPW-1:1]}] <= stk_wd;
    if (stk_we && stk_wslot[0]) stk_odd[{stk_widx, stk_wslot[TPW-1:1]}] <= stk_wd;
  end

  // ---- C: the comparators that do not wait for the node: the prune of the current entry and of
  // the stack's top (entry_rays, the second read port of trav_stack_step), and the restart's
  // max(tn, t_exit), then its tn < tf and best_t < tn (trav_restart), in case the step needs it
  logic c_valid;
  logic [CXW-1:0] c_cx, cx, cx_mid, d_cx;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) c_valid <= 1'b0;
    else c_valid <= b_valid;
  end
  always_ff @(posedge clk_i) if (b_valid) c_cx <= bx;
  always_comb begin
    cx = c_cx;
    cx[O_E1 +: ENW] = c_odd ? stk_rd_odd : stk_rd_even;
    cx[O_E2 +: ENW] = c_odd ? stk_rd_even : stk_rd_odd;
  end
  logic mid_valid, d_valid;
  logic [3:0] p1_lt, p2_lt, p1_lt_d, p2_lt_d, r1_lt, r2_lt;
  logic [4*W-1:0] rmax, rmax_d;
  /* verilator lint_off PINCONNECTEMPTY */
  for (genvar i = 0; i < 4; i++) begin : g_front
    /* verilator lint_off UNUSEDSIGNAL */
    logic [3:0] f1, f2, f3, f4; // {unordered, eq, le, lt}: lt is used
    /* verilator lint_on UNUSEDSIGNAL */
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_p1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
      .a_i(lane(cx[O_BEST +: 4 * W], i)), .b_i(lane(cx[S_CTN +: 4 * W], i)), .valid_o(), .flags_o(f1), .min_o(),
      .max_o());
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_p2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
      .a_i(lane(cx[O_BEST +: 4 * W], i)), .b_i(lane(cx[O_E1 + E_TN +: 4 * W], i)), .valid_o(), .flags_o(f2),
      .min_o(), .max_o());
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_max (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
      .valid_i(1'b0), .a_i(lane(cx[S_RTN +: 4 * W], i)), .b_i(lane(cx[S_TEXIT +: 4 * W], i)), .valid_o(),
      .flags_o(), .min_o(), .max_o(rmax[i*W +: W]));
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_r1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
      .a_i(rmax[i*W +: W]), .b_i(lane(cx_mid[S_RTF +: 4 * W], i)), .valid_o(), .flags_o(f3), .min_o(), .max_o());
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_r2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
      .a_i(lane(cx_mid[O_BEST +: 4 * W], i)), .b_i(rmax[i*W +: W]), .valid_o(), .flags_o(f4), .min_o(), .max_o());
    assign p1_lt[i] = f1[0];
    assign p2_lt[i] = f2[0];
    assign r1_lt[i] = f3[0];
    assign r2_lt[i] = f4[0];
  end
  /* verilator lint_off UNUSEDSIGNAL */
  logic pr_valid; // the same as d_valid
  /* verilator lint_on UNUSEDSIGNAL */
  /* verilator lint_on PINCONNECTEMPTY */
  f24_pipe #(.W(CXW), .STAGES(CMP_STAGES)) u_c_mid (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(c_valid),
    .data_i(cx), .valid_o(mid_valid), .data_o(cx_mid));
  f24_pipe #(.W(CXW), .STAGES(CMP_STAGES)) u_c_d (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(mid_valid),
    .data_i(cx_mid), .valid_o(d_valid), .data_o(d_cx));
  f24_pipe #(.W(8 + 4 * W), .STAGES(CMP_STAGES)) u_p_d (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(mid_valid), .data_i({p1_lt, p2_lt, rmax}), .valid_o(pr_valid), .data_o({p1_lt_d, p2_lt_d, rmax_d}));

  // ---- D: the prune (an entry left without rays is dropped and the next popped: the stack's top,
  // pruned alongside), the node to read, the restart's outcome; E: into the queues
  logic [CXW-1:0] dx, e_cx;
  logic [AW-1:0] d_addr, e_addr;
  logic e_valid;
  always_comb begin
    logic [3:0] m1, m2;
    logic pop;
    dx = d_cx;
    m1 = d_cx[S_CMASK +: 4] & d_cx[O_AMASK +: 4] & ~p1_lt_d;
    m2 = d_cx[O_E1 + E_MASK +: 4] & d_cx[O_AMASK +: 4] & ~p2_lt_d;
    pop = m1 == 0 && d_cx[S_SP +: SPW] != 0;
    if (d_cx[O_KIND +: 2] == K_WALK) begin
      if (pop) begin
        dx[S_CUR +: ENW] = {d_cx[O_E1 + E_NODE +: AW], m2, d_cx[O_E1 +: 8 * W]};
        dx[S_SP +: SPW] = d_cx[S_SP +: SPW] - SPW'(1);
        dx[S_TOP +: TPW] = d_cx[S_TOP +: TPW] - TPW'(1);
      end else begin
        dx[S_CMASK +: 4] = m1;
      end
      dx[O_POPPED] = pop;
      dx[S_RMASK +: 4] = d_cx[S_RMASK +: 4] & d_cx[O_AMASK +: 4];
      dx[O_NEED] = dx[S_CMASK +: 4] != 0;
      dx[S_HAVE] = d_cx[S_HAVE] && dx[O_NEED];
      // trav_restart: the rays with something left whose hit does not lie before it
      dx[O_RST_MASK +: 4] = dx[S_RMASK +: 4] & r1_lt & ~r2_lt;
      dx[O_RST_TN +: 4 * W] = rmax_d;
    end
    d_addr = dx[S_NODES +: AW] + (dx[S_CNODE +: AW] << 1);
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) e_valid <= 1'b0;
    else e_valid <= d_valid;
  end
  always_ff @(posedge clk_i) begin
    if (d_valid) begin
      e_cx <= dx;
      e_addr <= d_addr;
    end
  end

  // the queues, each of SLOTS entries (as many as operations in flight: they never refuse): the
  // operations in order, their node read requests, the node responses (taken when they come); in
  // block RAM (sync_fifo's BLOCK_RAM form, the same cycles: 136 kbit for the operations alone at the
  // defaults, which the iCE40, without LUT RAM, would build from flip-flops and multiplexers)
  logic q_valid, q_pop, rsp_valid, rsp_pop;
  logic [CXW-1:0] q_cx;
  logic [63:0] rsp;
  /* verilator lint_off PINCONNECTEMPTY */
  sync_fifo #(.W(CXW), .DEPTH(SLOTS), .BLOCK_RAM(1'b1)) u_queue (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(e_valid), .ready_o(),
    .data_i(e_cx), .valid_o(q_valid), .ready_i(q_pop), .data_o(q_cx));
  sync_fifo #(.W(AW + IW), .DEPTH(SLOTS), .BLOCK_RAM(1'b1)) u_req (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(e_valid && e_cx[O_NEED]),
    .ready_o(), .data_i({e_addr, e_cx[O_IDX +: IW]}), .valid_o(node_req_valid_o), .ready_i(node_req_ready_i),
    .data_o({node_addr_o, node_thread_o, node_level_o}));
  sync_fifo #(.W(64), .DEPTH(SLOTS), .BLOCK_RAM(1'b1)) u_rsp (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(node_rsp_valid_i), .ready_o(),
    .data_i({node_w1_i, node_w0_i}), .valid_o(rsp_valid), .ready_i(rsp_pop), .data_o(rsp));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- N: into the per-node datapath, one operation per cycle: the queue's head once its node's
  // words are there; a clip takes 6 slots in a row, its slab planes one after another, and leaves
  // the queue with the last. A leaf ends the entry here; an inner node and a clip's planes pass
  // trav_node, the other operations beside it. trav_clip narrows the clip's [n, f] from the
  // planes' distances in hls/units order (the chain's step per axis is the only dependency).
  logic n_valid, n_go, g_valid, g_go, g_clip, n_clip;
  logic [2:0] n_pass;             // the head clip's next plane
  logic n_last;                   // n_pass == 5, registered (the queue's pop stays one LUT level)
  logic [CXW-1:0] nx, g_cx;
  logic [1:0] n_axis, g_axis;
  logic [W-1:0] n_split, g_split;
  logic [3:0] n_mask, g_mask;
  assign n_clip = !q_cx[O_KIND + 1];
  assign n_valid = q_valid && (!q_cx[O_NEED] || rsp_valid);
  assign q_pop = n_valid && (!n_clip || n_last);
  assign rsp_pop = q_pop && q_cx[O_NEED];
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) {n_pass, n_last} <= '0;
    else if (n_valid && n_clip) {n_pass, n_last} <= n_last ? 4'b0000 : {n_pass + 3'd1, n_pass == 3'd4};
  end
  always_comb begin
    nx = q_cx;
    if (n_clip) nx[O_PASS +: 3] = n_pass;
    if (q_cx[O_NEED]) begin
      nx[O_W0 +: 32] = rsp[31:0];
      nx[O_W1 +: 32] = rsp[63:32];
      if (rsp[1:0] == 2'd3) begin        // a leaf: its list range and rays
        nx[S_HAVE] = 1'b0;
        nx[O_LEAF] = 1'b1;
        nx[O_LIST] = rsp[31:2] != 0;
        nx[O_LEAF_MASK +: 4] = q_cx[S_CMASK +: 4];
        nx[O_LEAF_TN +: 4 * W] = q_cx[S_CTN +: 4 * W];
      end
    end
    n_go = n_clip || (nx[O_NEED] && !nx[O_LEAF]);
    n_axis = n_clip ? n_pass[2:1] : nx[O_W0 +: 2];
    // the plane's word by a 6-way select on constant offsets (a variable offset times W became a
    // multiplier and a shifter)
    n_split = nx[O_W1 +: W];
    for (int k = 0; k < 6; k++)
      if (n_clip && {n_pass[0], n_pass[2:1]} == (k < 3 ? {1'b0, 2'(k)} : {1'b1, 2'(k - 3)}))
        n_split = q_cx[O_BOX + k * W +: W];
    n_mask = n_clip ? 4'hF : nx[S_CMASK +: 4];
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) {g_valid, g_go, g_clip} <= '0;
    else {g_valid, g_go, g_clip} <= {n_valid, n_valid && n_go, n_valid && n_clip};
  end
  always_ff @(posedge clk_i) begin
    if (n_valid) begin
      g_cx <= nx;
      g_axis <= n_axis;
      g_split <= n_split;
      g_mask <= n_mask;
    end
  end

  logic x_valid;
  logic [3:0] nd_l_mask, nd_r_mask, nd_near_left;
  logic [4*W-1:0] nd_l_tn, nd_l_tf, nd_r_tn, nd_r_tf, nd_ts, nd_tn_q, nd_tf_q;
  logic [CXW-1:0] x_cx;
  /* verilator lint_off PINCONNECTEMPTY */
  trav_node #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES)) u_node (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(g_go), .ready_o(), .axis_i(g_axis), .split_i(g_split),
    .mask_i(g_mask), .o_i(g_cx[O_O +: 12 * W]), .d_i(g_cx[O_D +: 12 * W]), .tn_i(g_cx[S_CTN +: 4 * W]),
    .tf_i(g_cx[S_CTF +: 4 * W]), .valid_o(), .ready_i(1'b1), .l_mask_o(nd_l_mask), .r_mask_o(nd_r_mask),
    .near_left_o(nd_near_left), .l_tn_o(nd_l_tn), .l_tf_o(nd_l_tf), .r_tn_o(nd_r_tn), .r_tf_o(nd_r_tf),
    .ts_o(nd_ts), .tn_q_o(nd_tn_q), .tf_q_o(nd_tf_q));
  /* verilator lint_on PINCONNECTEMPTY */
  f24_pipe #(.W(CXW), .STAGES(NODE_LATENCY)) u_beside (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(g_valid), .data_i(g_cx), .valid_o(x_valid), .data_o(x_cx));
  // a clip plane's pass and the sign bits of the rays' direction on its axis, to the distances
  logic [3:0] g_neg, t_neg;
  logic [2:0] t_pass;
  logic t_clip;
  always_comb
    for (int i = 0; i < 4; i++)
      g_neg[i] = g_axis == 2'd0 ? g_cx[O_D + (3 * i + 1) * W - 1] : g_axis == 2'd1 ? g_cx[O_D + (3 * i + 2) * W - 1]
               : g_cx[O_D + (3 * i + 3) * W - 1];
  f24_pipe #(.W(7), .STAGES(ADD_STAGES + DIV_STAGES)) u_clip_d (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(g_clip), .data_i({g_cx[O_PASS +: 3], g_neg}), .valid_o(t_clip), .data_o({t_pass, t_neg}));
  logic [4*W-1:0] cl_n, cl_f;
  logic [3:0] cl_le;
  trav_clip #(.E(E), .M(M), .CMP_STAGES(CMP_STAGES)) u_clip (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(t_clip),
    .pass_i(t_pass), .neg_i(t_neg), .ts_i(nd_ts), .tn_i(nd_tn_q), .tf_i(nd_tf_q), .tn_o(cl_n), .tf_o(cl_f),
    .le_o(cl_le));

  // ---- X: a clip ends with its last plane (its earlier slots end here; the rays outside the
  // clip's mask keep their interval); an inner node's children (a side that is an empty leaf is
  // not stored)
  logic x_clip, x_drop, y_valid;
  logic [CXW-1:0] xx, y_cx;
  logic [ENW-1:0] x_l, x_r, y_l, y_r;
  logic [3:0] y_near_left;
  assign x_clip = !x_cx[O_KIND + 1];
  assign x_drop = x_clip && x_cx[O_PASS +: 3] != 3'd5;
  always_comb begin
    logic [31:0] w0;
    w0 = x_cx[O_W0 +: 32];
    xx = x_cx;
    x_l = {AW'(w0 >> 4), nd_l_mask & {4{!w0[2]}}, nd_l_tn, nd_l_tf};
    x_r = {AW'(w0 >> 4) + AW'(!w0[2]), nd_r_mask & {4{!w0[3]}}, nd_r_tn, nd_r_tf};
    if (x_clip) begin
      for (int i = 0; i < 4; i++) begin
        xx[S_CTN + i * W +: W] = x_cx[O_AMASK + i] ? lane(cl_n, i) : lane(x_cx[S_RTN +: 4 * W], i);
        xx[S_CTF + i * W +: W] = x_cx[O_AMASK + i] ? lane(cl_f, i) : lane(x_cx[S_RTF +: 4 * W], i);
      end
      xx[S_CMASK +: 4] = cl_le & x_cx[O_AMASK +: 4];
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) y_valid <= 1'b0;
    else y_valid <= x_valid && !x_drop;
  end
  always_ff @(posedge clk_i) begin
    if (x_valid) begin
      y_cx <= xx;
      y_l <= x_l;
      y_r <= x_r;
      y_near_left <= nd_near_left;
    end
  end

  // ---- Y: in a restarted pass, the cells that end at t_exit are done (trav_restart_drop_done)
  logic [7:0] y_le;
  /* verilator lint_off PINCONNECTEMPTY */
  for (genvar i = 0; i < 4; i++) begin : g_drop
    /* verilator lint_off UNUSEDSIGNAL */
    logic [3:0] fl, fr; // {unordered, eq, le, lt}: le is used
    /* verilator lint_on UNUSEDSIGNAL */
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_l (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
      .a_i(lane(y_l[0 +: 4 * W], i)), .b_i(lane(y_cx[S_TEXIT +: 4 * W], i)), .valid_o(), .flags_o(fl), .min_o(),
      .max_o());
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_r (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
      .a_i(lane(y_r[0 +: 4 * W], i)), .b_i(lane(y_cx[S_TEXIT +: 4 * W], i)), .valid_o(), .flags_o(fr), .min_o(),
      .max_o());
    assign y_le[i] = fl[1];
    assign y_le[4+i] = fr[1];
  end
  /* verilator lint_on PINCONNECTEMPTY */
  logic z_valid;
  logic [CXW-1:0] z_cx;
  logic [ENW-1:0] z_l, z_r;
  logic [3:0] z_near_left;
  f24_pipe #(.W(CXW + 2 * ENW + 4), .STAGES(CMP_STAGES)) u_y_z (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
    .valid_i(y_valid), .data_i({y_cx, y_l, y_r, y_near_left}), .valid_o(z_valid),
    .data_o({z_cx, z_l, z_r, z_near_left}));

  // ---- Z: walker_split's choice (the lead ray, its near side, the far child to push), then the
  // push (a full stack drops its oldest entry: the stack is circular, top modulo DEPTH, sp
  // saturating at DEPTH, and lost is set), then the entry's end (trav_stack_step's tail)
  logic z2_both, z2_first_near_left;
  logic [ENW-1:0] z2_l, z2_r;
  always_comb begin
    logic restarted;
    logic [2:0] lead;                 // a fourth ray leads when none of the others does
    logic [1:0] first;
    restarted = z_cx[S_RESTARTED];
    z2_l = z_l;
    z2_r = z_r;
    if (restarted) begin
      z2_l[E_MASK +: 4] = z_l[E_MASK +: 4] & ~y_le[3:0];
      z2_r[E_MASK +: 4] = z_r[E_MASK +: 4] & ~y_le[7:4];
    end
    lead = restarted ? z2_l[E_MASK +: 3] | z2_r[E_MASK +: 3] : z_cx[S_CMASK +: 3];
    first = lead[0] ? 2'd0 : lead[1] ? 2'd1 : lead[2] ? 2'd2 : 2'd3;
    z2_first_near_left = z_near_left[first];
    if (restarted && !(z2_first_near_left ? z2_l[E_MASK + 32'(first)] : z2_r[E_MASK + 32'(first)]))
      z2_first_near_left = !z2_first_near_left;
    z2_both = z2_l[E_MASK +: 4] != 0 && z2_r[E_MASK +: 4] != 0;
  end
  logic z3_valid, z3_both, z3_first_near_left;
  logic [CXW-1:0] z3_cx;
  logic [ENW-1:0] z3_l, z3_r;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) z3_valid <= 1'b0;
    else z3_valid <= z_valid;
  end
  always_ff @(posedge clk_i) begin
    if (z_valid) begin
      {z3_cx, z3_l, z3_r, z3_both, z3_first_near_left} <= {z_cx, z2_l, z2_r, z2_both, z2_first_near_left};
    end
  end
  logic z3_inner;
  logic [CXW-1:0] z3x;
  assign z3_inner = z3_cx[O_KIND +: 2] == K_WALK && z3_cx[O_NEED] && !z3_cx[O_LEAF];
  assign stk_we = z3_valid && z3_inner && z3_both;
  assign stk_widx = z3_cx[O_IDX +: IW];
  assign stk_wslot = z3_cx[S_TOP +: TPW];
  assign stk_wd = z3_first_near_left ? z3_r : z3_l;
  always_comb begin
    z3x = z3_cx;
    if (z3_inner) begin
      if (!z3_both) begin
        z3x[S_CUR +: ENW] = z3_l[E_MASK +: 4] != 0 ? z3_l : z3_r;
      end else begin
        z3x[S_TOP +: TPW] = z3_cx[S_TOP +: TPW] + TPW'(1);
        if (z3_cx[S_SP +: SPW] == SPW'(DEPTH)) z3x[S_LOST] = 1'b1;
        else z3x[S_SP +: SPW] = z3_cx[S_SP +: SPW] + SPW'(1);
        z3x[S_CUR +: ENW] = z3_first_near_left ? z3_l : z3_r;
      end
    end
  end
  logic z4_valid;
  logic [CXW-1:0] z4_cx, z4x;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) z4_valid <= 1'b0;
    else z4_valid <= z3_valid;
  end
  always_ff @(posedge clk_i) if (z3_valid) z4_cx <= z3x;
  // the end: an entry used up is replaced by the top of the stack (the first of the two read if
  // nothing was popped before, else the second; no entry was pushed, which keeps the current
  // one), or after a drop the level restarts from its root entry with tn = t_exit = max(tn, t_exit)
  always_comb begin
    z4x = z4_cx;
    if (z4_cx[O_KIND +: 2] == K_WALK && !z4_cx[S_HAVE]) begin
      if (z4_cx[S_SP +: SPW] != 0) begin
        z4x[S_CUR +: ENW] = z4_cx[O_POPPED] ? z4_cx[O_E2 +: ENW] : z4_cx[O_E1 +: ENW];
        z4x[S_SP +: SPW] = z4_cx[S_SP +: SPW] - SPW'(1);
        z4x[S_TOP +: TPW] = z4_cx[S_TOP +: TPW] - TPW'(1);
        z4x[S_HAVE] = 1'b1;
      end else if (z4_cx[S_LOST]) begin
        z4x[S_CUR +: ENW] = {AW'(0), z4_cx[O_RST_MASK +: 4], z4_cx[O_RST_TN +: 4 * W], z4_cx[S_RTF +: 4 * W]};
        z4x[S_RMASK +: 4] = z4_cx[O_RST_MASK +: 4];
        z4x[S_TEXIT +: 4 * W] = z4_cx[O_RST_TN +: 4 * W];
        z4x[S_HAVE] = z4_cx[O_RST_MASK +: 4] != 0;
        z4x[S_LOST] = 1'b0;
        z4x[S_RESTARTED] = 1'b1;
      end
    end
  end

  // ---- a start bypasses the pipeline: it reads no node and compares nothing, its walker state
  // (walker_init's, made at A) and its result are all there as it enters. It goes into sb (one
  // entry, a register, so that the state memory's and the output queue's write enables come from
  // registers) and writes them from there in the first cycle the pipeline's end (Z4) does not;
  // while sb is full nothing enters (ready_o), so Z4 runs dry. The busy bit of its {thread,
  // level} keeps the next operation of that walk out until the result has left, so that
  // operation reads the state the start wrote.
  logic s_go;
  logic [CXW-1:0] sb_cx;
  assign s_go = sb_valid && !z4_valid;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) sb_valid <= 1'b0;
    else sb_valid <= (take && kind_i == K_START) || (sb_valid && z4_valid);
  end
  always_ff @(posedge clk_i) if (take && kind_i == K_START) sb_cx <= a_cx;

  // ---- the result: the walker state written back (a walk's at Z4, a start's from sb), the
  // result into the output queue (results leave in the order they are made: operations of
  // different threads overtake each other where a node read waits or a start bypasses the
  // pipeline)
  localparam int RW = IW + 2 + ENW + 3 + 64 + 4 + 4 * W + SPW + 2;
  logic [RW-1:0] out_d, out_q;
  logic [CXW-1:0] r_cx;          // the context whose result is written: Z4's, else the start's
  assign r_cx = z4_valid ? z4x : sb_cx;
  assign st_we = (z4_valid && z4_cx[O_KIND + 1]) || s_go;
  assign st_wa = r_cx[O_IDX +: IW];
  assign st_wd = r_cx[O_ST +: STW];
  assign out_d = {r_cx[O_IDX +: IW], r_cx[O_KIND +: 2], r_cx[S_CUR +: ENW], r_cx[S_HAVE], r_cx[O_LEAF],
                  r_cx[O_LIST], r_cx[O_W1 +: 32], r_cx[O_W0 +: 32], r_cx[O_LEAF_MASK +: 4],
                  r_cx[O_LEAF_TN +: 4 * W], r_cx[S_SP +: SPW], r_cx[S_LOST], r_cx[S_RESTARTED]};
  /* verilator lint_off PINCONNECTEMPTY */
  sync_fifo #(.W(RW), .DEPTH(SLOTS), .BLOCK_RAM(1'b1)) u_out (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(z4_valid || s_go), .ready_o(),
    .data_i(out_d), .valid_o(valid_o), .ready_i(ready_i), .data_o(out_q));
  /* verilator lint_on PINCONNECTEMPTY */
  /* verilator lint_off UNUSEDSIGNAL */
  logic [1:0] out_w0_type; // the node word's type bits (a leaf's)
  /* verilator lint_on UNUSEDSIGNAL */
  assign {out_idx, kind_o, node_o, mask_o, tn_o, tf_o, have_cur_o, leaf_o, list_o, leaf_first_o, leaf_count_o[29:0],
          out_w0_type, leaf_mask_o, leaf_tn_o, sp_o, lost_o, restarted_o} = out_q;
  assign leaf_count_o[31:30] = 2'b00;
  assign {thread_o, level_o} = out_idx;
  assign out_pop = valid_o && ready_i;
endmodule
