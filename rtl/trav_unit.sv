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
// restarted, the tree's address, the root entry and t_exit in one memory of 2 THREADS words; the
// stacks in one memory of 2 THREADS DEPTH entries {node, mask, 4 tn, 4 tf} (AW + 4 + 8 W bits),
// both with one synchronous read and one write port (block RAM): 2 x 64 x 64 x 228 bits of stack
// at the defaults (the prototype's 64 entries per thread in block RAM).
// Structure: CTX operation contexts (trav_ctx: the FSM of one operation with its operands, the
// walker state while it runs and 8 comparators) share one trav_node (4 sub, 4 div, 4 min, 4 max,
// 8 comparators: the split of a walk step, and a clip's 6 slab planes in turn), the state
// memory (read as an operation enters, written as its result leaves), the stack memory's read and
// write ports, the node read port and the result output. An operation enters a free context
// unless an operation of the same thread and level is in flight (in the DynRTP a thread has one
// operation in flight anyway); results leave as they are done, so operations of different threads
// may overtake each other. Each shared resource serves its requesting contexts round robin (a
// context waits at most CTX - 1 grants); node responses return in request order.
// Latency per operation (trav_ctx: walk step 33 cycles at an inner node, 9 at a leaf, clip 140,
// start 1, when no other context competes; the granted operands wait one cycle in stage G before
// trav_node); throughput up to CTX operations per latency, at most one trav_node issue per cycle
// (a walk step at an inner node takes one, a clip six). On the captured room frame (48x32, 64
// threads, rtl/tb/tb_trav.cpp) 10.28 cycles per operation with CTX = 4 (before stage G: 39.4 with
// CTX = 1, 9.95 with 4, 2.65 with 16, 1.56 with 32; bound: 1.33, the trav_node issues).
// Resources (synth_xilinx at e7m16, THREADS = 64, DEPTH = 64, CTX = 4; scripts/synth.py's flow):
// 31180 LUT6, 458 SRL, 18725 flip-flops, 7 DSP48E1, 120 RAMB18 (the walker states and the stacks);
// 11 LUT6 levels (14 before stage G).
// Handshake: valid/ready at the operation input, the result output and the node read request
// (node_thread_o, node_level_o: whose node); the node response (node_rsp_valid_i with w0, w1) is
// taken when it comes, in request order.
module trav_unit #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int THREADS = 64,
  parameter int DEPTH = 64,       // TRACE_STACK: stack entries per thread and level (a power of 2)
  parameter int CTX = 4,          // operations in flight (of different threads or levels)
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
  localparam int CW = CTX > 1 ? $clog2(CTX) : 1;
  localparam int NODE_LATENCY = ADD_STAGES + DIV_STAGES + 2 * CMP_STAGES; // trav_node's
  if (DEPTH < 2 || (DEPTH & (DEPTH - 1)) != 0) begin : g_depth_check
    $error("trav_unit: DEPTH is a power of 2 (the circular stack's top pointer wraps)");
  end

  // memories: the walker state and the stacks
  logic [STW-1:0] st_mem [2*THREADS];
  logic [ENW-1:0] stk_mem [2*THREADS*DEPTH];
  logic [STW-1:0] st_rd;
  logic [ENW-1:0] stk_rd;

  // the contexts' requests and results
  logic [CTX-1:0] busy, start, node_req, node_grant, node_done, stk_rd_req, stk_rd_grant, stk_wr_req, stk_wr_grant;
  logic [CTX-1:0] mem_req, mem_grant, mem_rsp, out_valid, out_grant, c_write_back, c_have_cur, c_leaf, c_list;
  logic [CTX-1:0] c_lost, c_restarted;
  logic [IW-1:0] c_idx [CTX];
  logic [1:0] c_axis [CTX], c_kind [CTX];
  logic [W-1:0] c_split [CTX];
  logic [3:0] c_node_mask [CTX], c_mask [CTX], c_leaf_mask [CTX];
  logic [4*3*W-1:0] c_o [CTX], c_d [CTX];
  logic [4*W-1:0] c_node_tn [CTX], c_node_tf [CTX], c_tn [CTX], c_tf [CTX], c_leaf_tn [CTX];
  logic [IW+TPW-1:0] c_stk_rd_addr [CTX], c_stk_wr_addr [CTX];
  logic [ENW-1:0] c_stk_wr_data [CTX];
  logic [AW-1:0] c_mem_addr [CTX], c_node [CTX];
  logic [STW-1:0] c_state [CTX];
  logic [31:0] c_leaf_first [CTX], c_leaf_count [CTX];
  logic [SPW-1:0] c_sp [CTX];

  // the shared per-node datapath and its results
  logic node_go, node_valid;
  /* verilator lint_off UNUSEDSIGNAL */
  logic tag_valid; // the same as node_valid
  /* verilator lint_on UNUSEDSIGNAL */
  logic [CW-1:0] node_sel, tag, stk_rd_sel, stk_wr_sel, mem_sel, out_sel;
  logic [3:0] nd_l_mask, nd_r_mask, nd_near_left;
  logic [4*W-1:0] nd_l_tn, nd_l_tf, nd_r_tn, nd_r_tf;

  for (genvar c = 0; c < CTX; c++) begin : g_ctx
    assign node_grant[c] = node_go && node_sel == CW'(c);
    assign node_done[c] = node_valid && tag == CW'(c);
    trav_ctx #(.E(E), .M(M), .IW(IW), .DEPTH(DEPTH), .AW(AW), .CMP_STAGES(CMP_STAGES)) u_ctx (
      .clk_i(clk_i), .rst_ni(rst_ni), .start_i(start[c]), .idx_i({thread_i, level_i}), .kind_i(kind_i), .o_i(o_i),
      .d_i(d_i), .tn_i(tn_i), .tf_i(tf_i), .best_i(best_i), .mask_i(mask_i), .box_i(box_i), .nodes_i(nodes_i),
      .state_i(st_rd), .busy_o(busy[c]), .idx_o(c_idx[c]),
      .node_req_o(node_req[c]), .node_grant_i(node_grant[c]), .node_axis_o(c_axis[c]), .node_split_o(c_split[c]),
      .node_mask_o(c_node_mask[c]), .node_o_o(c_o[c]), .node_d_o(c_d[c]), .node_tn_o(c_node_tn[c]),
      .node_tf_o(c_node_tf[c]), .node_done_i(node_done[c]), .nd_l_mask_i(nd_l_mask), .nd_r_mask_i(nd_r_mask),
      .nd_near_left_i(nd_near_left), .nd_l_tn_i(nd_l_tn), .nd_l_tf_i(nd_l_tf), .nd_r_tn_i(nd_r_tn), .nd_r_tf_i(nd_r_tf),
      .stk_rd_req_o(stk_rd_req[c]), .stk_rd_addr_o(c_stk_rd_addr[c]), .stk_rd_grant_i(stk_rd_grant[c]),
      .stk_rd_data_i(stk_rd), .stk_wr_req_o(stk_wr_req[c]), .stk_wr_addr_o(c_stk_wr_addr[c]),
      .stk_wr_data_o(c_stk_wr_data[c]), .stk_wr_grant_i(stk_wr_grant[c]),
      .mem_req_o(mem_req[c]), .mem_addr_o(c_mem_addr[c]), .mem_grant_i(mem_grant[c]), .mem_rsp_i(mem_rsp[c]),
      .mem_w0_i(node_w0_i), .mem_w1_i(node_w1_i),
      .out_valid_o(out_valid[c]), .out_grant_i(out_grant[c]), .state_o(c_state[c]), .write_back_o(c_write_back[c]),
      .kind_o(c_kind[c]), .mask_o(c_mask[c]), .tn_o(c_tn[c]), .tf_o(c_tf[c]), .node_o(c_node[c]),
      .have_cur_o(c_have_cur[c]), .leaf_o(c_leaf[c]), .list_o(c_list[c]), .leaf_first_o(c_leaf_first[c]),
      .leaf_count_o(c_leaf_count[c]), .leaf_mask_o(c_leaf_mask[c]), .leaf_tn_o(c_leaf_tn[c]), .sp_o(c_sp[c]),
      .lost_o(c_lost[c]), .restarted_o(c_restarted[c]));
  end

  // round robin: the first requesting context from `from` on (from = the one after the last
  // served), so that no context waits more than CTX - 1 grants
  function automatic logic [CW-1:0] pick(input logic [CTX-1:0] req, input logic [CW-1:0] from);
    pick = from;
    for (int k = CTX - 1; k >= 0; k--)
      if (req[(32'(from) + k) % CTX]) pick = CW'((32'(from) + k) % CTX);
  endfunction
  function automatic logic [CW-1:0] after(input logic [CW-1:0] c);
    after = c == CW'(CTX - 1) ? '0 : c + CW'(1);
  endfunction
  logic [CW-1:0] rr_node, rr_rd, rr_wr, rr_mem, rr_out;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) {rr_node, rr_rd, rr_wr, rr_mem, rr_out} <= '0;
    else begin
      if (node_go) rr_node <= after(node_sel);
      if (stk_rd_req != 0) rr_rd <= after(stk_rd_sel);
      if (stk_wr_req != 0) rr_wr <= after(stk_wr_sel);
      if (node_req_valid_o && node_req_ready_i) rr_mem <= after(mem_sel);
      if (valid_o && ready_i) rr_out <= after(out_sel);
    end
  end

  // input: into a free context, unless an operation of the same thread and level is in flight
  logic take, hazard;
  logic [CW-1:0] acc;
  always_comb begin
    hazard = 1'b0;
    for (int c = 0; c < CTX; c++) hazard = hazard | (busy[c] && c_idx[c] == {thread_i, level_i});
  end
  assign acc = pick(~busy, '0);
  assign ready_o = busy != '1 && !hazard;
  assign take = valid_i && ready_o;
  for (genvar c = 0; c < CTX; c++) begin : g_start
    assign start[c] = take && acc == CW'(c);
  end

  // the per-node datapath: one context's node or clip plane per cycle, its tag beside it. The
  // granted context's operands are registered before trav_node (stage G): the arbitration and
  // the operand choice (the context's state, plane and node words) would otherwise share a cycle
  // with trav_node's first segment (14 LUT6 levels; docs/synth.md).
  assign node_go = node_req != 0;
  assign node_sel = pick(node_req, rr_node);
  logic g_valid;
  logic [CW-1:0] g_sel;
  logic [1:0] g_axis;
  logic [W-1:0] g_split;
  logic [3:0] g_mask;
  logic [4*3*W-1:0] g_o, g_d;
  logic [4*W-1:0] g_tn, g_tf;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) g_valid <= 1'b0;
    else g_valid <= node_go;
  end
  always_ff @(posedge clk_i) begin
    if (node_go) begin
      g_sel <= node_sel;
      g_axis <= c_axis[node_sel];
      g_split <= c_split[node_sel];
      g_mask <= c_node_mask[node_sel];
      g_o <= c_o[node_sel];
      g_d <= c_d[node_sel];
      g_tn <= c_node_tn[node_sel];
      g_tf <= c_node_tf[node_sel];
    end
  end
  /* verilator lint_off PINCONNECTEMPTY */
  trav_node #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES)) u_node (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(g_valid), .ready_o(), .axis_i(g_axis), .split_i(g_split),
    .mask_i(g_mask), .o_i(g_o), .d_i(g_d), .tn_i(g_tn), .tf_i(g_tf), .valid_o(node_valid), .ready_i(1'b1),
    .l_mask_o(nd_l_mask), .r_mask_o(nd_r_mask), .near_left_o(nd_near_left), .l_tn_o(nd_l_tn), .l_tf_o(nd_l_tf),
    .r_tn_o(nd_r_tn), .r_tf_o(nd_r_tf));
  /* verilator lint_on PINCONNECTEMPTY */
  f24_pipe #(.W(CW), .STAGES(NODE_LATENCY)) u_tag (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(g_valid),
    .data_i(g_sel), .valid_o(tag_valid), .data_o(tag));

  // the state memory: read as an operation enters (its context loads it a cycle later), written
  // as the result of a start or walk leaves
  always_ff @(posedge clk_i) begin
    if (take) st_rd <= st_mem[{thread_i, level_i}];
    if (valid_o && ready_i && c_write_back[out_sel]) st_mem[c_idx[out_sel]] <= c_state[out_sel];
  end

  // the stack memory: one read and one write per cycle
  assign stk_rd_sel = pick(stk_rd_req, rr_rd);
  assign stk_wr_sel = pick(stk_wr_req, rr_wr);
  for (genvar c = 0; c < CTX; c++) begin : g_stk
    assign stk_rd_grant[c] = stk_rd_req[c] && stk_rd_sel == CW'(c);
    assign stk_wr_grant[c] = stk_wr_req[c] && stk_wr_sel == CW'(c);
  end
  always_ff @(posedge clk_i) begin
    if (stk_rd_req != 0) stk_rd <= stk_mem[c_stk_rd_addr[stk_rd_sel]];
    if (stk_wr_req != 0) stk_mem[c_stk_wr_addr[stk_wr_sel]] <= c_stk_wr_data[stk_wr_sel];
  end

  // the node reads: one request per cycle, the responses in request order (a FIFO of contexts)
  logic [CW-1:0] rsp_ctx [CTX], rsp_head, rsp_tail;
  assign mem_sel = pick(mem_req, rr_mem);
  assign node_req_valid_o = mem_req != 0;
  assign node_addr_o = c_mem_addr[mem_sel];
  assign {node_thread_o, node_level_o} = c_idx[mem_sel];
  for (genvar c = 0; c < CTX; c++) begin : g_mem
    assign mem_grant[c] = node_req_ready_i && mem_req[c] && mem_sel == CW'(c);
    assign mem_rsp[c] = node_rsp_valid_i && rsp_ctx[rsp_head] == CW'(c);
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rsp_head <= '0;
      rsp_tail <= '0;
    end else begin
      if (node_req_valid_o && node_req_ready_i) rsp_tail <= after(rsp_tail);
      if (node_rsp_valid_i) rsp_head <= after(rsp_head);
    end
  end
  always_ff @(posedge clk_i) begin
    if (node_req_valid_o && node_req_ready_i) rsp_ctx[rsp_tail] <= mem_sel;
  end

  // the results
  assign out_sel = pick(out_valid, rr_out);
  assign valid_o = out_valid != 0;
  for (genvar c = 0; c < CTX; c++) begin : g_out
    assign out_grant[c] = ready_i && out_valid[c] && out_sel == CW'(c);
  end
  assign {thread_o, level_o} = c_idx[out_sel];
  assign kind_o = c_kind[out_sel];
  assign mask_o = c_mask[out_sel];
  assign tn_o = c_tn[out_sel];
  assign tf_o = c_tf[out_sel];
  assign node_o = c_node[out_sel];
  assign have_cur_o = c_have_cur[out_sel];
  assign leaf_o = c_leaf[out_sel];
  assign list_o = c_list[out_sel];
  assign leaf_first_o = c_leaf_first[out_sel];
  assign leaf_count_o = c_leaf_count[out_sel];
  assign leaf_mask_o = c_leaf_mask[out_sel];
  assign leaf_tn_o = c_leaf_tn[out_sel];
  assign sp_o = c_sp[out_sel];
  assign lost_o = c_lost[out_sel];
  assign restarted_o = c_restarted[out_sel];
endmodule
