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
// them, an entry writes at most one slot per ray) and 4 of 2*THREADS x 3 bits, each with one
// synchronous read and one write port (block RAM or LUT RAM).
// Pipeline (LATENCY 3, one operation per cycle, II = 1):
//   S0 (input cycle): mailbox memories and memory port addressed (mem_re_o, mem_addr_o);
//   S1: mailbox words and the list entry (mem_rdata_i) arrive; 32 KW-bit equality comparators;
//   S2: seen bits registered; need = mask & ~seen, the slot writes (the mailboxes are written at
//       the end of S2) and the result registers;
//   S3: valid_o with the result.
// Memory wait (mem_valid_i): an entry whose list word is not yet at mem_rdata_i waits in S1 (the
// DynRTP's list cache answers a hit 2 cycles after the read, a miss after its fill, rtl/dynrtp.sv);
// S2 and the output drain meanwhile, and S0 takes nothing. With mem_valid_i = 1 (a memory that
// answers in the next cycle) the pipeline is the 3 cycles above.
// A thread has one operation in flight in the DynRTP; should a second operation of the same
// thread and level arrive while the first is in S1 or S2, ready_o stays low until the first has
// written its mailboxes (so back-to-back operations of one thread give the C unit's results:
// trace_core's issue FIFO can hold a thread's clear while the unit waits for a list word, and pass
// that thread's next entry right behind it).
// Memory read port: mem_rdata_i must hold mem[mem_addr_o] from the cycle mem_valid_i rises after
// mem_re_o until the next mem_re_o (a block RAM with read enable: mem_valid_i = 1; in the DynRTP
// the list cache behind a holding register, rtl/dynrtp.sv).
// Resources (THREADS = 64, KW = 32): 32 x 128 x 32 + 4 x 128 x 3 bits of mailbox memory
// (131,456 bits), 32 KW-bit equality comparators, one 3-input AW-bit adder, one AW-bit
// incrementer, 4 3-bit incrementers, about 120 + 2 AW flip-flops of pipeline (docs/synth.md).
// Handshake: valid/ready (the pipeline advances when ready_i or nothing is at the output).
module list_unit #(
  parameter int THREADS = 64,
  parameter int AW = 32,        // word address width (lists, first, k)
  parameter int KW = 32,        // list entry (key) width: a memory word
  parameter int LATENCY = 3     // fixed by the pipeline; documents the cycle model's default
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
  output logic                        mem_re_o,
  output logic [AW-1:0]               mem_addr_o,
  input  logic [KW-1:0]               mem_rdata_i,
  input  logic                        mem_valid_i, // mem_rdata_i holds the last read's word
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
  localparam int SLOTS = 8;              // TRACE_MAILBOX
  localparam logic [KW-1:0] NO_HIT = '1; // TRACE_NO_HIT
  if (LATENCY != 3) begin : g_latency_check
    $error("list_unit: LATENCY is 3 (the pipeline's registers)");
  end

  // out: S2 moves to the output; en: S0 and S1 move too (S1's list word is there)
  logic out, en, take, hazard;
  logic [IW-1:0] idx_in;
  assign out = ready_i || !valid_o;
  assign en = out && (!s1_valid || s1_clear || mem_valid_i);
  assign idx_in = {thread_i, level_i};

  // pipeline registers
  logic s1_valid, s1_clear, s2_valid, s2_clear;
  logic [IW-1:0] s1_idx, s2_idx;
  logic [3:0] s1_mask, s2_mask, s2_seen;
  logic [AW-1:0] s1_k1, s2_k1;
  logic [KW-1:0] s2_key;
  logic [2:0] s2_next [4];

  assign hazard = (s1_valid && s1_idx == idx_in) || (s2_valid && s2_idx == idx_in);
  assign ready_o = en && !hazard;
  assign take = valid_i && ready_o;
  assign mem_re_o = take && !clear_i;
  assign mem_addr_o = lists_i + first_i + k_i;

  // mailbox memories: key[ray][slot] and next[ray], read in S0, written at the end of S2
  logic [KW-1:0] key_rd [4][SLOTS];
  logic [2:0] next_rd [4];
  for (genvar r = 0; r < 4; r++) begin : g_ray
    logic [2:0] next_mem [2*THREADS];
    logic wr;
    assign wr = out && s2_valid && (s2_clear || (s2_mask[r] && !s2_seen[r]));
    always_ff @(posedge clk_i) begin
      if (en) next_rd[r] <= next_mem[idx_in];
      if (wr) next_mem[s2_idx] <= s2_clear ? 3'd0 : s2_next[r] + 3'd1;
    end
    for (genvar j = 0; j < SLOTS; j++) begin : g_slot
      logic [KW-1:0] key_mem [2*THREADS];
      always_ff @(posedge clk_i) begin
        if (en) key_rd[r][j] <= key_mem[idx_in];
        if (wr && (s2_clear || s2_next[r] == 3'(j))) key_mem[s2_idx] <= s2_clear ? NO_HIT : s2_key;
      end
    end
  end

  // S1: the comparators
  logic [3:0] seen;
  always_comb begin
    for (int r = 0; r < 4; r++) begin
      seen[r] = 1'b0;
      for (int j = 0; j < SLOTS; j++) seen[r] = seen[r] | (key_rd[r][j] == mem_rdata_i);
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_valid <= 1'b0;
      s2_valid <= 1'b0;
      valid_o <= 1'b0;
    end else if (out) begin
      s1_valid <= en ? take : s1_valid;
      s2_valid <= en && s1_valid;  // a bubble while S1 waits for its word
      valid_o <= s2_valid && !s2_clear;
    end
  end

  always_ff @(posedge clk_i) begin
    if (en) begin
      s1_clear <= clear_i;
      s1_idx <= idx_in;
      s1_mask <= leaf_mask_i & alive_i;
      s1_k1 <= k_i + AW'(1);
      s2_clear <= s1_clear;
      s2_idx <= s1_idx;
      s2_mask <= s1_mask;
      s2_seen <= seen;
      s2_key <= mem_rdata_i;
      s2_k1 <= s1_k1;
      for (int r = 0; r < 4; r++) s2_next[r] <= next_rd[r];
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
