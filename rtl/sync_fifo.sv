// sync_fifo: a first-in first-out queue of DEPTH words of W bits, one clock (not a paper unit: the
// queues between the pipelined traversal unit's stages, rtl/trav_unit.sv, where an operation may
// wait: for its node's words, for the per-node datapath, at the output). No C function of its own:
// it only holds words in order. The words sit in a memory with an asynchronous read (LUT RAM):
// the head is read combinationally, so a word pushed in one cycle may leave in the next.
// Latency 1 cycle (push to valid_o), throughput one push and one pop per cycle (when full, a push
// waits for the cycle after a pop). Resources: DEPTH x W bits of LUT RAM, two pointers and a
// count. Handshake: valid/ready on both sides.
module sync_fifo #(
  parameter int W = 32,
  parameter int DEPTH = 16         // a power of 2
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         valid_i,
  output logic         ready_o,
  input  logic [W-1:0] data_i,
  output logic         valid_o,
  input  logic         ready_i,
  output logic [W-1:0] data_o
);
  localparam int PW = DEPTH > 1 ? $clog2(DEPTH) : 1;
  if (DEPTH < 2 || (DEPTH & (DEPTH - 1)) != 0) begin : g_depth_check
    $error("sync_fifo: DEPTH is a power of 2 (the pointers wrap)");
  end
  logic [W-1:0] mem [DEPTH];
  logic [PW-1:0] head, tail;
  logic [PW:0] count;
  logic push, pop;
  assign pop = valid_o && ready_i;
  // not ready when full even if a pop is under way: no path from ready_i to the memory's write
  // enable (a LUT RAM's read data feeding its own write enable through the consumer)
  assign ready_o = count != (PW + 1)'(DEPTH);
  assign push = valid_i && ready_o;
  assign valid_o = count != 0;
  assign data_o = mem[head];
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head <= '0;
      tail <= '0;
      count <= '0;
    end else begin
      if (push) tail <= tail + PW'(1);
      if (pop) head <= head + PW'(1);
      count <= count + (PW + 1)'(push) - (PW + 1)'(pop);
    end
  end
  always_ff @(posedge clk_i) if (push) mem[tail] <= data_i;
endmodule
