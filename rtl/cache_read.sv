// cache_read: a read port of WORDS consecutive memory words through one direct-mapped cache
// (cache_dm), answered in request order (paper section 3, "Memory interface": how the DynRTP's
// units read through their caches; tb/cycle/mem_iface.c mem_iface_read, one lookup per line the
// read touches). The units' ports (trav_unit's kd-node port, the core's descriptor word port,
// list_unit's read port) take their answers in request order, while cache_dm answers as soon as a
// line is there (hits under misses): each read gets a slot of a ring of OUTSTANDING, its lookups
// carry {slot, part} as their id, and the words are collected into the slot; the oldest slot
// leaves when all its lookups are back. A read that crosses a line boundary (a kd node at an odd
// word address) makes a second lookup of the next line in the following cycle (req_ready_o low
// meanwhile), as mem_iface_read loops over the lines.
// Latency: the cache's (hit 2 cycles, 3 with its index stage; a miss its fill + 1) + 1 for the
// ring; throughput 1 read per cycle (a read of two lines: 1 per 2 cycles).
// Resources: cache_dm's, the ring OUTSTANDING x (32 WORDS + 4 + log2 LW) flip-flops, the line
// address a / LW (a shift, or a constant divider for the matrix cache's 10-word lines at e7m16).
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
  localparam int SW = $clog2(OUTSTANDING);
  localparam int OW = LW > 1 ? $clog2(LW) : 1;
  if (WORDS < 1 || WORDS > LW || (1 << SW) != OUTSTANDING) begin : g_check
    $error("cache_read: WORDS 1 .. LINE_BYTES / 4 (a read touches at most two lines), OUTSTANDING a power of two");
  end

  // ---- the ring of reads ----
  logic [SW-1:0] head, tail;
  logic [SW:0] used;
  logic [1:0] need [OUTSTANDING], got [OUTSTANDING];
  logic [OW-1:0] off [OUTSTANDING];
  logic [31:0] word [OUTSTANDING][WORDS];

  // ---- the lookups: a read's first line, or the second line of the read before ----
  logic second_q;
  logic [SW-1:0] second_slot;
  logic [31:0] second_line, line0;
  logic [OW-1:0] off0;
  logic two, c_valid, c_ready, c_rsp_valid, take;
  logic [SW:0] c_id, c_rsp_id;
  logic [8*LINE_BYTES-1:0] c_rsp_data;
  assign line0 = req_addr_i / 32'(LW);
  assign off0 = OW'(req_addr_i % 32'(LW));
  assign two = 32'(off0) + 32'(WORDS) > 32'(LW);
  assign req_ready_o = !second_q && used != (SW + 1)'(OUTSTANDING) && c_ready;
  assign take = req_valid_i && req_ready_o;
  assign c_valid = second_q || (req_valid_i && used != (SW + 1)'(OUTSTANDING));
  assign c_id = second_q ? {second_slot, 1'b1} : {tail, 1'b0};

  /* verilator lint_off PINCONNECTEMPTY */
  cache_dm #(.LINE_BYTES(LINE_BYTES), .SIZE_BYTES(SIZE_BYTES), .IDW(SW + 1), .OUTSTANDING(OUTSTANDING)) u_cache (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .req_valid_i(c_valid), .req_ready_o(c_ready),
    .req_id_i(c_id), .req_line_i(second_q ? second_line : line0), .rsp_valid_o(c_rsp_valid), .rsp_ready_i(1'b1),
    .rsp_id_o(c_rsp_id), .rsp_hit_o(), .rsp_data_o(c_rsp_data), .mem_req_valid_o(mem_req_valid_o),
    .mem_req_ready_i(mem_req_ready_i), .mem_req_addr_o(mem_req_addr_o), .mem_rsp_valid_i(mem_rsp_valid_i),
    .mem_rsp_data_i(mem_rsp_data_i));
  /* verilator lint_on PINCONNECTEMPTY */

  assign rsp_valid_o = used != 0 && got[head] == need[head];
  for (genvar j = 0; j < WORDS; j++) begin : g_out
    assign rsp_data_o[32*j +: 32] = word[head][j];
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head <= '0;
      tail <= '0;
      used <= '0;
      second_q <= 1'b0;
    end else begin
      if (take) begin
        tail <= tail + 1'b1;
        second_q <= two;
      end else if (second_q && c_ready) begin
        second_q <= 1'b0;
      end
      if (rsp_valid_o) head <= head + 1'b1;
      used <= used + (SW + 1)'(take) - (SW + 1)'(rsp_valid_o);
    end
  end

  // a line's words go to the read's words that lie in it: word j of the read is at off + j, in the
  // second line from LW on
  logic [SW-1:0] r_slot;
  logic r_part;
  assign {r_slot, r_part} = c_rsp_id;
  always_ff @(posedge clk_i) begin
    if (take) begin
      second_slot <= tail;
      second_line <= line0 + 32'd1;
      off[tail] <= off0;
      need[tail] <= two ? 2'b11 : 2'b01;
    end
    for (int s = 0; s < OUTSTANDING; s++) begin
      if (take && tail == SW'(s)) got[s] <= 2'b00;
      else if (c_rsp_valid && r_slot == SW'(s)) got[s][r_part] <= 1'b1;
    end
    if (c_rsp_valid)
      for (int j = 0; j < WORDS; j++)
        if ((32'(off[r_slot]) + 32'(j) >= 32'(LW)) == r_part)
          word[r_slot][j] <= c_rsp_data[32 * (32'(off[r_slot]) + 32'(j) - (r_part ? 32'(LW) : 32'd0)) +: 32];
  end
endmodule
