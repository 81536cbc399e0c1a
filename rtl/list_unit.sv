// list_unit: the mailboxed list unit (paper section 3, Figure 2 path c; the mailboxes of section
// 2.3) as hls/units/list_unit.c does it, bit for bit. One operation per transaction:
//   * entry (clear_i = 0): the next entry of the thread's current leaf, at word address
//     a = lists_i + first_i + k_i (the list address adder), is read through the memory read port
//     (key_o = mem[a], k_o = k_i + 1). Every ray of leaf_mask_i & alive_i checks it against its
//     mailbox of the level level_i (8 keys): a ray that holds it skips it (skip_o), any other
//     remembers it round robin (slot next, next = next + 1 mod 8) and needs it (need_o): the rays
//     that go on to the transformation unit (list_unit_entry).
//   * clear (clear_i = 1): empties the 4 mailboxes of (thread_i, level_i): every key becomes
//     NO_HIT (all ones), next = 0 (list_mailboxes_clear). No result leaves the unit for it.
// State: per thread and level (index {thread, level}) 4 rays x 8 keys of KW bits and 4 round-robin
// pointers, held in 32 memories of 2*THREADS x KW bits (one per ray and slot: a clear writes all of
// them, an entry writes at most one slot per ray) and one of 2*THREADS x 12 bits (the 4 rays'
// pointers, each written alone), each with one synchronous read and one write port (block RAM or
// LUT RAM).
// Pipeline (one operation per cycle, II = 1), not blocking on a list word: an entry's read goes
// out when the unit takes it, and the entry waits for its word in a queue while later entries'
// reads go out behind it (up to DEPTH + 1 operations in the unit, their reads in flight at once):
//   F (input cycle): the operation into the queue (a sync_fifo of DEPTH, then the head register
//       H), an entry's word address a into the read request register (mem_req_o from the next
//       cycle until mem_req_ready_i takes it);
//   H: the queue's oldest operation; its mailbox words (key and round-robin pointer memories) are
//       read while it waits, addressed by the operation that is in H in the next cycle;
//   C: H leaves when its word is the word queue's head (the answers in request order: a
//       sync_fifo of 2 DEPTH, more than the reads that can be in flight) and its mailbox words
//       are read after the last write to them: 32 KW-bit equality comparators;
//   S2: seen bits registered; need = mask & ~seen, the slot writes (the mailboxes are written at
//       the end of S2) and the result registers;
//   S3: valid_o with the result.
// So an entry's result leaves 2 cycles after its word has been answered (mem_rsp_valid_i), as
// when the unit waited in its pipeline for the word (until 2026-11-29: one read in flight, the
// unit taking nothing while a list word missed in the DynRTP's list cache), a clear's 2 cycles
// after it is in H; the results in the order the operations came in. A memory answering in the
// cycle after the request: 5 cycles from F to valid_o. In the DynRTP (rtl/README.md, "The list unit
// without blocking"; saarcor render SCENE --width 32 --height 24 --max-depth 3 --mode rtl, 2026-11-29)
// room at 32 blocks 137,273 -> 129,088 cycles, at 64 153,636 -> 127,993; at one thread the same
// (cornell 407,290).
// Order per thread and level: H's mailbox words are its own after every write of an earlier
// operation: "fresh" (registered) says that the words read in the cycle before are H's and no
// operation that writes that mailbox was in S2 or leaving C then (a clear and its thread's next
// entry back to back wait 2 cycles more).
// Memory read port: a request (mem_req_o, mem_addr_o) held until mem_req_ready_i; the answers in
// request order, one a cycle, always taken (mem_rsp_valid_i with mem_rdata_i; in the DynRTP the
// list cache, rtl/dynrtp.sv, hit 3 cycles after the request).
// Resources (THREADS = 64, KW = 32, DEPTH = 8): 32 x 128 x 32 + 4 x 128 x 3 bits of mailbox
// memory (131,456 bits), 32 KW-bit equality comparators, one 3-input AW-bit adder, one AW-bit
// incrementer, 4 3-bit incrementers; the queues DEPTH x (TW + 6 + AW) and 2 DEPTH x KW bits of
// LUT RAM; about 150 + 3 AW + KW flip-flops of registers. synth_xilinx (scripts/synth.py --levels
// list_unit THREADS=64 --hier, 2026-11-29): 5 LUT6 levels, 1,008 LUT6, 287 flip-flops, 32 RAMB18E1,
// 8 RAM64M, 14 RAM32M (before the queue: 4, 974, 230, 32, 8, 0; docs/synth.md). synth_ice40
// (scripts/synth.py --ice40 list_unit THREADS=64, 2026-11-30): 2,532 SB_LUT4, 1,306 flip-flops,
// 65 SB_RAM40_4K (64 for the keys, 128 of 256 rows used; 1 for the pointers, 4 with a memory per ray).
// Handshake: valid/ready (the pipeline advances when ready_i or nothing is at the output).
module list_unit #(
  parameter int THREADS = 64,
  parameter int AW = 32,        // word address width (lists, first, k)
  parameter int KW = 32,        // list entry (key) width: a memory word
  parameter int DEPTH = 8       // the operation queue (a power of 2): list reads in flight up to DEPTH + 1
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  input  logic                        valid_i,
  output logic                        ready_o,
  input  logic [$clog2(THREADS)-1:0]  thread_i,
  input  logic                        level_i,    // 0: top level (instances), 1: bottom (triangles)
  input  logic                        clear_i,
  input  logic [AW-1:0]               lists_i,    // the tree's list region
  input  logic [AW-1:0]               first_i,    // the leaf's first entry
  input  logic [AW-1:0]               k_i,        // entries of the leaf done
  input  logic [3:0]                  leaf_mask_i,
  input  logic [3:0]                  alive_i,
  output logic                        mem_req_o,
  input  logic                        mem_req_ready_i,
  output logic [AW-1:0]               mem_addr_o,
  input  logic                        mem_rsp_valid_i, // the answers in request order, always taken
  input  logic [KW-1:0]               mem_rdata_i,
  output logic                        valid_o,
  input  logic                        ready_i,
  output logic [$clog2(THREADS)-1:0]  thread_o,
  output logic                        level_o,
  output logic [KW-1:0]               key_o,
  output logic [3:0]                  need_o,
  output logic [3:0]                  skip_o,
  output logic [AW-1:0]               k_o
);
  localparam int TW = $clog2(THREADS);
  localparam int IW = TW + 1;            // mailbox index {thread, level}
  localparam int OW = IW + 1 + 4 + AW;   // a queued operation: index, clear, mask, k + 1
  localparam int SLOTS = 8;              // TRACE_MAILBOX
  localparam logic [KW-1:0] NO_HIT = '1; // TRACE_NO_HIT

  logic req_free, q_ready, take, q_valid, q_pop, w_valid, out, pop, h_valid, h_clear, fresh;
  logic [OW-1:0] q_head;
  logic [KW-1:0] w_head;
  logic [IW-1:0] h_idx, q_idx, rd_idx;
  logic [3:0] h_mask;
  logic [AW-1:0] h_k1;

  // F: the operation into the queue and an entry's read into the request register
  assign req_free = !mem_req_o || mem_req_ready_i;
  assign ready_o = req_free && q_ready;
  assign take = valid_i && ready_o;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) mem_req_o <= 1'b0;
    else if (req_free) mem_req_o <= take && !clear_i;
  end
  always_ff @(posedge clk_i) if (take && !clear_i) mem_addr_o <= lists_i + first_i + k_i;

  sync_fifo #(.W(OW), .DEPTH(DEPTH)) u_ops (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(valid_i && req_free), .ready_o(q_ready),
    .data_i({thread_i, level_i, clear_i, leaf_mask_i & alive_i, k_i + AW'(1)}), .valid_o(q_valid), .ready_i(q_pop),
    .data_o(q_head));

  // the answered words, in request order (the reads in flight never exceed the operations held)
  /* verilator lint_off PINCONNECTEMPTY */
  sync_fifo #(.W(KW), .DEPTH(2 * DEPTH)) u_words (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(mem_rsp_valid_i), .ready_o(), .data_i(mem_rdata_i),
    .valid_o(w_valid), .ready_i(pop && !h_clear), .data_o(w_head));
  /* verilator lint_on PINCONNECTEMPTY */

  // H: the oldest operation; pop: it leaves (C) with its word and its mailbox words
  assign out = ready_i || !valid_o;
  assign pop = out && h_valid && fresh && (h_clear || w_valid);
  assign q_pop = !h_valid || pop;
  assign q_idx = q_head[OW-1 -: IW];
  assign rd_idx = q_pop ? q_idx : h_idx;  // the operation in H next cycle

  // S2 registers
  logic s2_valid, s2_clear;
  logic [IW-1:0] s2_idx;
  logic [3:0] s2_mask, s2_seen;
  logic [AW-1:0] s2_k1;
  logic [KW-1:0] s2_key;
  logic [2:0] s2_next [4];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      h_valid <= 1'b0;
      fresh <= 1'b0;
      s2_valid <= 1'b0;
      valid_o <= 1'b0;
    end else begin
      if (q_pop) h_valid <= q_valid;
      // the words read now are the next H's unless an operation of its mailbox writes them later
      fresh <= (q_pop ? q_valid : h_valid) && !(s2_valid && s2_idx == rd_idx) && !(pop && h_idx == rd_idx);
      if (out) begin
        s2_valid <= pop;
        valid_o <= s2_valid && !s2_clear;
      end
    end
  end
  always_ff @(posedge clk_i) if (q_pop) {h_idx, h_clear, h_mask, h_k1} <= q_head;

  // mailbox memories: key[ray][slot] and next[ray], read every cycle for the next H, written at
  // the end of S2
  // The 4 rays' pointers are one memory of 12-bit words, each ray's 3 bits written on their own (a
  // write mask): one block RAM's 16-bit rows instead of four blocks with 3 of 16 bits used.
  logic [KW-1:0] key_rd [4][SLOTS];
  logic [11:0] next_rd;                   // ray r's pointer at 3 r
  logic [3:0] wr;
  logic [11:0] next_mem [2*THREADS];
  always_ff @(posedge clk_i) begin
    next_rd <= next_mem[rd_idx];
    for (int r = 0; r < 4; r++)
      if (wr[r]) next_mem[s2_idx][3*r +: 3] <= s2_clear ? 3'd0 : s2_next[r] + 3'd1;
  end
  for (genvar r = 0; r < 4; r++) begin : g_ray
    assign wr[r] = out && s2_valid && (s2_clear || (s2_mask[r] && !s2_seen[r]));
    for (genvar j = 0; j < SLOTS; j++) begin : g_slot
      logic [KW-1:0] key_mem [2*THREADS];
      always_ff @(posedge clk_i) begin
        key_rd[r][j] <= key_mem[rd_idx];
        if (wr[r] && (s2_clear || s2_next[r] == 3'(j))) key_mem[s2_idx] <= s2_clear ? NO_HIT : s2_key;
      end
    end
  end

  // C: the comparators
  logic [3:0] seen;
  always_comb begin
    for (int r = 0; r < 4; r++) begin
      seen[r] = 1'b0;
      for (int j = 0; j < SLOTS; j++) seen[r] = seen[r] | (key_rd[r][j] == w_head);
    end
  end

  always_ff @(posedge clk_i) begin
    if (pop) begin
      s2_clear <= h_clear;
      s2_idx <= h_idx;
      s2_mask <= h_mask;
      s2_seen <= seen;
      s2_key <= w_head;
      s2_k1 <= h_k1;
      for (int r = 0; r < 4; r++) s2_next[r] <= next_rd[3*r +: 3];
    end
    if (out) begin
      {thread_o, level_o} <= s2_idx;
      key_o <= s2_key;
      need_o <= s2_mask & ~s2_seen;
      skip_o <= s2_mask & s2_seen;
      k_o <= s2_k1;
    end
  end
endmodule
