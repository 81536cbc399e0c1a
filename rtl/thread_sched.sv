// thread_sched: the DynRTP's thread scheduler (paper section 3: the threads of a pipeline share
// its units, so that one thread's unit latency and memory wait are hidden by the others). Per
// unit a ready set of one bit per thread and a round-robin pointer; the timing rules of the cycle
// model (docs/cycle-model.md, tb/cycle/cycle_sim.c pipe_cycle), which models this module:
//   * a thread whose next operation is decided (and whose memory blocks are in the caches) raises
//     its bit of unit u in set_i (u * THREADS + thread); any number of threads per cycle, as the
//     units' results and the caches' fills wake them. The bit is seen by the unit's issue logic
//     from the next cycle on;
//   * a unit whose issue slots are free issues the first ready thread at or after its pointer,
//     cyclically (issue_valid_o, issue_thread_o; issue_slots_o is that thread's slots_i, the issue
//     slots of its operation: rays transformed, intersected or shaded); the pointer moves past it
//     and the unit is busy for `slots` cycles (the next issue comes that many cycles later);
//   * the issued thread's bit is cleared in the same cycle.
// Why a ready set and not a FIFO of thread ids: a cycle may wake many threads for one unit (a
// line fill wakes every thread parked on it); setting bits takes any number per cycle, a FIFO as
// many write ports. Round robin keeps it fair: no thread waits for more than THREADS issues.
// Latency: a thread set in cycle c can issue in c + 1. Throughput: one issue per unit and cycle
// (an operation of n slots blocks its unit n cycles).
// Resources (THREADS = 64, UNITS = 5): 5 x 64 ready flip-flops, 5 x 6-bit pointers, 5 SLOT_BITS
// busy counters; per unit two 64-bit priority encoders (at or after the pointer, and from 0) and
// a 64:1 SLOT_BITS-bit multiplexer of the slots.
module thread_sched #(
  parameter int THREADS = 64,
  parameter int UNITS = 5,       // RGS, transformation, traversal, list, intersection (trace.h)
  parameter int SLOT_BITS = 8,   // issue slots of one operation, 1 .. 2^SLOT_BITS - 1
  localparam int TW = $clog2(THREADS)
) (
  input  logic                           clk_i,
  input  logic                           rst_ni,
  input  logic [UNITS*THREADS-1:0]       set_i,        // bit u * THREADS + t: thread t ready for unit u
  input  logic [THREADS*SLOT_BITS-1:0]   slots_i,      // per thread: slots of its decided operation
  output logic [UNITS-1:0]               issue_valid_o,
  output logic [UNITS*TW-1:0]            issue_thread_o,
  output logic [UNITS*SLOT_BITS-1:0]     issue_slots_o
);
  logic [THREADS-1:0] ready_q [UNITS];
  logic [TW-1:0]      ptr_q [UNITS];
  logic [SLOT_BITS-1:0] busy_q [UNITS];  // cycles the unit's issue slots stay taken after this one

  // Lowest set bit of v (v != 0), as a priority encoder from the top down.
  function automatic logic [TW-1:0] lowest(input logic [THREADS-1:0] v);
    lowest = '0;
    for (int i = THREADS - 1; i >= 0; i--)
      if (v[i]) lowest = TW'(i);
  endfunction

  for (genvar u = 0; u < UNITS; u++) begin : g_unit
    logic [THREADS-1:0] at_or_after;
    logic [TW-1:0]      pick;
    logic               go;

    always_comb begin
      for (int t = 0; t < THREADS; t++) at_or_after[t] = ready_q[u][t] && TW'(t) >= ptr_q[u];
      pick = |at_or_after ? lowest(at_or_after) : lowest(ready_q[u]);
      go = |ready_q[u] && busy_q[u] == '0;
    end

    assign issue_valid_o[u] = go;
    assign issue_thread_o[u*TW +: TW] = pick;
    assign issue_slots_o[u*SLOT_BITS +: SLOT_BITS] = slots_i[pick*SLOT_BITS +: SLOT_BITS];

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        ready_q[u] <= '0;
        ptr_q[u] <= '0;
        busy_q[u] <= '0;
      end else begin
        ready_q[u] <= (ready_q[u] & ~(go ? THREADS'(1) << pick : '0)) | set_i[u*THREADS +: THREADS];
        if (go) begin
          ptr_q[u] <= TW'((32'(pick) + 1) % THREADS);
          busy_q[u] <= slots_i[pick*SLOT_BITS +: SLOT_BITS] - SLOT_BITS'(1);
        end else if (busy_q[u] != '0) begin
          busy_q[u] <= busy_q[u] - SLOT_BITS'(1);
        end
      end
    end
  end
endmodule
