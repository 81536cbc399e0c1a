// trace_core: the ray tracing core of a DynRTP (paper section 3, Figure 2 paths b..f): the thread
// state of a ray packet and the routing of hls/units/trace.c (trace_begin, trace_step and its
// operations route_after_list, enter_single_object, op_scene_clip, op_walk, rebase_leaf, op_list,
// op_inst_xform, op_inst_clip, op_tri_xform, op_tri_isect) around the units that have RTL:
// trav_unit (clips, walk start, walk steps; its stacks), list_unit (mailboxes), rebase_unit,
// xform_wide (instances, path d), xform_unit (triangle directions, path e; also rows 0 and 1 of
// the origin path), isect_unit, and the intersection unit's origin path of isect_unit_rebased /
// isect_origin (the offset from the vertex C on 3 adders, the plane distance on an f24_sum_exact
// of 9 terms). A packet of 4 rays enters with its TRACE_* flags (TRACE_SKIP_TOP, TRACE_ANY_HIT for
// shadow packets, TRACE_IDENTITY) and leaves with its 4 closest (or any) hits and its
// trace_counters, bit for bit those of trace_begin + trace_step to TP_DONE. The traversal algorithm
// is TRAV_STACK only (the algorithm trav_unit has; the others of the C unit have no RTL).
// State of the packet in flight (trace_state): the rays, alive, best_t, the hits, the level and per
// level the leaf (first, count, mask, tn, k), the list address and have_cur, the current
// instance/object/triangle and need mask, the object-space rays in double words, t0, best_rel,
// tmin_rel, the rebased origins p and te; the walkers' stacks and the mailboxes live in
// trav_unit and list_unit (indexed by thread and level). The memory image's words the C reads
// for its descriptors (header, instance, object, triangle records) come through a word read
// port, one request at a time; the traversal and list units read through their own ports.
// Step 1 of the thread state: THREADS sizes the units' per-thread memories and thread_i is the id
// the units see, but the core holds one packet at a time and runs one unit operation at a time
// (the units are pipelined; only one thread's operation is in flight): no thread_sched yet.
// Latency: per packet the sum of its operations' unit latencies plus the memory reads (tb_core
// reports cycles per packet); throughput one packet at a time.
// Resources: the units' (rtl/README.md) plus 3 f24_add, one f24_sum_exact of 9 terms and the state
// registers: 36 W bits per ray (3456 bits at e7m16 for the packet), a 40-word descriptor buffer,
// about 20 words of routing state and 10 counters of 32 bits (not yet synthesized).
// Handshake: valid/ready at the packet input and the result output; word port valid/ready with
// responses in request order (mem_rsp_valid_i); trav_unit's node port and list_unit's read port
// as those units define them.
module trace_core #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int THREADS = 64,
  parameter int CTX = 4,
  parameter int ADD_STAGES = 6,
  parameter int MUL_STAGES = 4,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2,
  parameter int SUM_STAGES = 25
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  // packet in (trace_begin)
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
  // word read port (descriptors)
  output logic                        mem_req_valid_o,
  input  logic                        mem_req_ready_i,
  output logic [31:0]                 mem_addr_o,
  input  logic                        mem_rsp_valid_i,
  input  logic [31:0]                 mem_rdata_i,
  // trav_unit's node port
  output logic                        node_req_valid_o,
  input  logic                        node_req_ready_i,
  output logic [31:0]                 node_addr_o,
  input  logic                        node_rsp_valid_i,
  input  logic [31:0]                 node_w0_i,
  input  logic [31:0]                 node_w1_i,
  // list_unit's read port
  output logic                        list_re_o,
  output logic [31:0]                 list_addr_o,
  input  logic [31:0]                 list_rdata_i
);
  localparam int W = 1 + E + M;
  localparam int TW = $clog2(THREADS);
  localparam logic [E-1:0] EXP_MAX = '1;
  localparam logic [W-1:0] POS_INF = {1'b0, EXP_MAX, {M{1'b0}}};
  localparam logic [W-1:0] DNAN = {1'b0, EXP_MAX, 1'b1, {(M-1){1'b0}}};
  localparam logic [31:0] NO_HIT = '1;
  // memory image layout (docs/memory-image.md; hls/units/trace.c)
  localparam int H_INSTANCES = 7, H_BOUNDS = 12, H_OBJECTS_AT = 18 + 2 * 5, H_INST_AT = 18 + 2 * 8;
  localparam int H_TOP_NODES_AT = 18 + 2 * 9, H_TOP_LISTS_AT = 18 + 2 * 10, HDR_WORDS = H_TOP_LISTS_AT + 1;
  localparam int TRI_BITS = 12 * W + 3 * 9 + 3;             // F24_TRIANGLE_BITS
  localparam int TRI_WORDS = (TRI_BITS + 31) / 32;          // F24_TRIANGLE_RECORD_WORDS
  localparam int INST_WORDS = TRI_WORDS * ((17 + TRI_WORDS - 1) / TRI_WORDS);
  localparam int INST_READ = 17, OBJ_READ = 14, LBUF = 40;
  localparam int C_STEPS = 0, C_LEAVES = 1, C_ENTRIES = 2, C_SKIPS = 3, C_XFORMS = 4, C_ISECTS = 5;
  localparam int C_NODES = 6, C_LISTS = 7, C_MATRICES = 8;
  if (M < 8) begin : g_m_check
    $error("trace_core: M >= 8 (the vertex's low part, 9-bit multiples, converts exactly)");
  end

  // ---- state of the packet in flight (trace_state) ----
  // the FSM's states (trace_step's operations and their unit transactions)
  localparam logic [5:0]
    S_IDLE = 6'd0, S_CLR0 = 6'd1, S_LOAD = 6'd2, S_HDR = 6'd3, S_SC_GO = 6'd4, S_TRAV_WAIT = 6'd5,
    S_SC_DONE = 6'd6, S_START_GO = 6'd7, S_START_DONE = 6'd8, S_SINGLE_NODE = 6'd9, S_SINGLE_LIST = 6'd10, S_ROUTE = 6'd11,
    S_WALK_GO = 6'd12, S_WALK_DONE = 6'd13, S_LIST_GO = 6'd14, S_LIST_WAIT = 6'd15, S_RB_RAY = 6'd16, S_RB_WAIT = 6'd17,
    S_IX_LOAD = 6'd18, S_IX = 6'd19, S_IX_RAY = 6'd20, S_WIDE_GO = 6'd21, S_WIDE_WAIT = 6'd22, S_IC_LOAD = 6'd23,
    S_IC_CLR = 6'd24, S_IC_RAY = 6'd25, S_ADD_WAIT = 6'd26, S_IC_CLIP = 6'd27, S_IC_DONE = 6'd28, S_TX_LOAD = 6'd29,
    S_TI_RAY = 6'd30, S_XF_GO = 6'd31, S_XF_WAIT = 6'd32, S_TI_OFS = 6'd33, S_TI_SUM = 6'd34, S_SUM_WAIT = 6'd35,
    S_TI_ISECT = 6'd36, S_TI_HIT = 6'd37, S_DONE = 6'd38;
  logic [5:0] st, ret, ld_ret, add_ret;

  logic [TW-1:0] thread;
  logic [2:0] flags;
  logic [3:0] active, alive, need, todo;
  logic [1:0] ray;
  logic [3*W-1:0] ro [4], rd [4], so [4], sd [4], so_lo [4], sd_lo [4], p_hi [4], p_lo [4];
  logic [W-1:0] tmin [4], best_t [4], best_rel [4], tmin_rel [4], t0 [4], te [4];
  logic [31:0] h_inst [4], h_tri [4];
  logic [W-1:0] h_t [4], h_u [4], h_v [4], h_cos [4];
  logic level;
  logic [31:0] lists [2], leaf_first [2], leaf_count [2], k [2];
  logic [3:0] leaf_mask [2];
  logic [W-1:0] leaf_tn [2][4];
  logic have_cur [2];
  logic [31:0] hdr_instances, hdr_objects, hdr_inst, hdr_top_nodes, hdr_top_lists;
  logic [6*W-1:0] scene_box;
  logic [31:0] inst, obj, tris, tri_ix;
  logic [31:0] cnt [10];
  logic walk_read;
  // the loader: ld_n words from ld_base into lbuf, then ld_ret
  logic [31:0] lbuf [LBUF];
  logic [31:0] ld_base;
  logic [5:0] ld_n, ld_sent, ld_got;
  // the intersection's intermediate values
  logic [3*W-1:0] dd, ofs_lo, ofs_hi, ofs;
  logic [1:0] ofs_pass;
  logic xf_dir;                      // xform_unit pass: 1 the direction, 0 the offset c

  // ---- lowest ray of todo ----
  logic [1:0] first;
  always_comb begin
    first = 2'd0;
    for (int i = 3; i >= 0; i--)
      if (todo[i]) first = 2'(i);
  end
  function automatic logic [31:0] popcount(input logic [3:0] m);
    popcount = {31'd0, m[0]} + {31'd0, m[1]} + {31'd0, m[2]} + {31'd0, m[3]};
  endfunction

  // ---- the records ----
  logic [TRI_WORDS*32-1:0] rec;
  always_comb
    for (int i = 0; i < TRI_WORDS; i++) rec[i*32 +: 32] = lbuf[i];
  logic [12*W-1:0] tri_m, inst_m;
  logic [3*W-1:0] c_hi, c_lo, neg_c_hi, inst_tlo;
  logic [2:0] tri_shared;
  // f24_vertex_lo: the low part k 2^-8 ulp(hi) of a vertex component from its 9-bit field
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
  always_comb begin
    tri_m = rec[0 +: 12*W];
    for (int i = 0; i < 12; i++) inst_m[i*W +: W] = lbuf[i][W-1:0];
    for (int j = 0; j < 3; j++) begin
      c_hi[j*W +: W] = tri_m[(4*j+3)*W +: W];
      neg_c_hi[j*W +: W] = c_hi[j*W +: W] ^ {1'b1, {(W-1){1'b0}}};
      c_lo[j*W +: W] = vertex_lo(rec[12*W + 9*j +: 9], c_hi[j*W + M +: E]);
      inst_tlo[j*W +: W] = lbuf[14 + j][W-1:0];
    end
    tri_shared = rec[12*W + 27 +: 3];
  end
  // xform_identity: the bits xform_point/xform_vector give for an identity with signed zeros
  function automatic logic [3*W-1:0] identity(input logic [12*W-1:0] m, input logic [3*W-1:0] v, input logic point);
    logic [3*W-1:0] r;
    for (int kk = 0; kk < 3; kk++) begin
      logic [W-1:0] c;
      logic nan, neg;
      c = v[kk*W +: W];
      nan = c[M +: E] == EXP_MAX && c[M-1:0] != 0;
      neg = point ? m[(4*kk+3)*W + W-1] : 1'b1;
      for (int j = 0; j < 3; j++) begin
        if (j != kk && v[j*W + M +: E] == EXP_MAX) nan = 1'b1;
        neg &= j == kk ? v[j*W + W-1] : m[(4*kk+j)*W + W-1] ^ v[j*W + W-1];
      end
      r[kk*W +: W] = nan ? DNAN : c[M +: E] != 0 ? c : {neg, {(W-1){1'b0}}};
    end
    identity = r;
  endfunction

  // ---- the units ----
  logic tv_valid, tv_ready, tv_out_valid, tv_level;
  logic [1:0] tv_kind;
  logic [4*3*W-1:0] tv_o, tv_d, ray_o, ray_d, obj_o, obj_d;
  logic [4*W-1:0] tv_tn, tv_tf, tv_best, tv_tn_o, tv_tf_o, tv_leaf_tn;
  logic [3:0] tv_mask, tv_mask_o, tv_leaf_mask;
  logic [6*W-1:0] tv_box;
  logic [31:0] tv_nodes, tv_leaf_first, tv_leaf_count;
  logic tv_have_cur, tv_leaf;
  logic [4*W-1:0] v_tmin, v_tmax, v_best_t, v_best_rel, v_tmin_rel;
  always_comb
    for (int i = 0; i < 4; i++) begin
      ray_o[i*3*W +: 3*W] = ro[i];
      ray_d[i*3*W +: 3*W] = rd[i];
      obj_o[i*3*W +: 3*W] = so[i];
      obj_d[i*3*W +: 3*W] = sd[i];
      v_tmin[i*W +: W] = tmin[i];
      v_best_t[i*W +: W] = best_t[i];
      v_best_rel[i*W +: W] = best_rel[i];
      v_tmin_rel[i*W +: W] = tmin_rel[i];
    end
  assign v_tmax = tmax_i;  // taken with the packet only (best_t holds it afterwards)
  assign tv_valid = st == S_SC_GO || st == S_START_GO || st == S_WALK_GO || st == S_IC_CLIP;
  assign tv_o = st == S_SC_GO || (st != S_IC_CLIP && !level) ? ray_o : obj_o;
  assign tv_d = st == S_SC_GO || (st != S_IC_CLIP && !level) ? ray_d : obj_d;
  assign tv_best = level ? v_best_rel : v_best_t;
  assign tv_box = st == S_SC_GO ? scene_box : {lbuf[13][W-1:0], lbuf[12][W-1:0], lbuf[11][W-1:0],
                                               lbuf[10][W-1:0], lbuf[9][W-1:0], lbuf[8][W-1:0]};
  logic [4*W-1:0] clip_tn, clip_tf, r_leaf_tn;   // the traversal unit's last result
  logic [3:0] clip_mask, r_leaf_mask;
  logic r_have_cur, r_leaf;
  logic [31:0] r_leaf_first, r_leaf_count;
  always_comb begin
    tv_kind = 2'd3;
    tv_level = level;
    tv_mask = alive;
    tv_tn = clip_tn;
    tv_tf = clip_tf;
    unique case (st)
      S_SC_GO: begin
        tv_kind = 2'd0;
        tv_level = 1'b0;
        tv_mask = active;
        tv_tn = v_tmin;
        tv_tf = v_best_t;     // tmax
      end
      S_IC_CLIP: begin
        tv_kind = 2'd1;
        tv_level = 1'b1;
        tv_mask = need;
        tv_tn = v_tmin_rel;
        tv_tf = v_best_rel;
      end
      S_START_GO: begin
        tv_kind = 2'd2;
        tv_mask = clip_mask;
      end
      default: ;
    endcase
  end
  assign tv_nodes = level ? lbuf[0] : hdr_top_nodes;
  /* verilator lint_off PINCONNECTEMPTY */
  trav_unit #(.E(E), .M(M), .THREADS(THREADS), .CTX(CTX), .ADD_STAGES(ADD_STAGES), .DIV_STAGES(DIV_STAGES),
              .CMP_STAGES(CMP_STAGES)) u_trav (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(tv_valid), .ready_o(tv_ready), .thread_i(thread),
    .level_i(tv_level), .kind_i(tv_kind), .o_i(tv_o), .d_i(tv_d), .tn_i(tv_tn), .tf_i(tv_tf), .best_i(tv_best),
    .mask_i(tv_mask), .box_i(tv_box), .nodes_i(tv_nodes),
    .node_req_valid_o(node_req_valid_o), .node_req_ready_i(node_req_ready_i), .node_addr_o(node_addr_o),
    .node_thread_o(), .node_level_o(), .node_rsp_valid_i(node_rsp_valid_i), .node_w0_i(node_w0_i),
    .node_w1_i(node_w1_i), .valid_o(tv_out_valid), .ready_i(1'b1), .thread_o(), .level_o(), .kind_o(),
    .mask_o(tv_mask_o), .tn_o(tv_tn_o), .tf_o(tv_tf_o), .node_o(), .have_cur_o(tv_have_cur), .leaf_o(tv_leaf),
    .list_o(), .leaf_first_o(tv_leaf_first), .leaf_count_o(tv_leaf_count), .leaf_mask_o(tv_leaf_mask),
    .leaf_tn_o(tv_leaf_tn), .sp_o(), .lost_o(), .restarted_o());

  logic lu_valid, lu_ready, lu_clear, lu_out_valid;
  logic [31:0] lu_key, lu_k;
  logic [3:0] lu_need, lu_skip;
  assign lu_valid = st == S_CLR0 || st == S_IC_CLR || st == S_LIST_GO;
  assign lu_clear = st != S_LIST_GO;
  list_unit #(.THREADS(THREADS)) u_list (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(lu_valid), .ready_o(lu_ready), .thread_i(thread),
    .level_i(st == S_CLR0 ? 1'b0 : st == S_IC_CLR ? 1'b1 : level), .clear_i(lu_clear), .lists_i(lists[level]),
    .first_i(leaf_first[level]), .k_i(k[level]), .leaf_mask_i(leaf_mask[level]), .alive_i(alive),
    .mem_re_o(list_re_o), .mem_addr_o(list_addr_o), .mem_rdata_i(list_rdata_i), .valid_o(lu_out_valid),
    .ready_i(1'b1), .thread_o(), .level_o(), .key_o(lu_key), .need_o(lu_need), .skip_o(lu_skip), .k_o(lu_k));

  // rebase: the leaf's origins (rebase_leaf, level 1) or the world ray to the top-level leaf (op_inst_xform)
  logic rb_valid, rb_ready, rb_out_valid, rb_leaf;
  logic [3*W-1:0] rb_p_hi, rb_p_lo;
  logic [W-1:0] rb_te;
  assign rb_valid = st == S_RB_RAY && todo != 0;
  rebase_unit #(.E(E), .M(M), .SUM_STAGES(SUM_STAGES)) u_rebase (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(rb_valid), .ready_o(rb_ready),
    .o_hi_i(rb_leaf ? so[first] : ro[first]), .o_lo_i(rb_leaf ? so_lo[first] : '0),
    .d_hi_i(rb_leaf ? sd[first] : rd[first]), .d_lo_i(rb_leaf ? sd_lo[first] : '0),
    .t_i(leaf_tn[rb_leaf][first]), .valid_o(rb_out_valid), .ready_i(1'b1), .p_hi_o(rb_p_hi), .p_lo_o(rb_p_lo),
    .te_o(rb_te));

  logic xw_valid, xw_ready, xw_out_valid, xw_point;
  logic [3*W-1:0] xw_hi, xw_lo;
  assign xw_valid = st == S_WIDE_GO;
  xform_wide #(.E(E), .M(M), .SUM_STAGES(SUM_STAGES)) u_wide (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(xw_valid), .ready_o(xw_ready), .m_i(inst_m), .tlo_i(inst_tlo),
    .p_hi_i(xw_point ? p_hi[ray] : rd[ray]), .p_lo_i(p_lo[ray]), .point_i(xw_point), .valid_o(xw_out_valid),
    .ready_i(1'b1), .r_hi_o(xw_hi), .r_lo_o(xw_lo));

  logic xf_valid, xf_ready, xf_out_valid;
  logic [3*W-1:0] xf_r;
  assign xf_valid = st == S_XF_GO;
  xform_unit #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .MUL_STAGES(MUL_STAGES)) u_xform (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(xf_valid), .ready_o(xf_ready), .m_i(tri_m),
    .v_i(xf_dir ? sd[ray] : ofs), .point_i(1'b0), .valid_o(xf_out_valid), .ready_i(1'b1), .r_o(xf_r));

  // 3 adders: the offset from the vertex, the relative distances, best_t = t0 + t
  logic add_valid, add_sub;
  logic [3*W-1:0] add_a, add_b, add_r;
  logic [2:0] add_out_valid;
  for (genvar j = 0; j < 3; j++) begin : g_add
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_add (
      .clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(add_valid), .a_i(add_a[j*W +: W]),
      .b_i(add_b[j*W +: W]), .sub_i(add_sub), .valid_o(add_out_valid[j]), .res_o(add_r[j*W +: W]));
  end

  // the plane distance O'z: n.p_hi + n.(-C_hi) + n.(p_lo - C_lo) in one exact sum
  logic sum_valid, sum_out_valid;
  logic [9*W-1:0] sum_a, sum_b;
  logic [W-1:0] sum_oz, oz;
  assign sum_valid = st == S_TI_SUM;
  assign sum_a = {3{tri_m[8*W +: 3*W]}};
  assign sum_b = {ofs_lo, neg_c_hi, p_hi[ray]};
  f24_sum_exact #(.E(E), .M(M), .N(9), .STAGES(SUM_STAGES)) u_sum (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(sum_valid), .a_i(sum_a), .b_i(sum_b),
    .valid_o(sum_out_valid), .hi_o(sum_oz), .lo_o());

  logic is_valid, is_ready, is_out_valid, is_hit;
  logic [W-1:0] is_t, is_u, is_v, is_cos;
  logic [2*W-1:0] oxy;
  assign is_valid = st == S_TI_ISECT;
  isect_unit #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .MUL_STAGES(MUL_STAGES), .DIV_STAGES(DIV_STAGES),
               .CMP_STAGES(CMP_STAGES)) u_isect (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(is_valid), .ready_o(is_ready), .o_i({oz, oxy}),
    .d_i(dd), .te_i(te[ray]), .tmin_i(tmin_rel[ray]), .tmax_i(best_rel[ray]), .shared_i(tri_shared),
    .valid_o(is_out_valid), .ready_i(1'b1), .hit_o(is_hit), .t_o(is_t), .u_o(is_u), .v_o(is_v), .cos_o(is_cos));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- the adders' operands, by the state that starts them ----
  always_comb begin
    add_valid = 1'b0;
    add_sub = 1'b1;
    add_a = '0;
    add_b = '0;
    unique case (st)
      S_IC_RAY: begin  // best_rel = best_t - t0, tmin_rel = tmin - t0
        add_valid = todo != 0;
        add_a[0 +: 2*W] = {tmin[first], best_t[first]};
        add_b[0 +: 2*W] = {t0[first], t0[first]};
      end
      S_TI_OFS: begin  // l = p_lo - C_lo, h = p_hi - C_hi, c = h + l
        add_valid = 1'b1;
        add_sub = ofs_pass != 2'd2;
        add_a = ofs_pass == 2'd0 ? p_lo[ray] : ofs_pass == 2'd1 ? p_hi[ray] : ofs_hi;
        add_b = ofs_pass == 2'd0 ? c_lo : ofs_pass == 2'd1 ? c_hi : ofs_lo;
      end
      S_TI_HIT: begin  // best_t = t0 + t
        add_valid = is_out_valid && is_hit;
        add_sub = 1'b0;
        add_a[0 +: W] = t0[ray];
        add_b[0 +: W] = is_t;
      end
      default: ;
    endcase
  end

  assign mem_req_valid_o = st == S_LOAD && ld_sent != ld_n;
  assign mem_addr_o = ld_base + 32'(ld_sent);
  assign ready_o = st == S_IDLE;
  assign valid_o = st == S_DONE;
  assign thread_o = thread;
  always_comb
    for (int i = 0; i < 4; i++) begin
      inst_o[i*32 +: 32] = h_inst[i];
      tri_o[i*32 +: 32] = h_tri[i];
      t_o[i*W +: W] = h_t[i];
      u_o[i*W +: W] = h_u[i];
      v_o[i*W +: W] = h_v[i];
      cos_o[i*W +: W] = h_cos[i];
    end
  always_comb
    for (int c = 0; c < 10; c++) count_o[c*32 +: 32] = cnt[c];

  // the loader: reads n words from base into lbuf through the word port, then goes to next
  task automatic load(input logic [31:0] base, input logic [5:0] n, input logic [5:0] next);
    ld_base <= base;
    ld_n <= n;
    ld_sent <= '0;
    ld_got <= '0;
    ld_ret <= next;
    st <= S_LOAD;
  endtask

  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      st <= S_IDLE;
    end else begin
      if (node_rsp_valid_i) begin
        cnt[C_NODES] <= cnt[C_NODES] + 2;
        walk_read <= 1'b1;
      end
      unique case (st)
        S_IDLE:
          if (valid_i) begin
            thread <= thread_i;
            flags <= flags_i;
            active <= active_i;
            alive <= active_i;
            level <= 1'b0;
            have_cur[0] <= 1'b0;
            have_cur[1] <= 1'b0;
            for (int i = 0; i < 4; i++) begin
              ro[i] <= o_i[i*3*W +: 3*W];
              rd[i] <= d_i[i*3*W +: 3*W];
              tmin[i] <= tmin_i[i*W +: W];
              tmin_rel[i] <= tmin_i[i*W +: W];
              best_t[i] <= v_tmax[i*W +: W];
              best_rel[i] <= v_tmax[i*W +: W];
              t0[i] <= '0;
              h_inst[i] <= NO_HIT;
              h_tri[i] <= NO_HIT;
              h_t[i] <= POS_INF;
              h_u[i] <= '0;
              h_v[i] <= '0;
              h_cos[i] <= '0;
            end
            for (int c = 0; c < 10; c++) cnt[c] <= '0;
            st <= S_CLR0;
          end
        S_CLR0:
          if (lu_ready) load(32'd0, 6'(HDR_WORDS), S_HDR);
        S_LOAD: begin
          if (mem_req_valid_o && mem_req_ready_i) ld_sent <= ld_sent + 1'b1;
          if (mem_rsp_valid_i) begin
            lbuf[ld_got] <= mem_rdata_i;
            ld_got <= ld_got + 1'b1;
            if (ld_got + 1'b1 == ld_n) st <= ld_ret;
          end
        end
        S_HDR: begin
          hdr_instances <= lbuf[H_INSTANCES];
          hdr_objects <= lbuf[H_OBJECTS_AT];
          hdr_inst <= lbuf[H_INST_AT];
          hdr_top_nodes <= lbuf[H_TOP_NODES_AT];
          hdr_top_lists <= lbuf[H_TOP_LISTS_AT];
          for (int j = 0; j < 6; j++) scene_box[j*W +: W] <= lbuf[H_BOUNDS + j][W-1:0];
          st <= S_SC_GO;
        end
        // traversal unit: an operation issued, its result awaited (ret: what follows)
        S_SC_GO: if (tv_ready) begin ret <= S_SC_DONE; st <= S_TRAV_WAIT; end
        S_START_GO: if (tv_ready) begin ret <= S_START_DONE; st <= S_TRAV_WAIT; end
        S_WALK_GO: if (tv_ready) begin ret <= S_WALK_DONE; walk_read <= 1'b0; st <= S_TRAV_WAIT; end
        S_IC_CLIP: if (tv_ready) begin ret <= S_IC_DONE; st <= S_TRAV_WAIT; end
        S_TRAV_WAIT:
          if (tv_out_valid) begin
            clip_mask <= tv_mask_o;
            clip_tn <= tv_tn_o;
            clip_tf <= tv_tf_o;
            r_have_cur <= tv_have_cur;
            r_leaf <= tv_leaf;
            r_leaf_first <= tv_leaf_first;
            r_leaf_count <= tv_leaf_count;
            r_leaf_mask <= tv_leaf_mask;
            r_leaf_tn <= tv_leaf_tn;
            st <= ret;
          end
        S_SC_DONE:  // op_scene_clip
          if (clip_mask == 0 || hdr_instances == 0) st <= S_DONE;
          else if (flags[0]) begin  // enter_single_object: its one-leaf list
            need <= clip_mask;
            leaf_count[0] <= '0;
            k[0] <= '0;
            for (int i = 0; i < 4; i++) leaf_tn[0][i] <= clip_tn[i*W +: W];
            load(hdr_top_nodes + 1, 6'd1, S_SINGLE_NODE);
          end else begin
            lists[0] <= hdr_top_lists;
            st <= S_START_GO;
          end
        S_START_DONE: begin
          have_cur[level] <= 1'b1;
          leaf_count[level] <= '0;
          k[level] <= '0;
          st <= S_WALK_GO;
        end
        S_SINGLE_NODE: load(hdr_top_lists + lbuf[0], 6'd1, S_SINGLE_LIST);
        S_SINGLE_LIST: begin
          inst <= lbuf[0];
          st <= S_IX_LOAD;
        end
        S_ROUTE:  // route_after_list: the next entry, the next walk step, back up, or done
          if (alive == 0) st <= S_DONE;
          else if (k[level] < leaf_count[level]) st <= S_LIST_GO;
          else if (have_cur[level]) st <= S_WALK_GO;
          else if (!level) st <= S_DONE;
          else level <= 1'b0;
        S_WALK_DONE: begin  // op_walk
          have_cur[level] <= r_have_cur;
          if (r_leaf) begin
            leaf_first[level] <= r_leaf_first;
            leaf_count[level] <= r_leaf_count;
            leaf_mask[level] <= r_leaf_mask;
            k[level] <= '0;
            for (int i = 0; i < 4; i++) leaf_tn[level][i] <= r_leaf_tn[i*W +: W];
            cnt[C_LEAVES] <= cnt[C_LEAVES] + 1;
          end else if (walk_read) cnt[C_STEPS] <= cnt[C_STEPS] + 1;
          st <= S_ROUTE;
        end
        S_LIST_GO: if (lu_ready) st <= S_LIST_WAIT;
        S_LIST_WAIT:  // op_list
          if (lu_out_valid) begin
            k[level] <= lu_k;
            need <= lu_need;
            cnt[C_ENTRIES] <= cnt[C_ENTRIES] + 1;
            cnt[C_SKIPS] <= cnt[C_SKIPS] + popcount(lu_skip);
            cnt[C_LISTS] <= cnt[C_LISTS] + 1;
            if (level) tri_ix <= lu_key;
            else inst <= lu_key;
            ret <= lu_need == 0 ? S_ROUTE : level ? S_TX_LOAD : S_IX_LOAD;
            if (level && k[1] == 0) begin  // rebase_leaf: the leaf opens
              rb_leaf <= 1'b1;
              todo <= leaf_mask[1] & alive;
              st <= S_RB_RAY;
            end else st <= lu_need == 0 ? S_ROUTE : level ? S_TX_LOAD : S_IX_LOAD;
          end
        S_RB_RAY:
          if (todo == 0) st <= ret;
          else if (rb_ready) begin
            ray <= first;
            todo[first] <= 1'b0;
            st <= S_RB_WAIT;
          end
        S_RB_WAIT:
          if (rb_out_valid) begin
            if (rb_leaf) begin
              p_hi[ray] <= rb_p_hi;
              p_lo[ray] <= rb_p_lo;
              te[ray] <= rb_te;
              st <= S_RB_RAY;
            end else begin
              p_hi[ray] <= rb_p_hi;
              p_lo[ray] <= rb_p_lo;
              t0[ray] <= rb_te;
              xw_point <= 1'b1;
              st <= S_WIDE_GO;
            end
          end
        // op_inst_xform
        S_IX_LOAD: load(hdr_inst + INST_WORDS * inst, 6'(INST_READ), S_IX);
        S_IX: begin
          obj <= hdr_objects + 16 * lbuf[12];
          cnt[C_MATRICES] <= cnt[C_MATRICES] + INST_READ + OBJ_READ;
          // an identity instance, or TRACE_IDENTITY's single one (enter_single_object): the rays pass
          // as wiring, and the clip follows in the same operation
          if (lbuf[13][0] || flags[2]) begin
            for (int i = 0; i < 4; i++)
              if (need[i]) begin
                so[i] <= identity(inst_m, ro[i], 1'b1);
                sd[i] <= identity(inst_m, rd[i], 1'b0);
                so_lo[i] <= '0;
                sd_lo[i] <= '0;
                t0[i] <= '0;
              end
            st <= S_IC_LOAD;
          end else begin
            cnt[C_XFORMS] <= cnt[C_XFORMS] + 2 * popcount(need);
            todo <= need;
            st <= S_IX_RAY;
          end
        end
        S_IX_RAY:  // per ray: rebase to the top-level leaf, the origin wide, the direction wide
          if (todo == 0) st <= S_IC_LOAD;
          else begin
            rb_leaf <= 1'b0;
            st <= S_RB_RAY;
            ret <= S_IC_LOAD;
          end
        S_WIDE_GO: if (xw_ready) st <= S_WIDE_WAIT;
        S_WIDE_WAIT:
          if (xw_out_valid) begin
            if (xw_point) begin
              so[ray] <= xw_hi;
              so_lo[ray] <= xw_lo;
              xw_point <= 1'b0;
              st <= S_WIDE_GO;
            end else begin
              sd[ray] <= xw_hi;
              sd_lo[ray] <= xw_lo;
              st <= S_RB_RAY;  // the next ray (todo)
            end
          end
        // op_inst_clip / inst_clip
        S_IC_LOAD: load(obj, 6'(OBJ_READ), S_IC_CLR);
        S_IC_CLR:
          if (lu_ready) begin
            todo <= need;
            st <= S_IC_RAY;
          end
        S_IC_RAY:
          if (todo == 0) st <= S_IC_CLIP;
          else begin
            ray <= first;
            todo[first] <= 1'b0;
            add_ret <= S_IC_RAY;
            st <= S_ADD_WAIT;
          end
        S_ADD_WAIT:
          if (&add_out_valid) begin
            if (add_ret == S_IC_RAY) begin
              best_rel[ray] <= add_r[0 +: W];
              tmin_rel[ray] <= add_r[W +: W];
            end else if (add_ret == S_TI_OFS) begin
              if (ofs_pass == 2'd0) ofs_lo <= add_r;
              else if (ofs_pass == 2'd1) ofs_hi <= add_r;
              else ofs <= add_r;
              ofs_pass <= ofs_pass + 1'b1;
            end else best_t[ray] <= add_r[0 +: W];
            if (add_ret == S_TI_OFS && ofs_pass == 2'd2) st <= S_XF_GO;
            else if (add_ret == S_TI_HIT) begin
              h_t[ray] <= add_r[0 +: W];
              st <= S_TI_RAY;
            end else st <= add_ret;
          end
        S_IC_DONE:
          if (clip_mask == 0) st <= S_ROUTE;
          else begin
            tris <= lbuf[2];
            lists[1] <= lbuf[1];
            level <= 1'b1;
            st <= S_START_GO;
          end
        // op_tri_xform, op_tri_isect
        S_TX_LOAD: begin
          cnt[C_MATRICES] <= cnt[C_MATRICES] + TRI_WORDS;
          cnt[C_XFORMS] <= cnt[C_XFORMS] + popcount(need);
          cnt[C_ISECTS] <= cnt[C_ISECTS] + popcount(need);
          todo <= need;
          load(tris + TRI_WORDS * tri_ix, 6'(TRI_WORDS), S_TI_RAY);
        end
        S_TI_RAY:
          if (todo == 0) st <= S_ROUTE;
          else begin
            ray <= first;
            todo[first] <= 1'b0;
            xf_dir <= 1'b1;
            st <= S_XF_GO;
          end
        S_XF_GO: if (xf_ready) st <= S_XF_WAIT;
        S_XF_WAIT:
          if (xf_out_valid) begin
            if (xf_dir) begin
              dd <= xf_r;
              xf_dir <= 1'b0;
              ofs_pass <= 2'd0;
              st <= S_TI_OFS;
            end else begin
              oxy <= xf_r[0 +: 2*W];
              st <= S_TI_SUM;
            end
          end
        S_TI_OFS: begin
          add_ret <= S_TI_OFS;
          st <= S_ADD_WAIT;
        end
        S_TI_SUM: st <= S_SUM_WAIT;
        S_SUM_WAIT:
          if (sum_out_valid) begin
            oz <= sum_oz;
            st <= S_TI_ISECT;
          end
        S_TI_ISECT: if (is_ready) st <= S_TI_HIT;
        S_TI_HIT:
          if (is_out_valid) begin
            if (is_hit) begin
              best_rel[ray] <= is_t;
              h_inst[ray] <= inst;
              h_tri[ray] <= tri_ix;
              h_u[ray] <= is_u;
              h_v[ray] <= is_v;
              h_cos[ray] <= is_cos;
              if (flags[1]) alive[ray] <= 1'b0;
              add_ret <= S_TI_HIT;
              st <= S_ADD_WAIT;
            end else st <= S_TI_RAY;
          end
        S_DONE: if (ready_i) st <= S_IDLE;
        default: st <= S_IDLE;
      endcase
    end
endmodule
