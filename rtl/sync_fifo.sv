// sync_fifo: a first-in first-out queue of DEPTH words of W bits, one clock (not a paper unit: the
// queues between the pipelined traversal unit's stages, rtl/trav_unit.sv, where an operation may
// wait: for its node's words, for the per-node datapath, at the output; the list unit's, the
// RGS's and trace_core's issue queues). No C function of its own: it only holds words in order.
// Two storages, one behaviour (rtl/tb/tb_fifo.sv checks both against a deque every cycle):
//   * BLOCK_RAM = 0: a memory read asynchronously (LUT RAM on Xilinx), the head read
//     combinationally. For small queues: the iCE40 has no LUT RAM, so there it is DEPTH x W
//     flip-flops and a DEPTH-to-1 multiplexer per bit.
//   * BLOCK_RAM = 1: a memory with a synchronous, registered read (block RAM: RAMB18/36,
//     SB_RAM40_4K) that reads ahead: every cycle it reads the word that is the head in the next
//     cycle (the address head + pop, chosen combinationally from this cycle's pop), so the word
//     is in its output register when it becomes the head. The one word it cannot read is the one
//     written in the same cycle (a push that becomes the head at once: into an empty queue, or
//     with a pop of a one-word queue); that word is taken into a bypass register instead and
//     data_o chooses it in the next cycle. A word read in the cycle it is written is never used
//     (no_rw_check: no bypass logic per bit from Yosys); ram_style "block" because synth_xilinx
//     would take LUT RAM and an output register for 64 words. For deep, wide queues (trav_unit's).
// Both: data_o is the word at the head of the memory every cycle (even while empty, once written).
// Latency 1 cycle (push to valid_o and data_o), throughput one push and one pop per cycle (when
// full, a push waits for the cycle after a pop: ready_o does not look at ready_i).
// Resources: two pointers and a count; BLOCK_RAM = 0: DEPTH x W bits of LUT RAM; BLOCK_RAM = 1:
// DEPTH x W bits of block RAM, W flip-flops (the bypass register) and a 2-to-1 multiplexer per bit.
// Measured (Yosys 0.23, DEPTH = 64, sync_fifo alone, 2026-11-29; synth_ice40 -dsp, and synth_xilinx
// in scripts/synth.py's flow):
//   W = 2124 (trav_unit's operations): BLOCK_RAM = 1: iCE40 2166 SB_LUT4, 2144 flip-flops, 133
//     SB_RAM40_4K; 7-series 2140 LUT6, 2144 FF, 59 RAMB18. BLOCK_RAM = 0: 7-series 708 RAM64M
//     (2832 LUTs of LUT RAM); iCE40 about 106,000 SB_LUT4 and 135,955 flip-flops (from W = 64 and
//     413 below, 50 LUT4 per bit; its ABC run took over 10 minutes).
//   W = 413: BLOCK_RAM = 1: iCE40 455 SB_LUT4, 433 FF, 26 SB_RAM40_4K; BLOCK_RAM = 0: iCE40 20,729
//     SB_LUT4, 26,451 FF; 7-series 138 RAM64M.
//   W = 64: BLOCK_RAM = 1: iCE40 106 SB_LUT4, 84 FF, 4 SB_RAM40_4K; 7-series 1 RAMB36, 64 + 20 FF;
//     BLOCK_RAM = 0: iCE40 3267 SB_LUT4, 4115 FF; 7-series 22 RAM64M.
// Handshake: valid/ready on both sides.
module sync_fifo #(
  parameter int W = 32,
  parameter int DEPTH = 16,        // a power of 2
  parameter bit BLOCK_RAM = 1'b0   // the storage (above): the instantiating module chooses
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
  logic [PW-1:0] head, tail;
  logic [PW:0] count;
  logic push, pop;
  assign pop = valid_o && ready_i;
  // not ready when full even if a pop is under way: no path from ready_i to the memory's write
  // enable (a LUT RAM's read data feeding its own write enable through the consumer)
  assign ready_o = count != (PW + 1)'(DEPTH);
  assign push = valid_i && ready_o;
  assign valid_o = count != 0;
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
  if (BLOCK_RAM) begin : g_block_ram
    (* ram_style = "block", no_rw_check *) logic [W-1:0] mem [DEPTH];
    logic [W-1:0] rd, pushed;
    logic bypass;                  // the head was pushed in the last cycle: pushed, not rd
    always_ff @(posedge clk_i) begin
      if (push) mem[tail] <= data_i;
      rd <= mem[head + PW'(pop)];
      pushed <= data_i;
    end
    // the word pushed now is the next head when the queue keeps no other: count == pop
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) bypass <= 1'b0;
      else bypass <= push && count == (PW + 1)'(pop);
    end
    assign data_o = bypass ? pushed : rd;
  end else begin : g_lut_ram
    logic [W-1:0] mem [DEPTH];
    always_ff @(posedge clk_i) if (push) mem[tail] <= data_i;
    assign data_o = mem[head];
  end
endmodule
