// thread_sched: the DynRTP's thread scheduler (paper section 3: the threads of a pipeline share
// its units, so that one thread's unit latency and memory wait are hidden by the others). Per
// unit a ready set of one bit per thread and a round-robin pointer; the timing rules of the cycle
// model (docs/cycle-model.md, tb/cycle/cycle_sim.c pipe_cycle), which models this module:
//   * a thread whose next operation is decided (and whose memory blocks are in the caches) raises
//     its bit of unit u in set_i (u * THREADS + thread); any number of threads per cycle, as the
//     units' results and the caches' fills wake them. The bit is seen by the unit's issue logic
//     from the next cycle on;
//   * a unit whose issue slots are free issues the first ready thread at or after its pointer,
//     cyclically (issue_valid_o, issue_thread_o, one-hot in issue_grant_o; issue_slots_o is that thread's slots_i, the issue
//     slots of its operation: rays transformed, intersected or shaded); the pointer moves past it
//     and the unit is busy for `slots` cycles (the next issue comes that many cycles later);
//   * the issued thread's bit is cleared in the same cycle.
// Why a ready set and not a FIFO of thread ids: a cycle may wake many threads for one unit (a
// line fill wakes every thread parked on it); setting bits takes any number per cycle, a FIFO as
// many write ports. Round robin keeps it fair: no thread waits for more than THREADS issues.
// Latency: a thread set in cycle c can issue in c + 1. Throughput: one issue per unit and cycle
// (an operation of n slots blocks its unit n cycles).
// Resources (THREADS = 64, UNITS = 5): 5 x 64 ready flip-flops, 5 x 64 pointer flip-flops (the
// pointer as the mask of the threads after it, so that no comparator per thread is needed), 5
// SLOT_BITS busy counters; per unit an rr_pick (a lowest-set-bit isolation on a 64-bit carry chain, OR trees
// for the index) and an OR tree for the slots (docs/synth.md: LUT6 levels).
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
  output logic [UNITS*THREADS-1:0]       issue_grant_o,  // issue_thread_o one-hot (zero without an issue)
  output logic [UNITS*SLOT_BITS-1:0]     issue_slots_o
);
  // public_flat_rd: read by tb_dynrtp for render --mode rtl --vcd (queue_depth)
  logic [THREADS-1:0] ready_q [UNITS] /*verilator public_flat_rd*/;
  logic [THREADS-1:0] after_q [UNITS];   // the threads after the one issued last (the pointer as a mask)
  logic [SLOT_BITS-1:0] busy_q [UNITS];  // cycles the unit's issue slots stay taken after this one

  // The slots of the thread of a one-hot vector: an AND-OR multiplexer.
  function automatic logic [SLOT_BITS-1:0] slots_of(input logic [THREADS-1:0] onehot,
                                                    input logic [THREADS*SLOT_BITS-1:0] slots);
    slots_of = '0;
    for (int t = 0; t < THREADS; t++)
      if (onehot[t]) slots_of = slots_of | slots[t*SLOT_BITS +: SLOT_BITS];
  endfunction

  for (genvar u = 0; u < UNITS; u++) begin : g_unit
    logic [THREADS-1:0] grant, after_next;
    logic [SLOT_BITS-1:0] slots;
    logic               any, go;

    // Round robin: the first ready thread at or after the pointer, cyclically (rr_pick); the slots
    // follow from the one-hot grant by an OR tree.
    rr_pick #(.N(THREADS)) u_pick (
      .req_i(ready_q[u]), .after_i(after_q[u]), .any_o(any), .grant_o(grant),
      .index_o(issue_thread_o[u*TW +: TW]), .after_o(after_next)
    );
    assign slots = slots_of(grant, slots_i);
    assign go = any && busy_q[u] == '0;

    assign issue_valid_o[u] = go;
    // the pick's one-hot grant as it is (a requester implies any): the caller's grants to the
    // threads need no decoder after the index's OR trees
    assign issue_grant_o[u*THREADS +: THREADS] = busy_q[u] == '0 ? grant : '0;
    assign issue_slots_o[u*SLOT_BITS +: SLOT_BITS] = slots;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        ready_q[u] <= '0;
        after_q[u] <= '1;
        busy_q[u] <= '0;
      end else begin
        ready_q[u] <= (ready_q[u] & ~(go ? grant : '0)) | set_i[u*THREADS +: THREADS];
        if (go) begin
          after_q[u] <= after_next;
          busy_q[u] <= slots - SLOT_BITS'(1);
        end else if (busy_q[u] != '0) begin
          busy_q[u] <= busy_q[u] - SLOT_BITS'(1);
        end
      end
    end
  end
endmodule
