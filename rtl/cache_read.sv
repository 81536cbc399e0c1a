// cache_read: a read port of WORDS consecutive memory words through one direct-mapped cache
// (cache_dm), answered in request order (paper section 3, "Memory interface": how the DynRTP's
// units read through their caches; tb/cycle/mem_iface.c mem_iface_read, one lookup per line the
// read touches). The units' ports (trav_unit's kd-node port, the core's descriptor word port,
// list_unit's read port) take their answers in request order, while cache_dm answers as soon as a
// line is there (hits under misses): each read gets a slot of a ring of OUTSTANDING, its lookups
// carry {slot, part} as their id, and the words are collected into the slot; the oldest slot
// leaves when all its lookups are back. A read that crosses a line boundary (a kd node at an odd
// word address) makes a second lookup of the next line in the following cycle, as mem_iface_read
// loops over the lines.
// The front: a read's line (word address / LW, LW = LINE_BYTES / 4 words), the line's index in
// the cache (line mod LINES) and the read's offset in the line (word address mod LW). With LW and
// LINES powers of two they are bit fields and the first lookup is made in the request cycle. Else
// (the matrix cache: lines of one 10-word triangle record, 153 of them, at e7m16) there is no
// divider, whose constant division of 32 bits is a 70-level LUT network: the address is a sum of
// CB-bit chunks c_k 2^(CB k), and per chunk three tables give floor(c_k 2^(CB k) / LW), that mod
// LINES, and c_k 2^(CB k) mod LW. Stage F (the request cycle) looks them up and adds each kind as
// a balanced tree; the next cycle adds the remainders' carry floor(sum r / LW) to the line and to
// its residue, reduces the residue mod LINES by comparisons with its multiples and makes the first
// lookup, its index read straight into the cache's arrays (cache_dm's S0). So the matrix cache
// keeps the latency it had when cache_dm took a cycle for the index.
// The words: a response's line is rotated once by the read's offset, which its lookup's id
// carries with {slot, part} (word j of the read is the line's word (off + j) mod LW, from the
// second line when off + j >= LW) and written into the slot's words that lie in it; each word of
// the ring is a column of OUTSTANDING entries in distributed RAM, written at the responding slot
// and read at the oldest.
// Latency: the cache's (hit 2 cycles; a miss its fill + 1) + 1 for the ring, + 1 for stage F
// (the matrix cache: hit 4); throughput 1 read per cycle (a read of two lines: 1 per 2 cycles).
// Resources: cache_dm's (its ids log2 LW + log2 OUTSTANDING + 1 bits); the ring WORDS x
// OUTSTANDING x 32 bits of LUT RAM and OUTSTANDING x 4 flip-flops; the rotation WORDS x 32 LW-to-1 multiplexers; stage F 3 x 7 tables of
// 32 entries, three adder trees and its registers.
module cache_read #(
  parameter int LINE_BYTES = 8,
  parameter int SIZE_BYTES = 4096,
  parameter int WORDS = 2,          // words per read: 1 .. a line's (LINE_BYTES / 4)
  parameter int OUTSTANDING = 16    // reads in flight (a power of two)
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic                     flush_i,
  input  logic                     req_valid_i,
  output logic                     req_ready_o,
  input  logic [31:0]              req_addr_i,    // word address
  output logic                     rsp_valid_o,   // in request order; always taken
  output logic [32*WORDS-1:0]      rsp_data_o,    // word j at bits 32 j
  output logic                     mem_req_valid_o,
  input  logic                     mem_req_ready_i,
  output logic [31:0]              mem_req_addr_o,
  input  logic                     mem_rsp_valid_i,
  input  logic [8*LINE_BYTES-1:0]  mem_rsp_data_i
);
  localparam int LW = LINE_BYTES / 4;               // words per line
  localparam int LINES = SIZE_BYTES / LINE_BYTES;
  localparam int IXW = LINES > 1 ? $clog2(LINES) : 1;
  localparam int SW = $clog2(OUTSTANDING);
  localparam int OW = LW > 1 ? $clog2(LW) : 1;
  localparam bit FIELDS = (LW & (LW - 1)) == 0 && (LINES & (LINES - 1)) == 0;
  if (WORDS < 1 || WORDS > LW || (1 << SW) != OUTSTANDING) begin : g_check
    $error("cache_read: WORDS 1 .. LINE_BYTES / 4 (a read touches at most two lines), OUTSTANDING a power of two");
  end

  // ---- the ring of reads ----
  logic [SW-1:0] head, tail;
  logic [SW:0] used;
  logic [1:0] need [OUTSTANDING], got [OUTSTANDING];
  logic room, take;
  assign room = used != (SW + 1)'(OUTSTANDING);

  // ---- the front: the read whose first lookup is next (f_*) ----
  logic f_valid, first;
  logic [SW-1:0] f_slot;
  logic [31:0] f_line;
  logic [IXW-1:0] f_idx;
  logic [OW-1:0] f_off;
  logic second_q, c_ready;
  if (FIELDS) begin : g_fields
    assign f_valid = req_valid_i && room;
    assign f_slot = tail;
    assign f_line = req_addr_i >> $clog2(LW);
    assign f_idx = IXW'(f_line);
    assign f_off = OW'(req_addr_i & 32'(LW - 1));
    assign req_ready_o = room && !second_q && c_ready;
  end else begin : g_tables
    localparam int CB = 5;
    localparam int CHUNKS = (32 + CB - 1) / CB;
    localparam int RW = $clog2(CHUNKS * (LW - 1) + 1);        // the remainders' sum
    localparam int MW = $clog2(CHUNKS * (LINES - 1) + LW);    // the residues' sum and carry
    // the tables of chunk k: floor(v 2^(CB k) / LW), its residue mod LINES, v 2^(CB k) mod LW
    function automatic logic [31:0] quot(input int k, input int v);
      quot = 32'((64'(v) << (CB * k)) / 64'(LW));
    endfunction
    function automatic logic [MW-1:0] resid(input int k, input int v);
      resid = MW'(((64'(v) << (CB * k)) / 64'(LW)) % 64'(LINES));
    endfunction
    function automatic logic [RW-1:0] rem(input int k, input int v);
      rem = RW'((64'(v) << (CB * k)) % 64'(LW));
    endfunction
    logic [31:0] q [CHUNKS];
    logic [MW-1:0] m [CHUNKS];
    logic [RW-1:0] r [CHUNKS];
    for (genvar k = 0; k < CHUNKS; k++) begin : g_chunk
      logic [CB-1:0] c;
      assign c = CB'(req_addr_i >> (CB * k));
      always_comb begin
        q[k] = '0;
        m[k] = '0;
        r[k] = '0;
        for (int v = 0; v < (1 << CB); v++)
          if (c == CB'(v)) begin
            q[k] = quot(k, v);
            m[k] = resid(k, v);
            r[k] = rem(k, v);
          end
      end
    end
    // stage F's registers: the three sums, as balanced trees of adders (three adder levels)
    logic a_valid;
    logic [SW-1:0] a_slot;
    logic [31:0] a_q;
    logic [MW-1:0] a_m;
    logic [RW-1:0] a_r;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) a_valid <= 1'b0;
      else if (take) a_valid <= 1'b1;
      else if (first) a_valid <= 1'b0;
    end
    always_ff @(posedge clk_i) begin
      if (take) begin
        a_slot <= tail;
        a_q <= ((q[0] + q[1]) + (q[2] + q[3])) + ((q[4] + q[5]) + q[6]);
        a_m <= ((m[0] + m[1]) + (m[2] + m[3])) + ((m[4] + m[5]) + m[6]);
        a_r <= ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + r[6]);
      end
    end
    if (CHUNKS != 7) begin : g_chunks
      $error("cache_read: the adder trees are written for 7 chunks of 5 bits");
    end
    // the next cycle: the remainders' carry into the line and its residue, the residue mod LINES
    logic [OW-1:0] carry;
    logic [MW-1:0] t, multiple;
    always_comb begin
      carry = '0;
      f_off = '0;
      for (int v = 0; v < (1 << RW); v++)
        if (a_r == RW'(v)) begin
          carry = OW'(v / LW);
          f_off = OW'(v % LW);
        end
      t = a_m + MW'(carry);
      multiple = '0;
      for (int k = 1; k * LINES < (1 << MW); k++)
        if (t >= MW'(k * LINES)) multiple = MW'(k * LINES);
    end
    assign f_valid = a_valid;
    assign f_slot = a_slot;
    assign f_line = a_q + 32'(carry);
    assign f_idx = IXW'(t - multiple);
    assign req_ready_o = room && (!a_valid || first);
  end
  assign take = req_valid_i && req_ready_o;

  // ---- the lookups: a read's first line, or the second line of the read before ----
  logic [SW-1:0] second_slot;
  logic [OW-1:0] second_off;
  logic [31:0] second_line;
  logic [IXW-1:0] second_idx;
  logic two, c_valid, c_rsp_valid;
  logic [OW+SW:0] c_id, c_rsp_id;
  logic [8*LINE_BYTES-1:0] c_rsp_data;
  assign two = 32'(f_off) + 32'(WORDS) > 32'(LW);
  assign first = f_valid && !second_q && c_ready;
  assign c_valid = second_q || f_valid;
  assign c_id = second_q ? {second_off, second_slot, 1'b1} : {f_off, f_slot, 1'b0};

  /* verilator lint_off PINCONNECTEMPTY */
  cache_dm #(.LINE_BYTES(LINE_BYTES), .SIZE_BYTES(SIZE_BYTES), .IDW(OW + SW + 1), .OUTSTANDING(OUTSTANDING)) u_cache (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .req_valid_i(c_valid), .req_ready_o(c_ready),
    .req_id_i(c_id), .req_line_i(second_q ? second_line : f_line), .req_idx_i(second_q ? second_idx : f_idx),
    .rsp_valid_o(c_rsp_valid), .rsp_ready_i(1'b1), .rsp_id_o(c_rsp_id), .rsp_hit_o(), .rsp_data_o(c_rsp_data),
    .mem_req_valid_o(mem_req_valid_o), .mem_req_ready_i(mem_req_ready_i), .mem_req_addr_o(mem_req_addr_o),
    .mem_rsp_valid_i(mem_rsp_valid_i), .mem_rsp_data_i(mem_rsp_data_i));
  /* verilator lint_on PINCONNECTEMPTY */

  assign rsp_valid_o = used != 0 && got[head] == need[head];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head <= '0;
      tail <= '0;
      used <= '0;
      second_q <= 1'b0;
    end else begin
      if (take) tail <= tail + 1'b1;
      if (first) second_q <= two;
      else if (second_q && c_ready) second_q <= 1'b0;
      if (rsp_valid_o) head <= head + 1'b1;
      used <= used + (SW + 1)'(take) - (SW + 1)'(rsp_valid_o);
    end
  end

  // a read's lookups are known when its first is made: until then it waits for both parts
  logic [OW-1:0] r_off;
  logic [SW-1:0] r_slot;
  logic r_part;
  assign {r_off, r_slot, r_part} = c_rsp_id;
  always_ff @(posedge clk_i) begin
    if (first) begin
      second_slot <= f_slot;
      second_off <= f_off;
      second_line <= f_line + 32'd1;
      second_idx <= f_idx == IXW'(LINES - 1) ? '0 : f_idx + 1'b1;
    end
    for (int s = 0; s < OUTSTANDING; s++) begin
      if (first && f_slot == SW'(s)) need[s] <= two ? 2'b11 : 2'b01;
      else if (take && tail == SW'(s)) need[s] <= 2'b11;
      if (take && tail == SW'(s)) got[s] <= 2'b00;
      else if (c_rsp_valid && r_slot == SW'(s)) got[s][r_part] <= 1'b1;
    end
  end

  // the response's line rotated by the read's offset (carried in the lookup's id): word j of the
  // read is the line's word off + j, in the second line from LW on; per word a table of the
  // offset gives the line's word, an LW-to-1 multiplexer takes it
  logic [31:0] line_word [LW];
  for (genvar w = 0; w < LW; w++) begin : g_line
    assign line_word[w] = c_rsp_data[32*w +: 32];
  end
  for (genvar j = 0; j < WORDS; j++) begin : g_word
    logic [OW-1:0] at [1 << OW];
    logic [(1 << OW)-1:0] second;
    for (genvar o = 0; o < (1 << OW); o++) begin : g_at
      assign at[o] = OW'((o + j) % LW);
      assign second[o] = o + j >= LW;
    end
    logic [31:0] column [OUTSTANDING];
    always_ff @(posedge clk_i)
      if (c_rsp_valid && second[r_off] == r_part) column[r_slot] <= line_word[at[r_off]];
    assign rsp_data_o[32*j +: 32] = column[head];
  end
endmodule
