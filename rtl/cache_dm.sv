// cache_dm: a direct-mapped read cache of one data type (paper section 3, "Memory interface": the
// kd-node, list and matrix caches of the DynRTC, 4/2/6 KB in the prototype; here also the shading
// cache) with the semantics of the cycle model's caches (tb/cycle/mem_iface.c), lookup for lookup:
//   * one request is one line lookup (req_line_i: the byte address / LINE_BYTES; a read across
//     lines is one request per line, as mem_iface_read loops over them) at the line's index
//     req_idx_i = req_line_i mod LINES (LINES = SIZE_BYTES / LINE_BYTES), which the requester
//     computes: a bit field when LINES is a power of two, else a constant modulo that cache_read
//     computes in a stage of its own with its division by the line's words (the matrix cache's
//     153 lines of 40 bytes at e7m16);
//   * hit: the tag of the index holds the line. A miss tags the index at once and requests the
//     line from memory (one transfer of LINE_BYTES at byte address line * LINE_BYTES); a second
//     lookup of a line whose fill is still under way is a hit that waits for that fill (no second
//     transfer), the youngest fill of the line;
//   * the response (rsp_id_o = req_id_i, rsp_hit_o, the line's data) leaves as soon as the data is
//     there: a hit on a filled line two cycles after the request, a
//     lookup that waits for a fill in the cycle after the fill arrived; responses leave in any
//     order (only the requests that wait for memory wait: hits under misses), round robin over the
//     table's entries.
// Outstanding requests: a table of OUTSTANDING requests (id, hit, the fill awaited, the line's
// data) and a FIFO of the fills requested from memory (line addresses; fills return in request
// order, so the oldest fill is the one that arrives, and its data goes to every request waiting on
// it and into the data array). A request is taken only if the table has room, so the lookup never
// stalls; with the table full req_ready_o is low. After reset and flush_i the tags are cleared, one
// index per cycle (LINES cycles, req_ready_o low), as mem_iface_flush empties the caches.
// Pipeline: S0 (the request cycle) reads the tag and data arrays at req_idx_i (synchronous block
// RAM, with forwarding of the tag written and of the fill written in the cycle before); S1 compares
// the tag, searches the fill FIFO (one line-address comparator per slot), writes the tag on a miss
// and the table; the table's ready entries are offered at rsp_valid_o. Latency: hit 2 cycles,
// miss 1 cycle after the fill arrives; throughput one lookup per cycle.
// Every choice among the table's entries and the fill FIFO's slots is a one-hot vector (the free
// entry and the response's round robin isolated on carry chains, rr_pick; the youngest fill of a
// line marked by a bit per slot, cleared when a younger fill of its line is requested), so no
// path between registers has a priority chain (docs/synth.md: LUT6 levels).
// Resources: tag array LINES x (AW + 1) and data array LINES x 8 LINE_BYTES bits (block RAM),
// request table OUTSTANDING x (IDW + 8 LINE_BYTES + log2 OUTSTANDING + 4) flip-flops, fill FIFO
// OUTSTANDING x (AW + 2) flip-flops and as many AW-bit equality comparators.
module cache_dm #(
  parameter int LINE_BYTES = 8,
  parameter int SIZE_BYTES = 4096,
  parameter int AW = 32,           // byte address width (line addresses use AW bits too)
  parameter int IDW = 8,           // request id width (the requester's thread or tag)
  parameter int OUTSTANDING = 16,  // requests in flight (table entries, fills)
  localparam int LINES = SIZE_BYTES / LINE_BYTES,
  localparam int IXW = LINES > 1 ? $clog2(LINES) : 1
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic                     flush_i,
  input  logic                     req_valid_i,
  output logic                     req_ready_o,
  input  logic [IDW-1:0]           req_id_i,
  input  logic [AW-1:0]            req_line_i,
  input  logic [IXW-1:0]           req_idx_i,     // req_line_i mod LINES
  output logic                     rsp_valid_o,
  input  logic                     rsp_ready_i,
  output logic [IDW-1:0]           rsp_id_o,
  output logic                     rsp_hit_o,
  output logic [8*LINE_BYTES-1:0]  rsp_data_o,
  output logic                     mem_req_valid_o,
  input  logic                     mem_req_ready_i,
  output logic [AW-1:0]            mem_req_addr_o,   // byte address of the line
  input  logic                     mem_rsp_valid_i,  // fills, in request order
  input  logic [8*LINE_BYTES-1:0]  mem_rsp_data_i
);
  localparam int DW = 8 * LINE_BYTES;
  localparam int OW = OUTSTANDING > 1 ? $clog2(OUTSTANDING) : 1;

  // ---- flush: clear the tags one index per cycle ----
  logic flushing;
  logic [IXW-1:0] flush_idx;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      flushing <= 1'b1;
      flush_idx <= '0;
    end else if (flush_i) begin
      flushing <= 1'b1;
      flush_idx <= '0;
    end else if (flushing) begin
      flush_idx <= flush_idx + 1'b1;
      if (flush_idx == IXW'(LINES - 1)) flushing <= 1'b0;
    end
  end

  // ---- request table ----
  // rt_ready: the entry is valid and its data is here (cleared when it is answered), so that the
  // response's pick reads registers only
  logic [OUTSTANDING-1:0] rt_valid, rt_ready, rt_hit;
  logic [IDW-1:0] rt_id [OUTSTANDING];
  logic [OW-1:0] rt_slot [OUTSTANDING];
  logic [DW-1:0] rt_data [OUTSTANDING];
  // all per-entry selections by one-hot vectors: free entries and grants isolated on carry chains
  logic [OUTSTANDING-1:0] rt_free, rt_alloc, rt_grant, rt_after, rt_after_next;
  logic [OW-1:0] rt_out;
  logic rt_out_any, rt_room1, rt_room2;
  logic [OW:0] rt_used, rt_used_next;  // valid entries, counted
  always_comb begin
    rt_free = ~rt_valid;
    rt_alloc = rt_free & (~rt_free + OUTSTANDING'(1));             // the lowest free entry
  end
  // round robin from the entry after the last one answered: no response waits for more than
  // OUTSTANDING others
  rr_pick #(.N(OUTSTANDING)) u_out (
    .req_i(rt_ready), .after_i(rt_after), .any_o(rt_out_any), .grant_o(rt_grant),
    .index_o(rt_out), .after_o(rt_after_next)
  );
  assign rsp_valid_o = rt_out_any;
  assign rsp_id_o = rt_id[rt_out];
  assign rsp_hit_o = rt_hit[rt_out];
  assign rsp_data_o = rt_data[rt_out];

  // ---- fill FIFO: head = oldest outstanding fill, send = next to request, tail = next free ----
  logic [AW-1:0] ff_line [OUTSTANDING];
  logic [IXW-1:0] ff_idx [OUTSTANDING]; // its index (no second modulo)
  logic [OUTSTANDING-1:0] ff_valid;  // the slot's fill is under way
  logic [OUTSTANDING-1:0] ff_young;  // no younger fill of the slot's line was requested since
  logic [OW-1:0] ff_head, ff_send, ff_tail;
  logic [OW:0] ff_count, ff_unsent;
  assign mem_req_valid_o = ff_unsent != 0;
  assign mem_req_addr_o = AW'(ff_line[ff_send] * AW'(LINE_BYTES));

  // ---- S0 ----
  logic take, s1_valid;
  logic [IDW-1:0] s1_id;
  logic [AW-1:0] s1_line;
  logic [IXW-1:0] s1_idx;
  // the request as it reads the arrays (S0)
  logic a_valid;
  logic [IDW-1:0] a_id;
  logic [AW-1:0] a_line;
  logic [IXW-1:0] a_idx;
  assign a_valid = take;
  assign a_id = req_id_i;
  assign a_line = req_line_i;
  assign a_idx = req_idx_i;
  // room in the table for the request in S1 and this one: they never stall
  // room for one (two) more: registers, from the count of valid entries (not an OR over the free
  // entries in the request's cycle: req_ready_o reaches the requester's logic)
  assign rt_used_next = rt_used + (OW + 1)'(s1_valid) - (OW + 1)'(rsp_valid_o && rsp_ready_i);
  assign req_ready_o = !flushing && !flush_i && (s1_valid ? rt_room2 : rt_room1);
  assign take = req_valid_i && req_ready_o;

  logic [AW:0] tag_mem [LINES];  // {valid, line}
  logic [DW-1:0] data_mem [LINES];
  logic [AW:0] tag_q;
  logic [DW-1:0] data_q;
  logic tag_we;
  logic [IXW-1:0] tag_widx;
  logic [AW:0] tag_wdata;
  always_ff @(posedge clk_i) begin
    tag_q <= tag_mem[a_idx];
    data_q <= data_mem[a_idx];
    if (tag_we) tag_mem[tag_widx] <= tag_wdata;
  end

  // ---- S1 ----
  logic miss, wait_fill, fill_now;
  logic [AW:0] tag_eff;
  logic [DW-1:0] data_eff;
  logic [OW-1:0] match_slot;
  logic match_any, match_head;
  logic [OUTSTANDING-1:0] match_vec, match_young;
  // forwarding registers: the tag written and the fill written in the cycle before
  logic p_tag_we, p_fill_we;
  logic [IXW-1:0] p_tag_idx, p_fill_idx;
  logic [AW:0] p_tag;
  logic [DW-1:0] p_fill_data;
  assign fill_now = mem_rsp_valid_i;
  always_comb begin
    tag_eff = (p_tag_we && p_tag_idx == s1_idx) ? p_tag : tag_q;
    data_eff = (p_fill_we && p_fill_idx == s1_idx) ? p_fill_data : data_q;
    miss = !(tag_eff[AW] && tag_eff[AW-1:0] == s1_line);
    // the fills under way of this line (one comparator per slot); the youngest wins, the one
    // match whose young bit is set (fills complete oldest first, so it is valid while any is)
    for (int s = 0; s < OUTSTANDING; s++) match_vec[s] = ff_valid[s] && ff_line[s] == s1_line;
    match_young = match_vec & ff_young;
    match_any = |match_vec;
    match_slot = '0;
    for (int s = 0; s < OUTSTANDING; s++)
      if (match_young[s]) match_slot = match_slot | OW'(s);
    match_head = match_young[ff_head];
    wait_fill = miss || match_any;
    tag_we = flushing || (s1_valid && miss);
    tag_widx = flushing ? flush_idx : s1_idx;
    tag_wdata = flushing ? '0 : {1'b1, s1_line};
  end

  logic [OW-1:0] s1_slot;
  assign s1_slot = miss ? ff_tail : match_slot;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_valid <= 1'b0;
      rt_valid <= '0;
      rt_ready <= '0;
      rt_used <= '0;
      rt_room1 <= 1'b1;
      rt_room2 <= OUTSTANDING > 1;
      rt_after <= '0;
      ff_head <= '0;
      ff_send <= '0;
      ff_tail <= '0;
      ff_count <= '0;
      ff_unsent <= '0;
      ff_valid <= '0;
      ff_young <= '0;
      p_tag_we <= 1'b0;
      p_fill_we <= 1'b0;
    end else begin
      s1_valid <= a_valid;
      p_tag_we <= tag_we;
      p_fill_we <= fill_now;
      // fill FIFO
      ff_count <= ff_count + (OW + 1)'(s1_valid && miss) - (OW + 1)'(fill_now);
      ff_unsent <= ff_unsent + (OW + 1)'(s1_valid && miss) - (OW + 1)'(mem_req_valid_o && mem_req_ready_i);
      if (s1_valid && miss) ff_tail <= ff_tail + 1'b1;
      if (mem_req_valid_o && mem_req_ready_i) ff_send <= ff_send + 1'b1;
      if (fill_now) begin
        ff_head <= ff_head + 1'b1;
        ff_valid[ff_head] <= 1'b0;
      end
      if (s1_valid && miss) begin
        ff_valid[ff_tail] <= 1'b1;
        ff_young <= (ff_young & ~match_vec) | (OUTSTANDING'(1) << ff_tail);
      end
      // request table: a fill completes the requests waiting on it; the response frees its entry
      for (int e = 0; e < OUTSTANDING; e++)
        if (fill_now && rt_valid[e] && !rt_ready[e] && rt_slot[e] == ff_head) rt_ready[e] <= 1'b1;
        else if (rsp_valid_o && rsp_ready_i && rt_grant[e]) rt_ready[e] <= 1'b0;
      if (rsp_valid_o && rsp_ready_i) rt_after <= rt_after_next;
      rt_used <= rt_used_next;
      rt_room1 <= rt_used_next < (OW + 1)'(OUTSTANDING);
      rt_room2 <= rt_used_next < (OW + 1)'(OUTSTANDING - 1);
      rt_valid <= (rt_valid & ~(rsp_valid_o && rsp_ready_i ? rt_grant : '0)) | (s1_valid ? rt_alloc : '0);
      for (int e = 0; e < OUTSTANDING; e++)
        if (s1_valid && rt_alloc[e]) rt_ready[e] <= !wait_fill || (fill_now && match_head && !miss);
    end
  end

  always_ff @(posedge clk_i) begin
    if (a_valid) begin
      s1_id <= a_id;
      s1_line <= a_line;
      s1_idx <= a_idx;
    end
    p_tag_idx <= tag_widx;
    p_tag <= tag_wdata;
    p_fill_idx <= ff_idx[ff_head];
    p_fill_data <= mem_rsp_data_i;
    if (fill_now) data_mem[ff_idx[ff_head]] <= mem_rsp_data_i;
    if (s1_valid && miss) begin
      ff_line[ff_tail] <= s1_line;
      ff_idx[ff_tail] <= s1_idx;
    end
    for (int e = 0; e < OUTSTANDING; e++)
      if (fill_now && rt_valid[e] && !rt_ready[e] && rt_slot[e] == ff_head) rt_data[e] <= mem_rsp_data_i;
    for (int e = 0; e < OUTSTANDING; e++)
      if (s1_valid && rt_alloc[e]) begin
        rt_id[e] <= s1_id;
        rt_hit[e] <= !miss;
        rt_slot[e] <= s1_slot;
        rt_data[e] <= (fill_now && match_head && !miss && wait_fill) ? mem_rsp_data_i : data_eff;
      end
  end
endmodule
