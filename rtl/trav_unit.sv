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
// both with one synchronous read and one write port (block RAM).
// Datapath: one trav_node (4 sub, 4 div, 4 min, 4 max, 8 comparators; the clips run their 6 slab
// planes through it: the lo plane of an axis narrows [tn, tf] as the node's right child does, the
// hi plane as its left child, so that every max and min happens in hls/units order) and 8 f24_cmp
// (the prune, the restart's drop of done cells, the restart).
// Control: one operation at a time (a small FSM). Latency from the operation's transfer to the
// result's, at the defaults (trav_node NODE = 21, comparator CMP = 2) with a memory answering in
// the cycle after the request: start 1; walk step at an inner node 1 (walker read) + (CMP + 1)
// (prune) + 1 + 2 (node request, response) + (NODE + 1) (split) + 2 (push, pop) = 31, at a leaf
// 9, without a node read (every ray pruned) 6; + CMP + 2 when the pruned entry is dropped and the
// next popped, + 1 for a pop at the end, + CMP in a restarted pass, + 2 CMP for a restart; clip
// 6 (NODE + 1) + 2 = 134 (its planes one after the other through trav_node). The next operation
// is accepted in the cycle after the result leaves: II = latency + 1.
// Handshake: valid/ready at the operation input, the result output and the node read request;
// the node response (node_rsp_valid_i with w0, w1) is taken when it comes.
module trav_unit #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int THREADS = 64,
  parameter int DEPTH = 64,       // TRACE_STACK: stack entries per thread and level (a power of 2)
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
  localparam logic [1:0] K_OBJECT = 2'd1, K_START = 2'd2, K_WALK = 2'd3;
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] POS_INF = {1'b0, EMAX, {M{1'b0}}};
  if (DEPTH < 2 || (DEPTH & (DEPTH - 1)) != 0) begin : g_depth_check
    $error("trav_unit: DEPTH is a power of 2 (the circular stack's top pointer wraps)");
  end

  typedef enum logic [4:0] {
    S_IDLE, S_PRUNE_GO, S_PRUNE, S_POP, S_AFTER, S_REQ, S_RSP, S_DECODE, S_NODE, S_DROP, S_CHOOSE, S_END,
    S_END_POP, S_RST_MAX, S_RST_CMP, S_CLIP_GO, S_CLIP, S_CLIP_END, S_OUT
  } state_t;
  state_t st;

  // the operation
  logic [IW-1:0] idx;
  logic [1:0] kind;
  logic [4*3*W-1:0] op_o, op_d;
  logic [4*W-1:0] op_tn, op_tf, op_best;
  logic [3:0] op_mask;
  logic [6*W-1:0] op_box;

  // the walker state of (thread, level) while the operation runs
  logic [AW-1:0] cur_node, nodes;
  logic [3:0] cur_mask, root_mask;
  logic [4*W-1:0] cur_tn, cur_tf, root_tn, root_tf, t_exit;
  logic have_cur, lost, restarted;
  logic [SPW-1:0] sp;
  logic [TPW-1:0] top;

  // step results
  logic popped, leaf, list;
  logic [31:0] w0, w1;
  logic [4*W-1:0] leaf_tn;
  logic [3:0] leaf_mask;
  logic [AW-1:0] l_node, r_node;
  logic [3:0] l_mask, r_mask, near_left;
  logic [4*W-1:0] l_tn, l_tf, r_tn, r_tf;
  logic [2:0] pass;                 // clip: the slab plane (axis = pass / 2, hi when odd)
  logic [3:0] clip_mask;
  logic [4*W-1:0] cl_n, cl_f;

  // memories: the walker state and the stacks
  logic [STW-1:0] st_mem [2*THREADS];
  logic [ENW-1:0] stk_mem [2*THREADS*DEPTH];
  logic [ENW-1:0] stk_rd;

  // the per-node datapath
  logic node_go, node_valid;
  logic [1:0] node_axis;
  logic [W-1:0] node_split;
  logic [3:0] node_mask, nd_l_mask, nd_r_mask, nd_near_left;
  logic [4*W-1:0] node_tn, node_tf, nd_l_tn, nd_l_tf, nd_r_tn, nd_r_tf;
  /* verilator lint_off PINCONNECTEMPTY */
  trav_node #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .DIV_STAGES(DIV_STAGES), .CMP_STAGES(CMP_STAGES)) u_node (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(node_go), .ready_o(), .axis_i(node_axis), .split_i(node_split),
    .mask_i(node_mask), .o_i(op_o), .d_i(op_d), .tn_i(node_tn), .tf_i(node_tf), .valid_o(node_valid),
    .ready_i(1'b1), .l_mask_o(nd_l_mask), .r_mask_o(nd_r_mask), .near_left_o(nd_near_left), .l_tn_o(nd_l_tn),
    .l_tf_o(nd_l_tf), .r_tn_o(nd_r_tn), .r_tf_o(nd_r_tf));

  // 8 comparators: lanes 0..3 and 4..7 per ray
  logic cmp_go, cmp_valid;
  logic [W-1:0] cmp_a [8], cmp_b [8], cmp_max [4];
  logic [7:0] cmp_lt, cmp_le;
  for (genvar j = 0; j < 8; j++) begin : g_cmp
    /* verilator lint_off UNUSEDSIGNAL */
    logic [3:0] fl; // {unordered, eq, le, lt}: lt and le are used
    logic [W-1:0] mx; // lanes 0..3: the restart's max
    logic v;          // lane 0's stands for all
    /* verilator lint_on UNUSEDSIGNAL */
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_cmp (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
      .valid_i(cmp_go), .a_i(cmp_a[j]), .b_i(cmp_b[j]), .valid_o(v), .flags_o(fl), .min_o(), .max_o(mx));
    assign cmp_lt[j] = fl[0];
    assign cmp_le[j] = fl[1];
    if (j < 4) begin : g_max
      assign cmp_max[j] = mx;
    end
    if (j == 0) begin : g_valid
      assign cmp_valid = v;
    end
  end
  /* verilator lint_on PINCONNECTEMPTY */

  function automatic logic [W-1:0] lane(input logic [4*W-1:0] v, input int i);
    lane = v[i*W +: W];
  endfunction

  // what the operators are fed, by state (the registers they read are stable while they work)
  always_comb begin
    node_go = st == S_CLIP_GO || (st == S_DECODE && w0[1:0] != 2'd3);
    node_axis = st == S_CLIP_GO ? pass[2:1] : w0[1:0];
    node_split = st == S_CLIP_GO ? op_box[(pass[0] ? 3 + 32'(pass[2:1]) : 32'(pass[2:1]))*W +: W] : w1[W-1:0];
    node_mask = st == S_CLIP_GO ? 4'hF : cur_mask;
    node_tn = st == S_CLIP_GO ? cl_n : cur_tn;
    node_tf = st == S_CLIP_GO ? cl_f : cur_tf;
    cmp_go = st == S_PRUNE_GO || (st == S_NODE && node_valid && restarted) ||
             (st == S_END && !have_cur && sp == 0 && lost) || (st == S_RST_MAX && cmp_valid);
    for (int i = 0; i < 4; i++) begin
      if (st == S_PRUNE_GO) begin            // entry_rays: best_t < tn
        cmp_a[i] = lane(op_best, i);
        cmp_b[i] = lane(cur_tn, i);
        cmp_a[4+i] = lane(op_best, i);
        cmp_b[4+i] = lane(cur_tn, i);
      end else if (st == S_NODE) begin       // trav_restart_drop_done: tf <= t_exit
        cmp_a[i] = lane(nd_l_tf, i);
        cmp_b[i] = lane(t_exit, i);
        cmp_a[4+i] = lane(nd_r_tf, i);
        cmp_b[4+i] = lane(t_exit, i);
      end else if (st == S_END) begin        // trav_restart: max(tn, t_exit)
        cmp_a[i] = lane(root_tn, i);
        cmp_b[i] = lane(t_exit, i);
        cmp_a[4+i] = lane(root_tn, i);
        cmp_b[4+i] = lane(t_exit, i);
      end else begin                         // trav_restart: tn < tf, best_t < tn
        cmp_a[i] = cmp_max[i];
        cmp_b[i] = lane(root_tf, i);
        cmp_a[4+i] = lane(op_best, i);
        cmp_b[4+i] = cmp_max[i];
      end
    end
  end

  // walker_split's choice: the lead ray, its near side, the far child to push
  logic [2:0] lead;                 // a fourth ray leads when none of the others does
  logic [1:0] first;
  logic first_near_left, both;
  always_comb begin
    lead = restarted ? l_mask[2:0] | r_mask[2:0] : cur_mask[2:0];
    first = lead[0] ? 2'd0 : lead[1] ? 2'd1 : lead[2] ? 2'd2 : 2'd3;
    first_near_left = near_left[first];
    if (restarted && !(first_near_left ? l_mask[first] : r_mask[first])) first_near_left = !first_near_left;
    both = l_mask != 0 && r_mask != 0;
  end

  logic take;
  assign ready_o = st == S_IDLE;
  assign take = valid_i && ready_o;
  assign node_req_valid_o = st == S_REQ;
  assign node_addr_o = nodes + (cur_node << 1);
  assign valid_o = st == S_OUT;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) st <= S_IDLE;
    else begin
      case (st)
        S_IDLE: if (take) st <= kind_i == K_START ? S_OUT : kind_i == K_WALK ? S_PRUNE_GO : S_CLIP_GO;
        S_PRUNE_GO: st <= S_PRUNE;
        S_PRUNE: if (cmp_valid) st <= (cur_mask & op_mask & ~cmp_lt[3:0]) == 0 && sp != 0 && !popped ? S_POP : S_AFTER;
        S_POP: st <= S_PRUNE_GO;
        S_AFTER: st <= cur_mask == 0 ? S_END : S_REQ;
        S_REQ: if (node_req_ready_i) st <= S_RSP;
        S_RSP: if (node_rsp_valid_i) st <= S_DECODE;
        S_DECODE: st <= w0[1:0] == 2'd3 ? S_END : S_NODE;
        S_NODE: if (node_valid) st <= restarted ? S_DROP : S_CHOOSE;
        S_DROP: if (cmp_valid) st <= S_CHOOSE;
        S_CHOOSE: st <= S_END;
        S_END: st <= have_cur ? S_OUT : sp != 0 ? S_END_POP : lost ? S_RST_MAX : S_OUT;
        S_END_POP: st <= S_OUT;
        S_RST_MAX: if (cmp_valid) st <= S_RST_CMP;
        S_RST_CMP: if (cmp_valid) st <= S_OUT;
        S_CLIP_GO: st <= S_CLIP;
        S_CLIP: if (node_valid) st <= pass == 3'd5 ? S_CLIP_END : S_CLIP_GO;
        S_CLIP_END: st <= S_OUT;
        S_OUT: if (ready_i) st <= S_IDLE;
        default: st <= S_IDLE;
      endcase
    end
  end

  always_ff @(posedge clk_i) begin
    case (st)
      S_IDLE: if (take) begin
        idx <= {thread_i, level_i};
        kind <= kind_i;
        op_o <= o_i;
        op_d <= d_i;
        op_best <= best_i;
        op_mask <= mask_i;
        op_box <= box_i;
        popped <= 1'b0;
        leaf <= 1'b0;
        list <= 1'b0;
        pass <= 3'd0;
        for (int i = 0; i < 4; i++) begin  // the clips' intervals before the box (trav_object_clip)
          op_tn[i*W +: W] <= kind_i == K_OBJECT && !mask_i[i] ? POS_INF : lane(tn_i, i);
          op_tf[i*W +: W] <= kind_i == K_OBJECT && !mask_i[i] ? '0 : lane(tf_i, i);
          cl_n[i*W +: W] <= kind_i == K_OBJECT && !mask_i[i] ? POS_INF : lane(tn_i, i);
          cl_f[i*W +: W] <= kind_i == K_OBJECT && !mask_i[i] ? '0 : lane(tf_i, i);
        end
        if (kind_i == K_START) begin         // walker_init
          {cur_node, cur_mask, cur_tn, cur_tf} <= {AW'(0), mask_i, tn_i, tf_i};
          {have_cur, lost, restarted, sp, top} <= {3'b100, SPW'(0), TPW'(0)};
          {nodes, root_mask, root_tn, root_tf, t_exit} <= {nodes_i, mask_i, tn_i, tf_i, tn_i};
        end else begin
          {cur_node, cur_mask, cur_tn, cur_tf, have_cur, lost, restarted, sp, top, nodes, root_mask, root_tn,
           root_tf, t_exit} <= st_mem[{thread_i, level_i}];
        end
      end
      S_PRUNE: if (cmp_valid) begin
        cur_mask <= cur_mask & op_mask & ~cmp_lt[3:0];
        stk_rd <= stk_mem[{idx, top - TPW'(1)}];
      end
      S_POP: begin                           // the second read port: the next entry, pruned anew
        {cur_node, cur_mask, cur_tn, cur_tf} <= stk_rd;
        sp <= sp - SPW'(1);
        top <= top - TPW'(1);
        popped <= 1'b1;
      end
      S_AFTER: begin
        root_mask <= root_mask & op_mask;
        if (cur_mask == 0) have_cur <= 1'b0;
      end
      S_RSP: if (node_rsp_valid_i) begin
        w0 <= node_w0_i;
        w1 <= node_w1_i;
      end
      S_DECODE: if (w0[1:0] == 2'd3) begin  // a leaf: its list range and rays
        have_cur <= 1'b0;
        leaf <= 1'b1;
        list <= w0[31:2] != 0;
        leaf_mask <= cur_mask;
        leaf_tn <= cur_tn;
      end
      S_NODE: if (node_valid) begin         // a side that is an empty leaf is not stored
        l_mask <= nd_l_mask & {4{!w0[2]}};
        r_mask <= nd_r_mask & {4{!w0[3]}};
        l_node <= AW'(w0 >> 4);
        r_node <= AW'(w0 >> 4) + AW'(!w0[2]);
        near_left <= nd_near_left;
        {l_tn, l_tf, r_tn, r_tf} <= {nd_l_tn, nd_l_tf, nd_r_tn, nd_r_tf};
      end
      S_DROP: if (cmp_valid) begin          // a restarted pass: cells that end at t_exit are done
        l_mask <= l_mask & ~cmp_le[3:0];
        r_mask <= r_mask & ~cmp_le[7:4];
      end
      S_CHOOSE: begin
        if (both) begin                      // walker_push: a full stack drops its oldest entry
          stk_mem[{idx, top}] <= first_near_left ? {r_node, r_mask, r_tn, r_tf} : {l_node, l_mask, l_tn, l_tf};
          top <= top + TPW'(1);
          if (sp == SPW'(DEPTH)) lost <= 1'b1;
          else sp <= sp + SPW'(1);
          {cur_node, cur_mask, cur_tn, cur_tf} <=
            first_near_left ? {l_node, l_mask, l_tn, l_tf} : {r_node, r_mask, r_tn, r_tf};
        end else begin
          {cur_node, cur_mask, cur_tn, cur_tf} <= l_mask != 0 ? {l_node, l_mask, l_tn, l_tf} : {r_node, r_mask, r_tn, r_tf};
        end
      end
      S_END: stk_rd <= stk_mem[{idx, top - TPW'(1)}];
      S_END_POP: begin
        {cur_node, cur_mask, cur_tn, cur_tf} <= stk_rd;
        sp <= sp - SPW'(1);
        top <= top - TPW'(1);
        have_cur <= 1'b1;
      end
      S_RST_MAX: if (cmp_valid) begin       // trav_restart: from the root, tn = t_exit = max(tn, t_exit)
        for (int i = 0; i < 4; i++) begin
          t_exit[i*W +: W] <= cmp_max[i];
          cur_tn[i*W +: W] <= cmp_max[i];
        end
      end
      S_RST_CMP: if (cmp_valid) begin       // rays with nothing left or their hit before it are done
        root_mask <= root_mask & cmp_lt[3:0] & ~cmp_lt[7:4];
        cur_mask <= root_mask & cmp_lt[3:0] & ~cmp_lt[7:4];
        cur_node <= '0;
        cur_tf <= root_tf;
        have_cur <= (root_mask & cmp_lt[3:0] & ~cmp_lt[7:4]) != 0;
        lost <= 1'b0;
        restarted <= 1'b1;
      end
      S_CLIP: if (node_valid) begin         // lo plane: the right child's interval, hi plane: the left's
        cl_n <= pass[0] ? nd_l_tn : nd_r_tn;
        cl_f <= pass[0] ? nd_l_tf : nd_r_tf;
        clip_mask <= nd_l_mask;
        pass <= pass + 3'd1;
      end
      S_CLIP_END: begin                      // rays outside the mask keep their interval
        for (int i = 0; i < 4; i++) begin
          cl_n[i*W +: W] <= op_mask[i] ? lane(cl_n, i) : lane(op_tn, i);
          cl_f[i*W +: W] <= op_mask[i] ? lane(cl_f, i) : lane(op_tf, i);
        end
        clip_mask <= clip_mask & op_mask;
      end
      S_OUT: if (kind == K_START || kind == K_WALK)
        st_mem[idx] <= {cur_node, cur_mask, cur_tn, cur_tf, have_cur, lost, restarted, sp, top, nodes, root_mask,
                        root_tn, root_tf, t_exit};
      default: ;
    endcase
  end

  assign {thread_o, level_o} = idx;
  assign kind_o = kind;
  assign mask_o = kind[1] ? cur_mask : clip_mask;
  assign tn_o = kind[1] ? cur_tn : cl_n;
  assign tf_o = kind[1] ? cur_tf : cl_f;
  assign node_o = cur_node;
  assign have_cur_o = have_cur;
  assign leaf_o = leaf;
  assign list_o = list;
  assign leaf_first_o = w1;
  assign leaf_count_o = {2'b00, w0[31:2]};
  assign leaf_mask_o = leaf_mask;
  assign leaf_tn_o = leaf_tn;
  assign sp_o = sp;
  assign lost_o = lost;
  assign restarted_o = restarted;
endmodule
