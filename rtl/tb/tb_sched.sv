// tb_sched: test wrapper (not synthesized) around the thread scheduler (rtl/thread_sched.sv) at
// the paper's 64 threads and the DynRTP's 5 units; the C++ bench (tb_sched.cpp) plays the threads
// and checks every issue against the cycle model's.
module tb_sched #(
  parameter int E = 7,  // unused: the Makefile passes the fp24 format to every bench
  parameter int M = 16,
  parameter int THREADS = 64,
  parameter int UNITS = 5,
  parameter int SLOT_BITS = 8
) (
  input  logic                                 clk_i,
  input  logic                                 rst_ni,
  input  logic [UNITS*THREADS-1:0]             set_i,
  input  logic [THREADS*SLOT_BITS-1:0]         slots_i,
  output logic [UNITS-1:0]                     issue_valid_o,
  output logic [UNITS*$clog2(THREADS)-1:0]     issue_thread_o,
  output logic [UNITS*THREADS-1:0]             issue_grant_o,
  output logic [UNITS*SLOT_BITS-1:0]           issue_slots_o
);
  if (E + M < 0) begin : g_unused
  end
  thread_sched #(.THREADS(THREADS), .UNITS(UNITS), .SLOT_BITS(SLOT_BITS)) u_sched (.*);
endmodule
