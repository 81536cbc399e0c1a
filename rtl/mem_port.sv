// mem_port: the one memory port of a DynRTP (paper section 3, "Memory interface"; the cycle
// model's port in tb/cycle/mem_iface.c): N requesters (the kd-node, list and matrix caches and the
// shading reads, through the shading cache or uncached) share one request channel to memory,
// round robin, one transfer request per cycle. A transfer is a byte address and a byte count (a
// cache line, or the words of an uncached read); memory returns the transfers in request order
// (the bandwidth and latency are memory's: the testbench's model has the cycle model's
// --mem-mbps, --clock-mhz and --mem-latency arithmetic), and the port routes each response to its
// requester through a FIFO of the requesters of the transfers under way (DEPTH entries; with it
// full, no request is granted). Latency: a request 1 cycle (each requester's queue of 2, so its
// ready is a register: since 2026-11-30), a response 0 (combinational); one request and one
// response per cycle.
// Resources: per requester a `sync_fifo` of 2 x (AW + BW) bits (LUT RAM), the round-robin arbiter
// (`rr_pick`, the mask of the requesters after the last grant) over the queues' heads, an N-way mux
// of AW + BW bits, the source FIFO DEPTH x log2 N flip-flops with its pointers; the response data
// is one bus of DW bits to every requester (each takes its low bits).
module mem_port #(
  parameter int N = 4,        // requesters
  parameter int AW = 32,      // byte address width
  parameter int BW = 8,       // byte count width
  parameter int DW = 320,     // response data width: the widest line
  parameter int DEPTH = 64    // transfers under way
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic [N-1:0]         req_valid_i,
  output logic [N-1:0]         req_ready_o,
  input  logic [N*AW-1:0]      req_addr_i,
  input  logic [N*BW-1:0]      req_bytes_i,
  output logic [N-1:0]         rsp_valid_o,
  output logic [DW-1:0]        rsp_data_o,
  output logic                 mem_req_valid_o,
  input  logic                 mem_req_ready_i,
  output logic [AW-1:0]        mem_req_addr_o,
  output logic [BW-1:0]        mem_req_bytes_o,
  output logic [$clog2(N)-1:0] mem_req_src_o,   // for waveforms and the testbench
  input  logic                 mem_rsp_valid_i,
  input  logic [DW-1:0]        mem_rsp_data_i
);
  localparam int SW = N > 1 ? $clog2(N) : 1;
  localparam int PW = $clog2(DEPTH);

  logic [SW-1:0] src_fifo [DEPTH];
  logic [PW-1:0] head, tail;
  logic [PW:0] count;
  logic full, grant_any, fire;
  logic [SW-1:0] grant;
  logic [N-1:0] after, after_next, in_valid, in_take, grant_1h;
  logic [N*(AW+BW)-1:0] in_data;

  // each requester's requests through a queue of 2 (a register pair in LUT RAM): req_ready_o is a
  // register, so no path runs from a requester's valid through the arbiter into its ready (on the
  // RGS's reads: 17 LUT6 levels from a line reader's state through this port into the surface's
  // texture stage, 2026-11-30); the arbiter picks among the queues' heads, 1 cycle later
  for (genvar i = 0; i < N; i++) begin : g_in
    sync_fifo #(.W(AW + BW), .DEPTH(2)) u_in (
      .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(req_valid_i[i]), .ready_o(req_ready_o[i]),
      .data_i({req_bytes_i[i*BW +: BW], req_addr_i[i*AW +: AW]}), .valid_o(in_valid[i]), .ready_i(in_take[i]),
      .data_o(in_data[i*(AW+BW) +: AW+BW]));
  end

  assign full = count == (PW + 1)'(DEPTH);
  // round robin: the first requester after the last granted one (after: the requesters above it),
  // without an index modulo N, which Yosys maps to a divider per candidate unless N is a power of 2
  rr_pick #(.N(N)) u_pick (
    .req_i(in_valid), .after_i(after), .any_o(grant_any), .grant_o(grant_1h), .index_o(grant),
    .after_o(after_next));
  assign mem_req_valid_o = grant_any && !full;
  assign mem_req_src_o = grant;
  assign fire = mem_req_valid_o && mem_req_ready_i;
  // the request and the queue's pop by the one-hot grant (an AND-OR over the queues' heads), not
  // by its index: the index's encoding and a decoder or multiplexer on it are 2 LUT6 levels more
  assign in_take = grant_1h & {N{fire}};
  always_comb begin
    {mem_req_bytes_o, mem_req_addr_o} = '0;
    for (int i = 0; i < N; i++)
      {mem_req_bytes_o, mem_req_addr_o} |= in_data[i*(AW+BW) +: AW+BW] & {(AW+BW){grant_1h[i]}};
    rsp_valid_o = '0;
    if (mem_rsp_valid_i) rsp_valid_o[src_fifo[head]] = 1'b1;
  end
  assign rsp_data_o = mem_rsp_data_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head <= '0;
      tail <= '0;
      count <= '0;
      after <= '0;  // before the first grant: the lowest requester
    end else begin
      if (fire) begin
        tail <= tail + 1'b1;
        after <= after_next;
      end
      if (mem_rsp_valid_i) head <= head + 1'b1;
      count <= count + (PW + 1)'(fire) - (PW + 1)'(mem_rsp_valid_i);
    end
  end
  always_ff @(posedge clk_i) begin
    if (fire) src_fifo[tail] <= grant;
  end
endmodule
