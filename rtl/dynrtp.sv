// dynrtp: one DynRTP (paper section 3, Figure 2) as far as it has RTL: the tile controller
// (tile_ctrl) deals the frame's 2x2 blocks, the ray tracing core (trace_core: THREADS threads,
// the traversal, list, rebase, transformation and intersection units, thread_sched) traces their
// packets, and its three memory ports read through the paper's direct-mapped caches (cache_read
// around cache_dm, the cycle model's default configuration tb/cycle/cycle_sim.c
// cycle_config_default: kd nodes NODE_KB KB in lines of one node (8 bytes), lists LIST_KB KB in
// lines of one entry (4 bytes), matrices MAT_KB KB in lines of one packed triangle record), all
// on one memory port (mem_port) to an external memory with valid/ready and in-order answers.
// What is RTL: the tile controller, the core, the caches and the memory port. What is not: the
// RGS (ray generation, shading, secondary rays, the per-block control of hls/units/rgs.c
// rgs_step; branch rgs builds rgs_ctrl): its seam is this module's ports, the blocks out
// (blk_*), the packets in (trace_core's packet input: thread, TRACE_* flags, rays) and their hits
// and trace_counters out, so the RGS drives the core as rgs_step would drive trace_step; the
// shading cache and the RGS's uncached reads (nothing of the RGS reads memory here).
// Where the memory interface differs from the cycle model (docs/cycle-model.md): the core's
// descriptor word port reads the header once per image (4 responses at e7m16; the cycle model:
// not at all) and a record in one or two responses of a matrix cache line's RW words each (a
// read across two lines takes two lookups; the cycle model looks the lines up at once); list_unit's entry waits in its pipeline for the list word (the cycle model parks the
// thread before the unit); every cache has OUTSTANDING reads in flight (the cycle model: no
// limit); the caches answer a hit after 2 cycles (3 with the matrix cache's index stage, the
// cycle model: at once).
// Counters (the usage counted inside the RTL): cycles_o counts the cycles from the frame taken at
// frame_valid_i until frame_end_i (the RGS's last block done); issues_o per unit of trace_core the
// operations issued in that time (thread_sched: trav, list, rebase, wide, xform, isect, add, sum,
// 64 bits each); packets_o the packets traced; reads_o per memory port of the core the reads its
// cache took (kd nodes, list entries, descriptor responses of RW words: the word port's usage).
// Latency and throughput: tile_ctrl 1 block per cycle; the core's (rtl/README.md); the memory port
// 1 transfer per cycle. Resources: trace_core's, 3 x cache_read (NODE_KB + LIST_KB + MAT_KB KB of
// data arrays and their tags), mem_port, tile_ctrl, 13 x 64-bit counters.
module dynrtp #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int THREADS = 32,
  parameter int CTX = 4,            // trav_unit's operation contexts (the bound at 32 threads: rtl/README.md)
  parameter int NODE_KB = 4,
  parameter int LIST_KB = 2,
  parameter int MAT_KB = 6,
  parameter int OUTSTANDING = 16,   // reads in flight per cache
  localparam int W = 1 + E + M,
  localparam int TW = $clog2(THREADS),
  localparam int RW = (12 * W + 27 + 3 + 31) / 32,         // F24_TRIANGLE_RECORD_WORDS
  localparam int MAT_LINE = 4 * RW,                         // bytes: one packed triangle record
  localparam int DW = 8 * MAT_LINE                          // the widest line
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  input  logic                   flush_i,     // a new memory image: the caches are emptied
  // the frame (tile_ctrl)
  input  logic                   frame_valid_i,
  output logic                   frame_ready_o,
  input  logic [31:0]            x0_i,
  input  logic [31:0]            y0_i,
  input  logic [31:0]            x1_i,
  input  logic [31:0]            y1_i,
  input  logic [12:0]            tile_i,
  input  logic                   frame_end_i, // the RGS has finished the frame's last block
  // the RGS's seam: blocks out
  output logic                   blk_valid_o,
  input  logic                   blk_ready_i,
  output logic [31:0]            blk_x_o,
  output logic [31:0]            blk_y_o,
  output logic                   blk_done_o,  // the frame's last block was taken
  // packets in (trace_begin) to thread thread_i
  input  logic                   valid_i,
  output logic                   ready_o,
  input  logic [TW-1:0]          thread_i,
  input  logic [2:0]             flags_i,
  input  logic [3:0]             active_i,
  input  logic [4*3*W-1:0]       o_i,
  input  logic [4*3*W-1:0]       d_i,
  input  logic [4*W-1:0]         tmin_i,
  input  logic [4*W-1:0]         tmax_i,
  // hits out (TP_DONE)
  output logic                   valid_o,
  input  logic                   ready_i,
  output logic [TW-1:0]          thread_o,
  output logic [4*32-1:0]        inst_o,
  output logic [4*32-1:0]        tri_o,
  output logic [4*W-1:0]         t_o,
  output logic [4*W-1:0]         u_o,
  output logic [4*W-1:0]         v_o,
  output logic [4*W-1:0]         cos_o,
  output logic [10*32-1:0]       count_o,
  // the external memory: byte address and byte count, answers in request order
  output logic                   mem_req_valid_o,
  input  logic                   mem_req_ready_i,
  output logic [31:0]            mem_req_addr_o,
  output logic [7:0]             mem_req_bytes_o,
  output logic [1:0]             mem_req_src_o,  // 0 kd nodes, 1 lists, 2 matrices
  input  logic                   mem_rsp_valid_i,
  input  logic [DW-1:0]          mem_rsp_data_i,
  // counters
  output logic [63:0]            cycles_o,
  output logic [8*64-1:0]        issues_o,
  output logic [63:0]            packets_o,
  output logic [3*64-1:0]        reads_o
);
  // ---- tile controller ----
  tile_ctrl u_tiles (
    .clk_i(clk_i), .rst_ni(rst_ni), .frame_valid_i(frame_valid_i), .frame_ready_o(frame_ready_o), .x0_i(x0_i),
    .y0_i(y0_i), .x1_i(x1_i), .y1_i(y1_i), .tile_i(tile_i), .blk_valid_o(blk_valid_o), .blk_ready_i(blk_ready_i),
    .blk_x_o(blk_x_o), .blk_y_o(blk_y_o), .done_o(blk_done_o));

  // ---- the core ----
  logic word_req, word_ready, word_rsp, node_req, node_ready, node_rsp, list_re, list_valid;
  logic [31:0] word_addr, node_addr, list_addr, list_data;
  logic [32*RW-1:0] word_data;
  logic [63:0] node_data;
  logic [7:0] issue;
  /* verilator lint_off PINCONNECTEMPTY */
  trace_core #(.E(E), .M(M), .THREADS(THREADS), .CTX(CTX)) u_core (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .valid_i(valid_i), .ready_o(ready_o), .thread_i(thread_i),
    .flags_i(flags_i),
    .active_i(active_i), .o_i(o_i), .d_i(d_i), .tmin_i(tmin_i), .tmax_i(tmax_i), .valid_o(valid_o),
    .ready_i(ready_i), .thread_o(thread_o), .inst_o(inst_o), .tri_o(tri_o), .t_o(t_o), .u_o(u_o), .v_o(v_o),
    .cos_o(cos_o), .count_o(count_o), .inflight_o(), .mem_req_valid_o(word_req), .mem_req_ready_i(word_ready),
    .mem_addr_o(word_addr), .mem_rsp_valid_i(word_rsp), .mem_rdata_i(word_data), .node_req_valid_o(node_req),
    .node_req_ready_i(node_ready), .node_addr_o(node_addr), .node_rsp_valid_i(node_rsp),
    .node_w0_i(node_data[31:0]), .node_w1_i(node_data[63:32]), .list_re_o(list_re), .list_addr_o(list_addr),
    .list_rdata_i(list_data), .list_rvalid_i(list_valid), .issue_o(issue));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- the caches ----
  logic [2:0] mreq_valid, mreq_ready, mrsp_valid;
  logic [3*32-1:0] mreq_addr;
  logic [DW-1:0] mrsp_data;
  cache_read #(.LINE_BYTES(8), .SIZE_BYTES(1024 * NODE_KB), .WORDS(2), .OUTSTANDING(OUTSTANDING)) u_nodes (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .req_valid_i(node_req), .req_ready_o(node_ready),
    .req_addr_i(node_addr), .rsp_valid_o(node_rsp), .rsp_data_o(node_data), .mem_req_valid_o(mreq_valid[0]),
    .mem_req_ready_i(mreq_ready[0]), .mem_req_addr_o(mreq_addr[0 +: 32]), .mem_rsp_valid_i(mrsp_valid[0]),
    .mem_rsp_data_i(mrsp_data[0 +: 64]));

  // list_unit's read is a pulse with its address: held until the cache takes it; its word is held
  // from the answer until the next read (list_unit waits for it with list_valid)
  logic lreq_q, lrsp;
  logic [31:0] laddr_q, lword;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lreq_q <= 1'b0;
      list_valid <= 1'b0;
    end else begin
      if (list_re) lreq_q <= 1'b1;
      else if (lreq_ready) lreq_q <= 1'b0;
      if (list_re) list_valid <= 1'b0;
      else if (lrsp) list_valid <= 1'b1;
    end
  end
  always_ff @(posedge clk_i) begin
    if (list_re) laddr_q <= list_addr;
    if (lrsp) list_data <= lword;
  end
  logic lreq_ready;
  cache_read #(.LINE_BYTES(4), .SIZE_BYTES(1024 * LIST_KB), .WORDS(1), .OUTSTANDING(OUTSTANDING)) u_lists (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .req_valid_i(lreq_q), .req_ready_o(lreq_ready),
    .req_addr_i(laddr_q), .rsp_valid_o(lrsp), .rsp_data_o(lword), .mem_req_valid_o(mreq_valid[1]),
    .mem_req_ready_i(mreq_ready[1]), .mem_req_addr_o(mreq_addr[32 +: 32]), .mem_rsp_valid_i(mrsp_valid[1]),
    .mem_rsp_data_i(mrsp_data[0 +: 32]));

  cache_read #(.LINE_BYTES(MAT_LINE), .SIZE_BYTES(1024 * MAT_KB), .WORDS(RW), .OUTSTANDING(OUTSTANDING)) u_matrices (
    .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i), .req_valid_i(word_req), .req_ready_o(word_ready),
    .req_addr_i(word_addr), .rsp_valid_o(word_rsp), .rsp_data_o(word_data), .mem_req_valid_o(mreq_valid[2]),
    .mem_req_ready_i(mreq_ready[2]), .mem_req_addr_o(mreq_addr[64 +: 32]), .mem_rsp_valid_i(mrsp_valid[2]),
    .mem_rsp_data_i(mrsp_data));

  // ---- the memory port ----
  mem_port #(.N(3), .DW(DW)) u_port (
    .clk_i(clk_i), .rst_ni(rst_ni), .req_valid_i(mreq_valid), .req_ready_o(mreq_ready), .req_addr_i(mreq_addr),
    .req_bytes_i({8'(MAT_LINE), 8'd4, 8'd8}), .rsp_valid_o(mrsp_valid), .rsp_data_o(mrsp_data),
    .mem_req_valid_o(mem_req_valid_o), .mem_req_ready_i(mem_req_ready_i), .mem_req_addr_o(mem_req_addr_o),
    .mem_req_bytes_o(mem_req_bytes_o), .mem_req_src_o(mem_req_src_o), .mem_rsp_valid_i(mem_rsp_valid_i),
    .mem_rsp_data_i(mem_rsp_data_i));

  // ---- counters: from the frame taken to the RGS's end of it ----
  logic running;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      running <= 1'b0;
      cycles_o <= '0;
      issues_o <= '0;
      packets_o <= '0;
      reads_o <= '0;
    end else begin
      if (frame_valid_i && frame_ready_o) begin
        running <= 1'b1;
        cycles_o <= '0;
        issues_o <= '0;
        packets_o <= '0;
        reads_o <= '0;
      end else if (running) begin
        running <= !frame_end_i;
        cycles_o <= cycles_o + 64'd1;
        for (int u = 0; u < 8; u++) issues_o[64*u +: 64] <= issues_o[64*u +: 64] + 64'(issue[u]);
        packets_o <= packets_o + 64'(valid_o && ready_i);
        reads_o[0 +: 64] <= reads_o[0 +: 64] + 64'(node_req && node_ready);
        reads_o[64 +: 64] <= reads_o[64 +: 64] + 64'(lreq_q && lreq_ready);
        reads_o[128 +: 64] <= reads_o[128 +: 64] + 64'(word_req && word_ready);
      end
    end
  end
endmodule
