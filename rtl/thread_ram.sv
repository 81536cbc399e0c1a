// thread_ram: per-thread state of the ray tracing core in a memory (not a paper unit: the paper's
// DynRTP keeps its threads' state in block RAM, section 3). trace_core holds here, one word per
// thread (and ray), instead of in each trace_thread's flip-flops, the fields that its units take
// as operands: the rays' o and d (world and object space; trace_state's fields of
// hls/units/trace.c), the rebased origins p, te, t0, the hits' records, and the records' words
// (the instance's matrix, the triangle's record, the object's bounds): the unit's operand
// multiplexer over the threads becomes this read. rgs_ctrl keeps its ray-tree stack's rays here
// (32-bit words, a task written and read a word a cycle).
// No C function of its own: it only holds words.
// One write port (the unit whose results the words are), one read port with its output
// registered, so that Yosys infers block RAM or LUT RAM (synth_xilinx: RAMB18 or RAM64M/RAM32M by
// size; synth_ice40: SB_RAM40_4K); a field group read by several units takes one instance per
// reader, as a block RAM with one read port each would. Read-during-write of one address gives
// the old word in simulation; trace_core never reads a word in the cycle its thread's result
// writes it (a thread's batch on a unit starts after the batch that wrote its operands has ended,
// its hits are read after its last batch, its rays are written as it takes a packet, its
// records' words two cycles or more before it issues an operation that reads them; rgs_ctrl reads
// its stack only after the task written into it is whole; thread_count's sum, read as a thread's
// next event comes, is replaced by the sum being written), so the memory is marked no_rw_check: without it
// synth_ice40 adds a bypass per bit (a LUT4 and two flip-flops) to give the old word.
// Latency 1 cycle (address to data), one read and one write per cycle.
// Resources: DEPTH x W bits of RAM, W flip-flops (the read register, or the block RAM's own).
// Yosys 0.23: W = 144, DEPTH = 256 (p at 64 threads) 2 RAMB36E1 (synth_xilinx), 9 SB_RAM40_4K
// (synth_ice40); W = 136, DEPTH = 64 (a ray's hits at 64 threads) 46 RAM64M and 136 FDRE, 9
// SB_RAM40_4K; synth_ice40 -dsp -noflatten (python3 scripts/synth.py's per-module flow,
// 2026-11-29) W = 144 or 72, DEPTH = 64 (a ray's o and d, or one of them, at 64 threads) 9 or 5
// SB_RAM40_4K, W = 24, DEPTH = 256 2: an SB_RAM40_4K is 16 bits wide at 256 words or fewer, so at
// DEPTH = 64 three quarters of its bits are unused: a field read one ray at a time belongs in one
// memory of 4 THREADS words ({thread, ray}), written a ray a cycle (trace_core's world rays).
module thread_ram #(
  parameter int W = 32,
  parameter int DEPTH = 256,
  localparam int AW = $clog2(DEPTH)
) (
  input  logic          clk_i,
  input  logic          we_i,
  input  logic [AW-1:0] waddr_i,
  input  logic [W-1:0]  wdata_i,
  input  logic          re_i,            // the read register takes the word (else holds)
  input  logic [AW-1:0] raddr_i,
  output logic [W-1:0]  rdata_o
);
  (* no_rw_check *) logic [W-1:0] mem [DEPTH];
  always_ff @(posedge clk_i) begin
    if (we_i) mem[waddr_i] <= wdata_i;
    if (re_i) rdata_o <= mem[raddr_i];
  end
endmodule
