// cache_dm: a direct-mapped read cache of one data type (paper section 3, "Memory interface": the
// kd-node, list and matrix caches of the DynRTC, 4/2/6 KB in the prototype; here also the shading
// cache) with the semantics of the cycle model's caches (tb/cycle/mem_iface.c), lookup for lookup:
//   * one request is one line lookup (req_line_i: the byte address / LINE_BYTES; a read across
//     lines is one request per line, as mem_iface_read loops over them); the line's index is
//     req_line_i mod LINES (LINES = SIZE_BYTES / LINE_BYTES; a bit field when LINES is a power of
//     two, else a constant modulo: the matrix cache's 153 lines of 40 bytes at e7m16);
//   * hit: the tag of the index holds the line. A miss tags the index at once and requests the
//     line from memory (one transfer of LINE_BYTES at byte address line * LINE_BYTES); a second
//     lookup of a line whose fill is still under way is a hit that waits for that fill (no second
//     transfer), the youngest fill of the line;
//   * the response (rsp_id_o = req_id_i, rsp_hit_o, the line's data) leaves as soon as the data is
//     there: a hit on a filled line two cycles after the request, a lookup that waits for a fill
//     in the cycle after the fill arrived; responses leave in any order (only the requests that
//     wait for memory wait: hits under misses), round robin over the table's entries.
// Outstanding requests: a table of OUTSTANDING requests (id, hit, the fill awaited, the line's
// data) and a FIFO of the fills requested from memory (line addresses; fills return in request
// order, so the oldest fill is the one that arrives, and its data goes to every request waiting on
// it and into the data array). A request is taken only if the table has room, so the lookup never
// stalls; with the table full req_ready_o is low. After reset and flush_i the tags are cleared, one
// index per cycle (LINES cycles, req_ready_o low), as mem_iface_flush empties the caches.
// Pipeline: S0 (request cycle) reads the tag and data arrays (synchronous block RAM, with forwarding
// of the tag written and of the fill written in the cycle before); S1 compares the tag, searches the
// fill FIFO (one line-address comparator per slot), writes the tag on a miss and the table;
// the table's ready entries are offered at rsp_valid_o. Latency: hit 2 cycles, miss 1 cycle after
// the fill arrives; throughput one lookup per cycle.
// Resources: tag array LINES x (AW + 1) and data array LINES x 8 LINE_BYTES bits (block RAM),
// request table OUTSTANDING x (IDW + 8 LINE_BYTES + log2 OUTSTANDING + 3) flip-flops, fill FIFO
// OUTSTANDING x AW flip-flops and as many AW-bit equality comparators (docs/synth.md).
module cache_dm #(
  parameter int LINE_BYTES = 8,
  parameter int SIZE_BYTES = 4096,
  parameter int AW = 32,           // byte address width (line addresses use AW bits too)
  parameter int IDW = 8,           // request id width (the requester's thread or tag)
  parameter int OUTSTANDING = 16   // requests in flight (table entries, fills)
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic                     flush_i,
  input  logic                     req_valid_i,
  output logic                     req_ready_o,
  input  logic [IDW-1:0]           req_id_i,
  input  logic [AW-1:0]            req_line_i,
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
  localparam int LINES = SIZE_BYTES / LINE_BYTES;
  localparam int IXW = LINES > 1 ? $clog2(LINES) : 1;
  localparam int DW = 8 * LINE_BYTES;
  localparam int OW = OUTSTANDING > 1 ? $clog2(OUTSTANDING) : 1;
  localparam bit POW2 = (LINES & (LINES - 1)) == 0;

  function automatic logic [IXW-1:0] index_of(input logic [AW-1:0] line);
    /* verilator lint_off UNUSEDSIGNAL */
    logic [AW-1:0] r; // below LINES
    /* verilator lint_on UNUSEDSIGNAL */
    r = POW2 ? line & AW'(LINES - 1) : line % AW'(LINES);
    index_of = r[IXW-1:0];
  endfunction

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
  logic [OUTSTANDING-1:0] rt_valid, rt_ready, rt_hit;
  logic [IDW-1:0] rt_id [OUTSTANDING];
  logic [OW-1:0] rt_slot [OUTSTANDING];
  logic [DW-1:0] rt_data [OUTSTANDING];
  logic [OW:0] rt_free_n;
  logic [OW-1:0] rt_alloc, rt_out, rt_last;
  logic rt_out_any;
  always_comb begin
    rt_free_n = '0;
    rt_alloc = '0;
    for (int e = OUTSTANDING - 1; e >= 0; e--)
      if (!rt_valid[e]) rt_alloc = OW'(e);
    for (int e = 0; e < OUTSTANDING; e++) rt_free_n = rt_free_n + (OW + 1)'(!rt_valid[e]);
    // round robin from the entry after the last one answered: no response waits for more than
    // OUTSTANDING others
    rt_out = '0;
    rt_out_any = 1'b0;
    for (int k = OUTSTANDING; k >= 1; k--)
      if (rt_valid[OW'(32'(rt_last) + k)] && rt_ready[OW'(32'(rt_last) + k)]) begin
        rt_out = OW'(32'(rt_last) + k);
        rt_out_any = 1'b1;
      end
  end
  assign rsp_valid_o = rt_out_any;
  assign rsp_id_o = rt_id[rt_out];
  assign rsp_hit_o = rt_hit[rt_out];
  assign rsp_data_o = rt_data[rt_out];

  // ---- fill FIFO: head = oldest outstanding fill, send = next to request, tail = next free ----
  logic [AW-1:0] ff_line [OUTSTANDING];
  logic [IXW-1:0] ff_idx [OUTSTANDING]; // its index (no second modulo)
  logic [OUTSTANDING-1:0] ff_valid;  // the slot's fill is under way
  logic [OW-1:0] ff_head, ff_send, ff_tail;
  logic [OW:0] ff_count, ff_unsent;
  assign mem_req_valid_o = ff_unsent != 0;
  assign mem_req_addr_o = AW'(ff_line[ff_send] * AW'(LINE_BYTES));

  // ---- S0 ----
  logic take, s1_valid;
  logic [IDW-1:0] s1_id;
  logic [AW-1:0] s1_line;
  logic [IXW-1:0] idx0, s1_idx;
  assign idx0 = index_of(req_line_i);
  // room in the table for S1's request and this one: S1 never stalls
  assign req_ready_o = !flushing && !flush_i && rt_free_n > (OW + 1)'(s1_valid);
  assign take = req_valid_i && req_ready_o;

  logic [AW:0] tag_mem [LINES];  // {valid, line}
  logic [DW-1:0] data_mem [LINES];
  logic [AW:0] tag_q;
  logic [DW-1:0] data_q;
  logic tag_we;
  logic [IXW-1:0] tag_widx;
  logic [AW:0] tag_wdata;
  always_ff @(posedge clk_i) begin
    tag_q <= tag_mem[idx0];
    data_q <= data_mem[idx0];
    if (tag_we) tag_mem[tag_widx] <= tag_wdata;
  end

  // ---- S1 ----
  logic miss, wait_fill, fill_now;
  logic [AW:0] tag_eff;
  logic [DW-1:0] data_eff;
  logic [OW-1:0] match_slot;
  logic match_any;
  logic [OUTSTANDING-1:0] match_vec;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [2*OUTSTANDING-1:0] match_rot; // the low half is used
  /* verilator lint_on UNUSEDSIGNAL */
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
    // the fills under way of this line (one comparator per slot), rotated so that bit k is the
    // k-th oldest: the youngest match wins
    for (int s = 0; s < OUTSTANDING; s++) match_vec[s] = ff_valid[s] && ff_line[s] == s1_line;
    match_rot = {match_vec, match_vec} >> ff_head;
    match_any = 1'b0;
    match_slot = '0;
    for (int k = 0; k < OUTSTANDING; k++)
      if (match_rot[k]) begin
        match_any = 1'b1;
        match_slot = OW'(32'(ff_head) + k);
      end
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
      rt_last <= OW'(OUTSTANDING - 1);
      ff_head <= '0;
      ff_send <= '0;
      ff_tail <= '0;
      ff_count <= '0;
      ff_unsent <= '0;
      ff_valid <= '0;
      p_tag_we <= 1'b0;
      p_fill_we <= 1'b0;
    end else begin
      s1_valid <= take;
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
      if (s1_valid && miss) ff_valid[ff_tail] <= 1'b1;
      // request table: a fill completes the requests waiting on it; the response frees its entry
      for (int e = 0; e < OUTSTANDING; e++)
        if (fill_now && rt_valid[e] && !rt_ready[e] && rt_slot[e] == ff_head) rt_ready[e] <= 1'b1;
      if (rsp_valid_o && rsp_ready_i) begin
        rt_valid[rt_out] <= 1'b0;
        rt_last <= rt_out;
      end
      if (s1_valid) begin
        rt_valid[rt_alloc] <= 1'b1;
        rt_ready[rt_alloc] <= !wait_fill || (fill_now && s1_slot == ff_head && !miss);
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (take) begin
      s1_id <= req_id_i;
      s1_line <= req_line_i;
      s1_idx <= idx0;
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
    if (s1_valid) begin
      rt_id[rt_alloc] <= s1_id;
      rt_hit[rt_alloc] <= !miss;
      rt_slot[rt_alloc] <= s1_slot;
      rt_data[rt_alloc] <= (fill_now && s1_slot == ff_head && !miss && wait_fill) ? mem_rsp_data_i : data_eff;
    end
  end
endmodule
