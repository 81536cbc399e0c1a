// trav_ctx: one operation context of the traversal unit (rtl/trav_unit.sv; paper section 3): the
// control of one scene clip, object clip, walk start or walk step of the algorithm TRAV_STACK
// (hls/units/trav_unit.c, trav_stack.c: trav_stack_step, walker_split, walker_push, entry_rays;
// trav_restart.c: trav_restart_drop_done, trav_restart) as a small FSM, bit for bit. It holds the
// operation's operands and, for a walk, the walker state of its thread and level (read from the
// unit's state memory in the cycle after the start, written back by the unit as the result
// leaves), and its own 8 comparators (the prune of the current and of a popped entry, the
// restarted pass's drop of done cells, the restart). It shares with the other contexts, through
// request/grant pairs that the unit arbitrates: the per-node datapath trav_node (the split of a
// walk step; a clip passes its 6 slab planes through it in turn: the lo plane of an axis narrows
// [tn, tf] as the node's right child does, the hi plane as its left child, so that every max and
// min happens in hls/units order), the stack memory's read and write ports, the node read request
// (its response comes back in request order) and the result output.
// Walk step: load the walker; prune (best_t < tn: the ray's hit lies before the entry); an entry
// left without rays is dropped and the next popped and pruned (the second read port of
// trav_stack_step); the node's two words; a leaf ends the entry, an inner node is split: a side
// that is an empty leaf gets no rays, in a restarted pass cells that end at t_exit are done, the
// packet's first ray (after a restart: the first that still needs a child) goes near first and
// the far child is pushed (a full stack drops its oldest entry: the stack is circular, top
// modulo DEPTH, sp saturating at DEPTH, and lost is set); an entry used up is replaced by the top
// of the stack, or after a drop the level restarts from its root entry with tn = max(tn, t_exit).
// Latency at the defaults (trav_node NODE = 21, comparator CMP = 2) when every grant comes at
// once and the memory answers in the cycle after the request: start 1; walk step at an inner node
// 2 (walker read) + (CMP + 1) (prune) + 1 + 2 (node request, response) + (NODE + 1) (split) + 2
// (push, pop) = 32, at a leaf 9, without a node read 7; + CMP + 3 when the pruned entry is dropped
// and the next popped, + 2 for a pop at the end, + CMP in a restarted pass, + 2 CMP for a restart;
// clip 6 (NODE + 1) + 2 = 134. One operation at a time; the context is free again in the cycle
// after its result leaves.
// Resources: 8 f24_cmp, about 90 W + 4 AW + 130 flip-flops of operands, walker state and step
// results (2.4 kbit at e7m16) and their input multiplexers: 6153 LUT6 and 3135 flip-flops with
// synth_xilinx at e7m16 (scripts/synth.py's flow, measured alone).
module trav_ctx #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int IW = 7,           // state index {thread, level}
  parameter int DEPTH = 64,
  parameter int AW = 32,
  parameter int CMP_STAGES = 2
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  // the operation: taken when start_i (the unit's input transfer), the walker state a cycle later
  input  logic                        start_i,
  input  logic [IW-1:0]               idx_i,
  input  logic [1:0]                  kind_i,
  input  logic [4*3*(E+M+1)-1:0]      o_i,
  input  logic [4*3*(E+M+1)-1:0]      d_i,
  input  logic [4*(E+M+1)-1:0]        tn_i,
  input  logic [4*(E+M+1)-1:0]        tf_i,
  input  logic [4*(E+M+1)-1:0]        best_i,
  input  logic [3:0]                  mask_i,
  input  logic [6*(E+M+1)-1:0]        box_i,
  input  logic [AW-1:0]               nodes_i,
  input  logic [AW+4+8*(E+M+1)+3+$clog2(DEPTH+1)+$clog2(DEPTH)+AW+4+12*(E+M+1)-1:0] state_i,
  output logic                        busy_o,
  output logic [IW-1:0]               idx_o,
  // the per-node datapath
  output logic                        node_req_o,
  input  logic                        node_grant_i,
  output logic [1:0]                  node_axis_o,
  output logic [E+M:0]                node_split_o,
  output logic [3:0]                  node_mask_o,
  output logic [4*3*(E+M+1)-1:0]      node_o_o,
  output logic [4*3*(E+M+1)-1:0]      node_d_o,
  output logic [4*(E+M+1)-1:0]        node_tn_o,
  output logic [4*(E+M+1)-1:0]        node_tf_o,
  input  logic                        node_done_i,   // trav_node's result is this context's
  input  logic [3:0]                  nd_l_mask_i,
  input  logic [3:0]                  nd_r_mask_i,
  input  logic [3:0]                  nd_near_left_i,
  input  logic [4*(E+M+1)-1:0]        nd_l_tn_i,
  input  logic [4*(E+M+1)-1:0]        nd_l_tf_i,
  input  logic [4*(E+M+1)-1:0]        nd_r_tn_i,
  input  logic [4*(E+M+1)-1:0]        nd_r_tf_i,
  // the stack memory: a read's data in the cycle after its grant
  output logic                        stk_rd_req_o,
  output logic [IW+$clog2(DEPTH)-1:0] stk_rd_addr_o,
  input  logic                        stk_rd_grant_i,
  input  logic [AW+4+8*(E+M+1)-1:0]   stk_rd_data_i,
  output logic                        stk_wr_req_o,
  output logic [IW+$clog2(DEPTH)-1:0] stk_wr_addr_o,
  output logic [AW+4+8*(E+M+1)-1:0]   stk_wr_data_o,
  input  logic                        stk_wr_grant_i,
  // the node read (granted when the memory takes it) and its response
  output logic                        mem_req_o,
  output logic [AW-1:0]               mem_addr_o,
  input  logic                        mem_grant_i,
  input  logic                        mem_rsp_i,
  input  logic [31:0]                 mem_w0_i,
  input  logic [31:0]                 mem_w1_i,
  // the result
  output logic                        out_valid_o,
  input  logic                        out_grant_i,
  output logic [AW+4+8*(E+M+1)+3+$clog2(DEPTH+1)+$clog2(DEPTH)+AW+4+12*(E+M+1)-1:0] state_o,
  output logic                        write_back_o,
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
  localparam int SPW = $clog2(DEPTH + 1);
  localparam int TPW = $clog2(DEPTH);
  localparam logic [1:0] K_OBJECT = 2'd1, K_START = 2'd2, K_WALK = 2'd3;
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] POS_INF = {1'b0, EMAX, {M{1'b0}}};

  typedef enum logic [4:0] {
    S_IDLE, S_LOAD, S_PRUNE_GO, S_PRUNE, S_POP_RD, S_POP, S_AFTER, S_REQ, S_RSP, S_NODE_GO, S_NODE, S_DROP,
    S_CHOOSE, S_END, S_END_RD, S_END_POP, S_RST_MAX, S_RST_CMP, S_CLIP_GO, S_CLIP, S_CLIP_END, S_OUT
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

  // 8 comparators: lanes 0..3 and 4..7 per ray
  logic cmp_go, cmp_valid;
  logic [W-1:0] cmp_a [8], cmp_b [8], cmp_max [4];
  logic [7:0] cmp_lt, cmp_le;
  /* verilator lint_off PINCONNECTEMPTY */
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

  // what the comparators are fed, by state (the registers they read are stable while they work)
  always_comb begin
    cmp_go = st == S_PRUNE_GO || (st == S_NODE && node_done_i && restarted) ||
             (st == S_END && !have_cur && sp == 0 && lost) || (st == S_RST_MAX && cmp_valid);
    for (int i = 0; i < 4; i++) begin
      if (st == S_PRUNE_GO) begin            // entry_rays: best_t < tn
        cmp_a[i] = lane(op_best, i);
        cmp_b[i] = lane(cur_tn, i);
        cmp_a[4+i] = lane(op_best, i);
        cmp_b[4+i] = lane(cur_tn, i);
      end else if (st == S_NODE) begin       // trav_restart_drop_done: tf <= t_exit
        cmp_a[i] = lane(nd_l_tf_i, i);
        cmp_b[i] = lane(t_exit, i);
        cmp_a[4+i] = lane(nd_r_tf_i, i);
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

  assign busy_o = st != S_IDLE;
  assign idx_o = idx;
  assign node_req_o = st == S_NODE_GO || st == S_CLIP_GO;
  assign node_axis_o = st == S_CLIP_GO ? pass[2:1] : w0[1:0];
  assign node_split_o = st == S_CLIP_GO ? op_box[(pass[0] ? 3 + 32'(pass[2:1]) : 32'(pass[2:1]))*W +: W] : w1[W-1:0];
  assign node_mask_o = st == S_CLIP_GO ? 4'hF : cur_mask;
  assign node_o_o = op_o;
  assign node_d_o = op_d;
  assign node_tn_o = st == S_CLIP_GO ? cl_n : cur_tn;
  assign node_tf_o = st == S_CLIP_GO ? cl_f : cur_tf;
  assign stk_rd_req_o = st == S_POP_RD || st == S_END_RD;
  assign stk_rd_addr_o = {idx, top - TPW'(1)};
  assign stk_wr_req_o = st == S_CHOOSE && both;
  assign stk_wr_addr_o = {idx, top};
  assign stk_wr_data_o = first_near_left ? {r_node, r_mask, r_tn, r_tf} : {l_node, l_mask, l_tn, l_tf};
  assign mem_req_o = st == S_REQ;
  assign mem_addr_o = nodes + (cur_node << 1);
  assign out_valid_o = st == S_OUT;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) st <= S_IDLE;
    else begin
      case (st)
        S_IDLE: if (start_i) st <= kind_i == K_START ? S_OUT : kind_i == K_WALK ? S_LOAD : S_CLIP_GO;
        S_LOAD: st <= S_PRUNE_GO;
        S_PRUNE_GO: st <= S_PRUNE;
        S_PRUNE: if (cmp_valid) st <= (cur_mask & op_mask & ~cmp_lt[3:0]) == 0 && sp != 0 && !popped ? S_POP_RD : S_AFTER;
        S_POP_RD: if (stk_rd_grant_i) st <= S_POP;
        S_POP: st <= S_PRUNE_GO;
        S_AFTER: st <= cur_mask == 0 ? S_END : S_REQ;
        S_REQ: if (mem_grant_i) st <= S_RSP;
        S_RSP: if (mem_rsp_i) st <= mem_w0_i[1:0] == 2'd3 ? S_END : S_NODE_GO;
        S_NODE_GO: if (node_grant_i) st <= S_NODE;
        S_NODE: if (node_done_i) st <= restarted ? S_DROP : S_CHOOSE;
        S_DROP: if (cmp_valid) st <= S_CHOOSE;
        S_CHOOSE: if (!both || stk_wr_grant_i) st <= S_END;
        S_END: st <= have_cur ? S_OUT : sp != 0 ? S_END_RD : lost ? S_RST_MAX : S_OUT;
        S_END_RD: if (stk_rd_grant_i) st <= S_END_POP;
        S_END_POP: st <= S_OUT;
        S_RST_MAX: if (cmp_valid) st <= S_RST_CMP;
        S_RST_CMP: if (cmp_valid) st <= S_OUT;
        S_CLIP_GO: if (node_grant_i) st <= S_CLIP;
        S_CLIP: if (node_done_i) st <= pass == 3'd5 ? S_CLIP_END : S_CLIP_GO;
        S_CLIP_END: st <= S_OUT;
        S_OUT: if (out_grant_i) st <= S_IDLE;
        default: st <= S_IDLE;
      endcase
    end
  end

  always_ff @(posedge clk_i) begin
    case (st)
      S_IDLE: if (start_i) begin
        idx <= idx_i;
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
        end
      end
      S_LOAD: {cur_node, cur_mask, cur_tn, cur_tf, have_cur, lost, restarted, sp, top, nodes, root_mask, root_tn,
               root_tf, t_exit} <= state_i;
      S_PRUNE: if (cmp_valid) cur_mask <= cur_mask & op_mask & ~cmp_lt[3:0];
      S_POP: begin                           // the second read port: the next entry, pruned anew
        {cur_node, cur_mask, cur_tn, cur_tf} <= stk_rd_data_i;
        sp <= sp - SPW'(1);
        top <= top - TPW'(1);
        popped <= 1'b1;
      end
      S_AFTER: begin
        root_mask <= root_mask & op_mask;
        if (cur_mask == 0) have_cur <= 1'b0;
      end
      S_RSP: if (mem_rsp_i) begin
        w0 <= mem_w0_i;
        w1 <= mem_w1_i;
        if (mem_w0_i[1:0] == 2'd3) begin    // a leaf: its list range and rays
          have_cur <= 1'b0;
          leaf <= 1'b1;
          list <= mem_w0_i[31:2] != 0;
          leaf_mask <= cur_mask;
          leaf_tn <= cur_tn;
        end
      end
      S_NODE: if (node_done_i) begin        // a side that is an empty leaf is not stored
        l_mask <= nd_l_mask_i & {4{!w0[2]}};
        r_mask <= nd_r_mask_i & {4{!w0[3]}};
        l_node <= AW'(w0 >> 4);
        r_node <= AW'(w0 >> 4) + AW'(!w0[2]);
        near_left <= nd_near_left_i;
        {l_tn, l_tf, r_tn, r_tf} <= {nd_l_tn_i, nd_l_tf_i, nd_r_tn_i, nd_r_tf_i};
      end
      S_DROP: if (cmp_valid) begin          // a restarted pass: cells that end at t_exit are done
        l_mask <= l_mask & ~cmp_le[3:0];
        r_mask <= r_mask & ~cmp_le[7:4];
      end
      S_CHOOSE: if (!both) begin
        {cur_node, cur_mask, cur_tn, cur_tf} <= l_mask != 0 ? {l_node, l_mask, l_tn, l_tf} : {r_node, r_mask, r_tn, r_tf};
      end else if (stk_wr_grant_i) begin    // walker_push: a full stack drops its oldest entry
        top <= top + TPW'(1);
        if (sp == SPW'(DEPTH)) lost <= 1'b1;
        else sp <= sp + SPW'(1);
        {cur_node, cur_mask, cur_tn, cur_tf} <=
          first_near_left ? {l_node, l_mask, l_tn, l_tf} : {r_node, r_mask, r_tn, r_tf};
      end
      S_END_POP: begin
        {cur_node, cur_mask, cur_tn, cur_tf} <= stk_rd_data_i;
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
      S_CLIP: if (node_done_i) begin        // lo plane: the right child's interval, hi plane: the left's
        cl_n <= pass[0] ? nd_l_tn_i : nd_r_tn_i;
        cl_f <= pass[0] ? nd_l_tf_i : nd_r_tf_i;
        clip_mask <= nd_l_mask_i;
        pass <= pass + 3'd1;
      end
      S_CLIP_END: begin                      // rays outside the mask keep their interval
        for (int i = 0; i < 4; i++) begin
          cl_n[i*W +: W] <= op_mask[i] ? lane(cl_n, i) : lane(op_tn, i);
          cl_f[i*W +: W] <= op_mask[i] ? lane(cl_f, i) : lane(op_tf, i);
        end
        clip_mask <= clip_mask & op_mask;
      end
      default: ;
    endcase
  end

  assign state_o = {cur_node, cur_mask, cur_tn, cur_tf, have_cur, lost, restarted, sp, top, nodes, root_mask, root_tn,
                    root_tf, t_exit};
  assign write_back_o = kind[1];
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
