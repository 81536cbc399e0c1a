// cache_read: a read port of WORDS consecutive memory words through one direct-mapped cache
// (cache_dm), answered in request order (paper section 3, "Memory interface": how the DynRTP's
// units read through their caches; tb/cycle/mem_iface.c mem_iface_read, one lookup per line the
// read touches). The units' ports (trav_unit's kd-node port, the core's descriptor word port,
// list_unit's read port) take their answers in request order, while cache_dm answers as soon as a
// line is there (hits under misses): each read gets a slot of a ring of OUTSTANDING (read_ring),
// its lookups carry {off, slot, part} as their id, and the words are collected into the slot; the
// oldest slot leaves when all its lookups are back. A read that crosses a line boundary (a kd node
// at an odd word address) makes a second lookup of the next line in the following cycle, as
// mem_iface_read loops over the lines.
// The front: a read's line (word address / LW, LW = LINE_BYTES / 4 words), the line's index in
// the cache (line mod LINES) and the read's offset in the line (word address mod LW). With LW and
// LINES powers of two they are bit fields and the first lookup is made in the request cycle. Else
// (the matrix cache: lines of one 10-word triangle record, 153 of them, at e7m16) there is no
// divider, whose constant division of 32 bits is a 70-level LUT network: the address is a sum of
// CB-bit chunks c_k 2^(CB k), and per chunk three tables give floor(c_k 2^(CB k) / LW), that mod
// LINES, and c_k 2^(CB k) mod LW. Stage F (the request cycle) looks them up and adds each kind as
// a balanced tree; the next cycle adds the remainders' carry floor(sum r / LW) to the line, and
// finds the line's residue mod LINES among the candidates a_m + carry - k LINES by comparisons on
// carry chains (no adder before them), and makes the first lookup, its index read straight into
// the cache's arrays (cache_dm's S0). So the matrix cache keeps the latency it had when cache_dm
// took a cycle for the index. The second line's index is the first's + 1 (mod LINES), from a
// register in the second lookup's cycle.
// The words: read_ring registers a response and rotates its line by the read's offset, which the
// lookup's id carries, into the slot's words (LUT RAM), at no cycle (the registered response goes
// straight to the output when its read leaves then); its own module, so that its logic after the
// cache's late response stays short (docs/synth.md: LUT6 levels).
// Latency: the cache's (hit 2 cycles; a miss its fill + 1) + 1 for the ring, + 1 for stage F
// (the matrix cache: hit 4); throughput 1 read per cycle (a read of two lines: 1 per 2 cycles).
// LUT6 levels (synth_xilinx module by module as the DynRTP's, scripts/synth.py module_netlists and
// hier_lut_levels, 2026-11-30): 6 for the matrix cache (the request's way: cache_dm's ready, the
// front's first lookup, read_ring's flags; the response's: cache_dm's round-robin choice 3, its
// table's multiplexer 2, read_ring's flag enables 1), 7 for the kd-node, list and shading caches
// (in the DynRTP's elaboration the four 7, 6, 6, 7);
// 9 before (the DynRTP's run of 2026-11-30; 8 in this measure): read_ring rotated the response and
// compared its slot with each slot's number in the cycle of the cache's choice.
// Resources: cache_dm's (its ids log2 LW + log2 OUTSTANDING + 1 bits); read_ring's (WORDS x
// OUTSTANDING x 32 bits of LUT RAM, a line's register); stage F 3 x 7 tables of 32 entries, three adder trees and
// its registers; the next cycle up to 9 comparisons of MW + 1 bits.
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

  // ---- the ring of reads (read_ring) ----
  logic [SW-1:0] tail;
  logic room, take;

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
    // the next cycle: the remainders' carry into the line and its residue, the residue mod LINES.
    // t = a_m + carry <= TMAX; its index is t - k LINES for the k with k LINES <= t < (k + 1) LINES.
    // Each candidate a_m - (k LINES - carry) is one carry chain whose carry out says t >= k LINES,
    // and k LINES - carry is a table of a_r (as carry is): no adder before the comparisons. The
    // candidates (at most 9: 7 chunks of residues below LINES) are chosen by the comparisons in
    // two steps of 3 (each a LUT6 of 2 comparisons and 3 candidates), not by a priority chain.
    localparam int TMAX = CHUNKS * (LINES - 1) + (CHUNKS * (LW - 1)) / LW;
    localparam int KS = TMAX / LINES + 1;                   // candidates k = 0 .. KS - 1
    if (KS > 9) begin : g_ks
      $error("cache_read: the residue's choice is written for at most 9 candidates");
    end
    logic [OW-1:0] carry;
    logic [MW:0] minus [KS];       // k LINES - carry, per candidate
    logic [MW:0] diff [KS];        // a_m - (k LINES - carry); bit MW set: t < k LINES
    logic [IXW-1:0] cand [9];      // the candidates' indices (0 beyond KS)
    logic [8:0] ge;                // t >= k LINES (0 beyond KS)
    logic [IXW-1:0] grp [3];       // the candidate among 3 k .. 3 k + 2
    always_comb begin
      carry = '0;
      f_off = '0;
      for (int k = 0; k < KS; k++) minus[k] = '0;
      for (int v = 0; v < (1 << RW); v++)
        if (a_r == RW'(v)) begin
          carry = OW'(v / LW);
          f_off = OW'(v % LW);
          for (int k = 0; k < KS; k++) minus[k] = (MW + 1)'(k * LINES - v / LW);
        end
      ge = '0;
      for (int k = 0; k < 9; k++) cand[k] = '0;
      for (int k = 0; k < KS; k++) begin
        diff[k] = {1'b0, a_m} - minus[k];
        ge[k] = !diff[k][MW];
        cand[k] = IXW'(diff[k]);
      end
      for (int g = 0; g < 3; g++)
        grp[g] = ge[3 * g + 2] ? cand[3 * g + 2] : ge[3 * g + 1] ? cand[3 * g + 1] : cand[3 * g];
      f_idx = ge[6] ? grp[2] : ge[3] ? grp[1] : grp[0];
    end
    assign f_valid = a_valid;
    assign f_slot = a_slot;
    assign f_line = a_q + 32'(carry);
    assign req_ready_o = room && (!a_valid || first);
  end
  assign take = req_valid_i && req_ready_o;

  // ---- the lookups: a read's first line, or the second line of the read before ----
  logic [SW-1:0] second_slot;
  logic [OW-1:0] second_off;
  logic [31:0] second_line;
  logic [IXW-1:0] second_idx;  // the first line's (the second's is next_idx)
  logic two, c_valid, c_rsp_valid;
  logic [OW+SW:0] c_id, c_rsp_id;
  logic [8*LINE_BYTES-1:0] c_rsp_data;
  assign two = 32'(f_off) + 32'(WORDS) > 32'(LW);
  assign first = f_valid && !second_q && c_ready;
  assign c_valid = second_q || f_valid;
  assign c_id = second_q ? {second_off, second_slot, 1'b1} : {f_off, f_slot, 1'b0};
  // the second line's index, from the first's register (not before it: f_idx comes late)
  logic [IXW-1:0] next_idx;
  assign next_idx = second_idx == IXW'(LINES - 1) ? '0 : second_idx + 1'b1;

  /* verilator lint_off PINCONNECTEMPTY */
  cache_dm #(.LINE_BYTES(LINE_BYTES), .SIZE_BYTES(SIZE_BYTES), .IDW(OW + SW + 1), .OUTSTANDING(OUTSTANDING)) u_cache (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .req_valid_i(c_valid), .req_ready_o(c_ready),
    .req_id_i(c_id), .req_line_i(second_q ? second_line : f_line), .req_idx_i(second_q ? next_idx : f_idx),
    .rsp_valid_o(c_rsp_valid), .rsp_ready_i(1'b1), .rsp_id_o(c_rsp_id), .rsp_hit_o(), .rsp_data_o(c_rsp_data),
    .mem_req_valid_o(mem_req_valid_o), .mem_req_ready_i(mem_req_ready_i), .mem_req_addr_o(mem_req_addr_o),
    .mem_rsp_valid_i(mem_rsp_valid_i), .mem_rsp_data_i(mem_rsp_data_i));
  /* verilator lint_on PINCONNECTEMPTY */

  read_ring #(.LW(LW), .WORDS(WORDS), .OUTSTANDING(OUTSTANDING)) u_ring (
    .clk_i(clk_i), .rst_ni(rst_ni), .room_o(room), .tail_o(tail), .take_i(take), .look_i(first), .look_slot_i(f_slot),
    .two_i(two), .rsp_valid_i(c_rsp_valid), .rsp_off_i(c_rsp_id[OW+SW:SW+1]), .rsp_slot_i(c_rsp_id[SW:1]),
    .rsp_part_i(c_rsp_id[0]), .rsp_line_i(c_rsp_data), .out_valid_o(rsp_valid_o), .out_data_o(rsp_data_o));

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) second_q <= 1'b0;
    else if (first) second_q <= two;
    else if (second_q && c_ready) second_q <= 1'b0;
  end

  always_ff @(posedge clk_i)
    if (first) begin
      second_slot <= f_slot;
      second_off <= f_off;
      second_line <= f_line + 32'd1;
      second_idx <= f_idx;
    end
endmodule
