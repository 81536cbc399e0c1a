// trace_thread: one thread of the ray tracing core (trace_core): the state of its packet
// (trace_state: alive, best_t, a hit flag per ray, the level and per level the leaf, the list
// address and have_cur, the current instance/object/triangle and need mask, best_rel, tmin_rel;
// the rays themselves and the fields only the per-ray units read or write, the world and
// object-space rays' o and d, the rebased origins p, te, t0, the hits' records, the packet's
// tmin, the leaves' entry distances (written by the traversal unit's results) and its
// trace_counters (counted from the units' reports), are trace_core's, in thread_ram indexed by thread (and ray), with a flag per ray here where the C
// sets them to zero or to a function of other fields: lo_zero (an identity instance's
// object-space ray, xform_identity of the world ray with the matrix signs id_sg, low words zero),
// t0_zero) and the FSM of
// hls/units/trace.c's trace_step (route_after_list, enter_single_object, op_scene_clip, op_walk,
// rebase_leaf, op_list, op_inst_xform, op_inst_clip, op_tri_xform, op_tri_isect). Per unit it
// raises a request with the operation's operands (*_req_o and the operand ports) and its issue
// slots (slots_o) and waits for the core's grant (*_grant_i: the unit took it), then for the
// result, which the core delivers to this thread alone (*_done_i with the result ports, shared by
// all threads). The traversal and list units take one operation per packet; the per-ray units
// (rebase, wide transformation, the relative distances' subtractors, the triangle test
// isect_rebased) take a batch: one step of each ray of a mask, in one or two passes (an
// instance's origins then directions), issued on consecutive cycles while the core holds the unit
// for the thread (slots_o = the batch's steps), and its results collected as they come back, in
// issue order; the next batch starts when the last result is in. A triangle is one batch of a
// step per ray on isect_rebased (its transformation, intersection and best_t = t0 + t); so the
// packet's 4 rays flow through the pipelined units back to back, as the cycle model times an
// operation of n rays (n issue slots, the latency once). The header's fields (hdr_*_i: the instance count, the region
// table's addresses, the scene bounds) are the core's, read once per memory image and shared by all threads (the thread
// waits in S_HDR until hdr_ok_i); the instance, object and triangle records come through the wide
// word port, RW consecutive words (one matrix cache line, one packed triangle record) per response,
// so a record takes one or two responses (ld_n of them, unpacked from lbuf); a request names the
// record (ld_rec_o: its region, the object's tris_o for a triangle), its index (ld_ix_o) and the
// response's place in it (ld_sent_o), and trace_core computes the word address once, for the
// thread it grants (the records' sizes and the regions are the core's). TRAV_STACK only (the
// algorithm trav_unit has). The stacks and mailboxes live in trav_unit and list_unit.
// Latency: the sum of the packet's unit operations and batches (a batch: its issue slots plus the
// unit's latency), their waits for the units and the reads.
// Resources: the state registers, 5 W bits per ray (best_t, best_rel, tmin_rel, the last
// clip's tn and tf), 3 flags and 12 matrix signs (the rays' o and d, p, te, t0, tmin, the
// leaves' te, the object-space rays' low words, the hits' records and the records' operand words
// in trace_core's thread_ram; the triangle's intermediate values in isect_rebased's pipeline), of
// the descriptor buffer the 4 words and 13 bits its FSM reads, about 13 words of routing state
// (the packet's trace_counters: trace_core's thread_count memories; the thread says whether its
// walk step read a node, walk_read_o; the descriptor addresses: trace_core's word port). synth_ice40
// -dsp -noflatten (python3 scripts/synth.py --ice40 trace_thread, 2026-11-30): 1,539 SB_LUT4,
// 1,177 flip-flops, 0 SB_MAC16 (2,988 and 1,905 with the 10 counters of 32 bits here; 2,478 and
// 1,618 without them; 2,133 and 1,618 when t_o's +Inf for a miss moved to trace_core and the
// clips took one choice of two; 1,910 and 1,330 without the leaves' te, 1,845 and 1,234 without
// tmin: both trace_core's thread_ram; 2 SB_MAC16 until the records' addresses went to the core). Yosys 0.23 synth_xilinx at e7m16 (python3
// scripts/synth.py --levels trace_thread --hier, 2026-11-30): 1,430 LUT6, 1,179 flip-flops, 6 LUT6
// levels (1,600 and 1,236 with the descriptor addresses here; 2,269, 1,908 and 7 on 2026-11-29
// with the counters). With the rays' o and d and the
// records' words here (ro, rd, so, sd, the 20-word buffer, f24_vertex_lo, xform_identity): 5040
// LUT6, 3440 flip-flops, 8 levels, and 5,871 SB_LUT4, 3,437 flip-flops (5048 LUT6, 3439
// flip-flops before done; 5297, 3438 before ld_req; 6449, 5410 and 8 with p, te, t0, the low
// words and the hits' records here; 5718 LUTs and 6183 flip-flops before the header moved to the
// core and the buffer shrank from 40 words to 20). Its ports (synth.py --ports, 2026-11-30):
// valid_o, mem_req_valid_o and t_o 0 LUT6 levels from registers (t_o 1 before it was best_t),
// ready_i 2 into registers (3 before the counters moved), trav_grant_i 2, list_grant_i 3.
// Handshake: valid/ready at the packet input and the result output; request/grant to the units.
module trace_thread #(
  parameter int E = 7,
  parameter int M = 16,
  localparam int W = 1 + E + M,
  localparam int RW = (12 * W + 27 + 3 + 31) / 32   // words per response: F24_TRIANGLE_RECORD_WORDS
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  // packet in (trace_begin)
  input  logic                        valid_i,
  output logic                        ready_o,
  input  logic [2:0]                  flags_i,    // TRACE_SKIP_TOP, TRACE_ANY_HIT, TRACE_IDENTITY
  input  logic [3:0]                  active_i,   // (the rays' o and d: trace_core's)
  input  logic [4*(E+M+1)-1:0]        tmin_i,
  input  logic [4*(E+M+1)-1:0]        tmax_i,
  // hits out (TP_DONE)
  output logic                        valid_o,
  input  logic                        ready_i,
  output logic [3:0]                  hit_o,      // the rays with a hit (its record: trace_core's)
  output logic [4*(E+M+1)-1:0]        t_o,        // best_t: a hit's t where hit_o (trace_core puts +Inf for a miss)
  // the header's fields (the core's, hdr_ok_i when read)
  output logic                        hdr_want_o,  // waiting for the header
  input  logic                        hdr_ok_i,
  input  logic [31:0]                 hdr_instances_i,
  input  logic [31:0]                 hdr_top_nodes_i,
  input  logic [31:0]                 hdr_top_lists_i,
  // word read port (descriptors): RW words per response from the word address that trace_core
  // computes for the request (the record's region + its size x its index + RW x ld_sent_o)
  output logic                        mem_req_valid_o,
  input  logic                        mem_req_ready_i,
  output logic [2:0]                  ld_rec_o,    // the record: 0 the top node's word 1 (TRACE_SKIP_TOP), 1 a top-level
                                                   // list entry, 2 an instance, 3 an object, 4 a triangle
  output logic [31:0]                 ld_ix_o,     // its index (list entry, instance, object, triangle in the object's)
  output logic [31:0]                 tris_o,      // the object's triangle records' address (a triangle's region)
  output logic [1:0]                  ld_sent_o,   // the request's index in its record
  input  logic                        mem_rsp_valid_i,
  output logic [1:0]                  ld_got_o,    // the index of a response to this thread in its record
  input  logic [32*RW-1:0]            mem_rdata_i,
  input  logic                        node_rsp_i,  // a kd-node read of this thread answered
  output logic                        walk_read_o, // the walk step in flight read a kd node (so far)
  output logic                        waiting_o,   // an operation of this thread is in a unit
  output logic [3:0]                  slots_o,     // issue slots of the operation requested (thread_sched)
  output logic [1:0]                  step_ray_o,  // the ray of the batch's next step (the rays' fields in trace_core)
  output logic                        lo_zero_o,   // the step ray's object-space ray is the identity of its world ray
  output logic [11:0]                 id_sg_o,     // ... with these matrix signs (xform_identity), its low words zero
  // traversal unit
  output logic                        trav_req_o,
  input  logic                        trav_grant_i,
  output logic [1:0]                  trav_kind_o,
  output logic                        trav_level_o,
  output logic                        trav_obj_o,  // the object-space rays (else the world rays; both trace_core's)
  output logic [3:0]                  trav_lo_zero_o, // per ray: its object-space ray is the identity of the world ray
  output logic [4*12-1:0]             trav_id_sg_o, // ... with these matrix signs (ray i: bits 12i ..)
  output logic [4*(E+M+1)-1:0]        trav_tn_o,
  output logic [4*(E+M+1)-1:0]        trav_tf_o,
  output logic [4*(E+M+1)-1:0]        trav_best_o,
  output logic [3:0]                  trav_mask_o,
  output logic [31:0]                 trav_nodes_o,
  input  logic                        trav_done_i,
  input  logic [3:0]                  trav_mask_i,
  input  logic [4*(E+M+1)-1:0]        trav_tn_i,
  input  logic [4*(E+M+1)-1:0]        trav_tf_i,
  input  logic                        trav_have_cur_i,
  input  logic                        trav_leaf_i,
  input  logic [31:0]                 trav_leaf_first_i,
  input  logic [31:0]                 trav_leaf_count_i,
  input  logic [3:0]                  trav_leaf_mask_i,
  // list unit
  output logic                        list_req_o,
  input  logic                        list_grant_i,
  output logic                        list_level_o,
  output logic                        list_clear_o,
  output logic [31:0]                 list_lists_o,
  output logic [31:0]                 list_first_o,
  output logic [31:0]                 list_k_o,
  output logic [3:0]                  list_leaf_mask_o,
  output logic [3:0]                  list_alive_o,
  input  logic                        list_done_i,
  input  logic [31:0]                 list_key_i,
  input  logic [3:0]                  list_need_i,
  input  logic [31:0]                 list_k_i,
  // rebase unit
  output logic                        rb_req_o,
  input  logic                        rb_grant_i,
  output logic                        t0_zero_o,   // the ray's t0 is +0 (else trace_core's: adders, triangle test)
  output logic                        rb_leaf_o,   // a leaf's rebase: the object-space ray, te (else the world ray's: t0)
  input  logic                        rb_done_i,   // (its operands o, d and results p, te, t0: trace_core's)
  // the transformation unit's wide mode
  output logic                        xw_req_o,
  input  logic                        xw_grant_i,
  // (the instance's matrix and translation's low words, pass 0's origin p, pass 1's direction: trace_core's)
  output logic                        xw_point_o,
  input  logic                        xw_done_i,   // (its results, the object-space rays: trace_core's)
  // the triangle test (isect_rebased: the origin path, the transformations, the intersection, t0 + t)
  output logic                        is_req_o,
  input  logic                        is_grant_i,
  // (the triangle's record, p, te and the direction: trace_core's)
  output logic [E+M:0]                is_tmin_o,
  output logic [E+M:0]                is_tmax_o,
  input  logic                        is_done_i,
  input  logic                        is_hit_i,
  input  logic [E+M:0]                is_t_i,
  output logic [31:0]                 is_inst_o,   // the triangle's instance and index (a hit's record)
  output logic [31:0]                 is_tri_o,
  input  logic [E+M:0]                is_t_world_i,
  // 2 subtractors (one operation on 2 lanes: the relative distances)
  output logic                        add_req_o,
  input  logic                        add_grant_i,
  output logic [E+M:0]                add_a_o,     // best_t (tmin: trace_core's)
  input  logic                        add_done_i,
  input  logic [2*(E+M+1)-1:0]        add_r_i
);
  // memory image layout (docs/memory-image.md; hls/units/trace.c): the words read of a record (the
  // records' sizes and regions: trace_core's, which computes the requests' addresses)
  localparam int INST_READ = 17, OBJ_READ = 14;
  localparam logic [2:0] REC_NODE = 3'd0, REC_LIST = 3'd1, REC_INST = 3'd2, REC_OBJ = 3'd3, REC_TRI = 3'd4;
  // responses per record (the instance's 17 words the most) and the buffer they fill
  localparam int INST_RSP = (INST_READ + RW - 1) / RW, OBJ_RSP = (OBJ_READ + RW - 1) / RW;
  localparam int LBUF = RW * INST_RSP;

  // ---- state of the packet in flight (trace_state) ----
  // the FSM's states (trace_step's operations and their unit transactions)
  localparam logic [5:0]
    S_IDLE = 6'd0, S_CLR0 = 6'd1, S_LOAD = 6'd2, S_HDR = 6'd3, S_SC_GO = 6'd4, S_TRAV_WAIT = 6'd5,
    S_SC_DONE = 6'd6, S_START_GO = 6'd7, S_START_DONE = 6'd8, S_SINGLE_NODE = 6'd9, S_SINGLE_LIST = 6'd10, S_ROUTE = 6'd11,
    S_WALK_GO = 6'd12, S_WALK_DONE = 6'd13, S_LIST_GO = 6'd14, S_LIST_WAIT = 6'd15, S_BATCH = 6'd16,
    S_IX_LOAD = 6'd17, S_IX = 6'd18, S_IC_LOAD = 6'd19, S_IC_CLR = 6'd20, S_IC_CLIP = 6'd21, S_IC_DONE = 6'd22,
    S_TX_LOAD = 6'd23, S_DONE = 6'd24;
  logic [5:0] st, ret, ld_ret;
  // A batch (S_BATCH): one step of every ray of a mask through one per-ray unit, NPASS(op) passes of
  // the mask (passes outer, rays inner, the lowest ray first), issued on consecutive cycles as the
  // unit grants them (the core reserves the unit for the batch's slots, thread_sched) and collected
  // in the same order as the results come back, which may start before the last issue.
  localparam logic [3:0]
    B_RB_LEAF = 4'd0,  // rebase: the leaf's origins (rebase_leaf)
    B_RB_INST = 4'd1,  // rebase: the world rays to the top-level leaf (op_inst_xform)
    B_XW = 4'd2,       // xform_wide: pass 0 the rebased origins, pass 1 the directions (op_inst_xform)
    B_IC_ADD = 4'd3,   // adders: best_rel = best_t - t0, tmin_rel = tmin - t0 (relative_distances)
    B_TRI = 4'd4;      // isect_rebased: op_tri_xform and op_tri_isect, and best_t = t0 + t of a hit
  logic [3:0] bop;
  logic [3:0] bmask, itodo, ctodo;        // the batch's rays; the pass's rays to issue, to collect
  logic ipass, cpass, idone;              // the issue's and the collection's pass; all issued

  logic [2:0] flags;
  logic [3:0] active, alive, need;
  // the world rays (ro, rd) and the object-space rays (so, sd: high and low words) are trace_core's
  // (thread_ram); lo_zero[i]: ray i's object-space ray is xform_identity of its world ray with
  // the matrix signs id_sg[i] and low words zero (an identity instance's rays pass as wiring),
  // which trace_core makes as it reads the world ray
  logic [3:0] lo_zero;
  logic [11:0] id_sg [4];
  // the packet's tmin, read only by the subtractors (tmin_rel = tmin - t0), is trace_core's (thread_ram)
  logic [W-1:0] best_t [4], best_rel [4], tmin_rel [4];
  // t0 (an instance's entry distance, from its rebase) is trace_core's (thread_ram); t0_zero[i]:
  // ray i's is +0 (a new packet, an identity instance), read as +0 in its place
  logic [3:0] t0_zero;
  // the hits: hit[i] says ray i has one, whose t is best_t[i] (both written by each hit); its
  // instance, triangle, u, v and cos are trace_core's (thread_ram)
  logic [3:0] hit;
  logic level;
  logic [31:0] lists [2], leaf_first [2], leaf_count [2], k [2];
  logic [3:0] leaf_mask [2];
  logic have_cur [2];
  // ix: the index of the record the loader reads (the list entry's position, the instance, the
  // object, the triangle: then is_tri_o, the hit's record); inst: the instance (is_inst_o)
  logic [31:0] inst, ix, tris;
  // walk_read: the walk step in flight read a kd node (trace_core counts the step, C_STEPS, as its
  // result comes: walk_read_o)
  logic walk_read;
  // the loader: ld_n responses of RW words of record ld_rec (index ix) into lbuf, then ld_ret
  logic [31:0] lbuf [LBUF];
  logic [2:0] ld_rec;
  logic [1:0] ld_n, ld_sent, ld_got;
  // ld_req: requests of the load left to send (st == S_LOAD && ld_sent != ld_n) in a register of its
  // own, so that the word port's pick over the threads starts at a flip-flop (3 LUT6 levels later
  // before: with the pick and the port's ready back into ld_sent, 8 at 2 threads, 10 at 64)
  logic ld_req;
  // done: st == S_DONE in a register of its own (set by finish(), cleared as the packet leaves), so
  // that trace_core's output pick over the threads starts at a flip-flop (valid_o was 2 LUT6 levels
  // from st: the packet's path into the output register 10 at 64 threads, 8 from the register)
  logic done;

  // ---- the batch's issue ray (ir, lowest of itodo) and collection ray (cr, lowest of ctodo) ----
  function automatic logic [1:0] lowest(input logic [3:0] m);
    lowest = 2'd0;
    for (int i = 3; i >= 0; i--)
      if (m[i]) lowest = 2'(i);
  endfunction
  logic [1:0] ir, cr;
  assign ir = lowest(itodo);
  assign cr = lowest(ctodo);
  function automatic logic [31:0] popcount(input logic [3:0] m);
    popcount = {31'd0, m[0]} + {31'd0, m[1]} + {31'd0, m[2]} + {31'd0, m[3]};
  endfunction

  // ---- the records ----
  // lbuf keeps the words the FSM reads (the unit operands among them, the matrices, the
  // translation's low words, the triangle's record and the object's bounds, are trace_core's, in
  // thread_ram written from the same responses: the flip-flops of the words read nowhere here
  // are removed by synthesis)
  // the matrix's signs, all xform_identity reads of it (trace_core's identity)
  function automatic logic [11:0] signs();
    for (int j = 0; j < 12; j++) signs[j] = lbuf[j][W-1];
  endfunction

  // ---- the units ----
  logic [4*W-1:0] v_tmax, v_best_t, v_best_rel, v_tmin_rel;
  always_comb
    for (int i = 0; i < 4; i++) begin
      trav_id_sg_o[i*12 +: 12] = id_sg[i];
      v_best_t[i*W +: W] = best_t[i];
      v_best_rel[i*W +: W] = best_rel[i];
      v_tmin_rel[i*W +: W] = tmin_rel[i];
    end
  assign v_tmax = tmax_i;  // taken with the packet only (best_t holds it afterwards)
  assign trav_req_o = st == S_SC_GO || st == S_START_GO || st == S_WALK_GO || st == S_IC_CLIP;
  assign trav_obj_o = !(st == S_SC_GO || (st != S_IC_CLIP && !level));
  assign trav_lo_zero_o = lo_zero;
  assign trav_best_o = level ? v_best_rel : v_best_t;
  logic [4*W-1:0] clip_tn, clip_tf;   // the traversal unit's last result
  logic [3:0] clip_mask, r_leaf_mask;
  logic r_have_cur, r_leaf;
  logic [31:0] r_leaf_first, r_leaf_count;
  always_comb begin
    trav_kind_o = 2'd3;
    trav_level_o = level;
    trav_mask_o = alive;
    // the clips' [tn, tf]: the scene's [tmin, tmax] is the packet's [tmin_rel, best_rel] as it
    // enters (no batch before the scene clip writes them), the object's [tmin_rel, best_rel]: one
    // choice of two (a third, tmin and best_t, was 2 x 96 LUT4 more)
    trav_tn_o = st == S_SC_GO || st == S_IC_CLIP ? v_tmin_rel : clip_tn;
    trav_tf_o = st == S_SC_GO || st == S_IC_CLIP ? v_best_rel : clip_tf;
    unique case (st)
      S_SC_GO: begin
        trav_kind_o = 2'd0;
        trav_level_o = 1'b0;
        trav_mask_o = active;
      end
      S_IC_CLIP: begin
        trav_kind_o = 2'd1;
        trav_level_o = 1'b1;
        trav_mask_o = need;
      end
      S_START_GO: begin
        trav_kind_o = 2'd2;
        trav_mask_o = clip_mask;
      end
      default: ;
    endcase
  end
  assign trav_nodes_o = level ? lbuf[0] : hdr_top_nodes_i;
  // ---- the other units' operands ----
  assign list_req_o = st == S_CLR0 || st == S_IC_CLR || st == S_LIST_GO;
  assign list_clear_o = st != S_LIST_GO;
  assign list_level_o = st == S_CLR0 ? 1'b0 : st == S_IC_CLR ? 1'b1 : level;
  assign list_lists_o = lists[level];
  assign list_first_o = leaf_first[level];
  assign list_k_o = k[level];
  assign list_leaf_mask_o = leaf_mask[level];
  assign list_alive_o = alive;
  // ---- the batches' requests and operands (ray ir of pass ipass) ----
  logic batch_req;
  assign batch_req = st == S_BATCH && !idone;
  assign slots_o = st == S_BATCH ? 4'(popcount(bmask)) << (bop == B_XW) : 4'd1;
  // rebase: the leaf's origins (rebase_leaf, level 1) or the world ray to the top-level leaf (op_inst_xform)
  logic rb_leaf;
  assign rb_leaf = bop == B_RB_LEAF;
  assign rb_req_o = batch_req && (bop == B_RB_LEAF || bop == B_RB_INST);
  assign lo_zero_o = lo_zero[ir];
  assign id_sg_o = id_sg[ir];
  assign rb_leaf_o = rb_leaf;
  assign step_ray_o = ir;
  assign xw_req_o = batch_req && bop == B_XW;
  assign xw_point_o = !ipass;
  assign is_req_o = batch_req && bop == B_TRI;
  assign is_inst_o = inst;
  assign is_tri_o = ix;
  assign hit_o = hit;
  assign is_tmin_o = tmin_rel[ir];
  assign is_tmax_o = best_rel[ir];
  assign t0_zero_o = t0_zero[ir];

  // the subtractors: best_rel = best_t - t0, tmin_rel = tmin - t0
  assign add_req_o = batch_req && bop == B_IC_ADD;
  assign add_a_o = best_t[ir];

  // the batch's results: done of its unit, for ray cr of pass cpass
  logic batch_grant, batch_done;
  always_comb begin
    batch_grant = rb_grant_i;
    batch_done = rb_done_i;
    unique case (bop)
      B_XW: begin batch_grant = xw_grant_i; batch_done = xw_done_i; end
      B_IC_ADD: begin batch_grant = add_grant_i; batch_done = add_done_i; end
      B_TRI: begin batch_grant = is_grant_i; batch_done = is_done_i; end
      default: ;
    endcase
  end
  // the last step of the batch: the last ray of the last pass
  logic two_pass, i_last, c_last;
  assign two_pass = bop == B_XW;
  assign i_last = itodo == (4'd1 << ir) && ipass == two_pass;
  assign c_last = ctodo == (4'd1 << cr) && cpass == two_pass;

  assign mem_req_valid_o = ld_req;
  assign waiting_o = st == S_TRAV_WAIT || st == S_LIST_WAIT ||
                     (st == S_BATCH && {idone, ipass, itodo} != {1'b0, cpass, ctodo});
  assign ld_got_o = ld_got;
  assign ld_rec_o = ld_rec;
  assign ld_ix_o = ix;
  assign tris_o = tris;
  assign ld_sent_o = ld_sent;
  assign hdr_want_o = st == S_HDR;
  assign ready_o = st == S_IDLE;
  assign valid_o = done;
  assign t_o = v_best_t;
  assign walk_read_o = walk_read;

  // the loader: reads n responses of record rec (index ix) into lbuf through the word port, then
  // goes to next
  task automatic load(input logic [2:0] rec, input logic [1:0] n, input logic [5:0] next);
    ld_rec <= rec;
    ld_n <= n;
    ld_sent <= '0;
    ld_req <= n != '0;
    ld_got <= '0;
    ld_ret <= next;
    st <= S_LOAD;
  endtask
  // the packet's end: its hits wait in S_DONE for the core's output
  task automatic finish();
    done <= 1'b1;
    st <= S_DONE;
  endtask
  // a batch of operation op for the rays of mask (not empty)
  task automatic batch(input logic [3:0] op, input logic [3:0] mask);
    bop <= op;
    bmask <= mask;
    itodo <= mask;
    ctodo <= mask;
    ipass <= 1'b0;
    cpass <= 1'b0;
    idone <= 1'b0;
    st <= S_BATCH;
  endtask

  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      st <= S_IDLE;
      ld_req <= 1'b0;
      done <= 1'b0;
    end else begin
      if (node_rsp_i) walk_read <= 1'b1;
      unique case (st)
        S_IDLE:
          if (valid_i) begin
            flags <= flags_i;
            active <= active_i;
            alive <= active_i;
            level <= 1'b0;
            have_cur[0] <= 1'b0;
            have_cur[1] <= 1'b0;
            for (int i = 0; i < 4; i++) begin
              tmin_rel[i] <= tmin_i[i*W +: W];
              best_t[i] <= v_tmax[i*W +: W];
              best_rel[i] <= v_tmax[i*W +: W];
              t0_zero[i] <= 1'b1;
            end
            hit <= '0;
            st <= S_CLR0;
          end
        S_CLR0:
          if (list_grant_i) st <= S_HDR;
        S_LOAD: begin
          if (ld_req && mem_req_ready_i) begin
            ld_sent <= ld_sent + 1'b1;
            ld_req <= ld_sent + 1'b1 != ld_n;
          end
          if (mem_rsp_valid_i) begin
            for (int r = 0; r < INST_RSP; r++)
              if (ld_got == 2'(r))
                for (int j = 0; j < RW; j++) lbuf[r * RW + j] <= mem_rdata_i[32 * j +: 32];
            ld_got <= ld_got + 1'b1;
            if (ld_got + 1'b1 == ld_n) st <= ld_ret;
          end
        end
        S_HDR: if (hdr_ok_i) st <= S_SC_GO;
        // traversal unit: an operation issued, its result awaited (ret: what follows)
        S_SC_GO: if (trav_grant_i) begin ret <= S_SC_DONE; st <= S_TRAV_WAIT; end
        S_START_GO: if (trav_grant_i) begin ret <= S_START_DONE; st <= S_TRAV_WAIT; end
        S_WALK_GO: if (trav_grant_i) begin ret <= S_WALK_DONE; walk_read <= 1'b0; st <= S_TRAV_WAIT; end
        S_IC_CLIP: if (trav_grant_i) begin ret <= S_IC_DONE; st <= S_TRAV_WAIT; end
        S_TRAV_WAIT:
          if (trav_done_i) begin
            clip_mask <= trav_mask_i;
            clip_tn <= trav_tn_i;
            clip_tf <= trav_tf_i;
            r_have_cur <= trav_have_cur_i;
            r_leaf <= trav_leaf_i;
            r_leaf_first <= trav_leaf_first_i;
            r_leaf_count <= trav_leaf_count_i;
            r_leaf_mask <= trav_leaf_mask_i;
            st <= ret;
          end
        S_SC_DONE:  // op_scene_clip
          if (clip_mask == 0 || hdr_instances_i == 0) finish();
          else if (flags[0]) begin  // enter_single_object: its one-leaf list
            need <= clip_mask;
            leaf_count[0] <= '0;
            k[0] <= '0;
            load(REC_NODE, 2'd1, S_SINGLE_NODE);
          end else begin
            lists[0] <= hdr_top_lists_i;
            st <= S_START_GO;
          end
        S_START_DONE: begin
          have_cur[level] <= 1'b1;
          leaf_count[level] <= '0;
          k[level] <= '0;
          st <= S_WALK_GO;
        end
        S_SINGLE_NODE: begin
          ix <= lbuf[0];
          load(REC_LIST, 2'd1, S_SINGLE_LIST);
        end
        S_SINGLE_LIST: begin
          inst <= lbuf[0];
          ix <= lbuf[0];
          st <= S_IX_LOAD;
        end
        S_ROUTE:  // route_after_list: the next entry, the next walk step, back up, or done
          if (alive == 0) finish();
          else if (k[level] < leaf_count[level]) st <= S_LIST_GO;
          else if (have_cur[level]) st <= S_WALK_GO;
          else if (!level) finish();
          else level <= 1'b0;
        S_WALK_DONE: begin  // op_walk
          have_cur[level] <= r_have_cur;
          if (r_leaf) begin
            leaf_first[level] <= r_leaf_first;
            leaf_count[level] <= r_leaf_count;
            leaf_mask[level] <= r_leaf_mask;
            k[level] <= '0;
          end
          st <= S_ROUTE;
        end
        S_LIST_GO: if (list_grant_i) st <= S_LIST_WAIT;
        S_LIST_WAIT:  // op_list
          if (list_done_i) begin
            k[level] <= list_k_i;
            need <= list_need_i;
            ix <= list_key_i;
            if (!level) inst <= list_key_i;
            ret <= list_need_i == 0 ? S_ROUTE : level ? S_TX_LOAD : S_IX_LOAD;
            // rebase_leaf: the leaf opens
            if (level && k[1] == 0 && (leaf_mask[1] & alive) != 0) batch(B_RB_LEAF, leaf_mask[1] & alive);
            else st <= list_need_i == 0 ? S_ROUTE : level ? S_TX_LOAD : S_IX_LOAD;
          end
        // a batch: its issues as granted, its results as they come back, then what follows it
        S_BATCH: begin
          if (batch_grant) begin
            if (i_last) idone <= 1'b1;
            else if (itodo == (4'd1 << ir)) begin  // the pass's last ray: the second pass
              itodo <= bmask;
              ipass <= 1'b1;
            end else itodo[ir] <= 1'b0;
          end
          if (batch_done) begin
            if (ctodo == (4'd1 << cr)) begin
              ctodo <= bmask;
              cpass <= 1'b1;
            end else ctodo[cr] <= 1'b0;
            unique case (bop)
              B_RB_INST: t0_zero[cr] <= 1'b0;  // t0, p and a leaf's te: trace_core's thread_ram
              B_XW: lo_zero[cr] <= 1'b0;  // so or sd: trace_core's thread_ram
              B_IC_ADD: begin
                best_rel[cr] <= add_r_i[0 +: W];
                tmin_rel[cr] <= add_r_i[W +: W];
              end
              B_TRI:
                if (is_hit_i) begin
                  best_rel[cr] <= is_t_i;
                  best_t[cr] <= is_t_world_i;
                  hit[cr] <= 1'b1;
                  if (flags[1]) alive[cr] <= 1'b0;
                end
              default: ;
            endcase
            // the batch's last result: what follows it
            if (c_last)
              unique case (bop)
                B_RB_LEAF: st <= ret;
                B_RB_INST: batch(B_XW, need);
                B_XW: st <= S_IC_LOAD;
                B_IC_ADD: st <= S_IC_CLIP;
                default: st <= S_ROUTE;  // B_TRI
              endcase
          end
        end
        // op_inst_xform
        S_IX_LOAD: load(REC_INST, 2'(INST_RSP), S_IX);
        S_IX: begin
          ix <= lbuf[12];
          // an identity instance, or TRACE_IDENTITY's single one (enter_single_object): the rays pass
          // as wiring, and the clip follows in the same operation
          if (lbuf[13][0] || flags[2]) begin
            for (int i = 0; i < 4; i++)
              if (need[i]) begin
                id_sg[i] <= signs();
                lo_zero[i] <= 1'b1;
                t0_zero[i] <= 1'b1;
              end
            st <= S_IC_LOAD;
          end else begin
            batch(B_RB_INST, need);  // per ray: rebase to the top-level leaf, then the origins and directions wide
          end
        end
        // op_inst_clip / inst_clip
        S_IC_LOAD: load(REC_OBJ, 2'(OBJ_RSP), S_IC_CLR);
        S_IC_CLR: if (list_grant_i) batch(B_IC_ADD, need);
        S_IC_DONE:
          if (clip_mask == 0) st <= S_ROUTE;
          else begin
            tris <= lbuf[2];
            lists[1] <= lbuf[1];
            level <= 1'b1;
            st <= S_START_GO;
          end
        // op_tri_xform, op_tri_isect: the triangle's record, then its batches
        S_TX_LOAD: begin
          batch(B_TRI, need);
          load(REC_TRI, 2'd1, S_BATCH);
        end
        S_DONE:
          if (ready_i) begin
            done <= 1'b0;
            st <= S_IDLE;
          end
        default: st <= S_IDLE;
      endcase
    end
endmodule
