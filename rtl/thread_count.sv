// thread_count: per-thread event counters of the ray tracing core in a memory (not a paper unit:
// trace_core's count of a packet's trace_counters, hls/units/trace.c, which each trace_thread
// kept in 10 registers of 32 bits with their adders). F fields of 32 bits per thread: an event of
// thread thread_i adds inc_i's fields to that thread's (modulo 2^32, as the C's counters are read
// by the RTL's 32-bit ports); clear_i starts thread clear_thread_i's count at zero (a packet
// enters it); re_i reads thread rthread_i's count into count_o (registered, as thread_ram reads).
// The sum is a read-modify-write of one memory word (read as the event comes, written a cycle
// later): an event of the thread written in the cycle before takes that sum instead of the word
// read (the memory gives the old word then), and a thread cleared since its last write (fresh,
// a flip-flop per thread) counts from zero, so the memory is never written for a clear. count_o
// comes from a second copy of the words (the same writes, its own read port); a count read in
// the cycle its thread's sum is written would be the old one: trace_core reads a packet's
// counts as it leaves, two cycles or more after its thread's last event.
// No C function of its own: it adds what trace_core's units report for the thread (trace_core).
// Latency 1 cycle (event to written sum; read address to count_o). Throughput one event and one
// read per cycle.
// Resources: 2 thread_ram of THREADS x 32 F bits, THREADS flip-flops (fresh) and their set and
// clear decoders, 32 F adder bits, the event's registers (32 F + $clog2(THREADS) + 1 bits) and
// the last sum's (32 F + $clog2(THREADS) + 1).
module thread_count #(
  parameter int THREADS = 64,
  parameter int F = 1,
  localparam int TW = $clog2(THREADS),
  localparam int CW = 32 * F
) (
  input  logic          clk_i,
  input  logic          rst_ni,
  input  logic          clear_i,         // a packet enters thread clear_thread_i: its count is zero
  input  logic [TW-1:0] clear_thread_i,
  input  logic          add_i,           // an event of thread thread_i adds inc_i (field f: bits 32f ..)
  input  logic [TW-1:0] thread_i,
  input  logic [CW-1:0] inc_i,
  input  logic          re_i,            // the read register takes thread rthread_i's count (else holds)
  input  logic [TW-1:0] rthread_i,
  output logic [CW-1:0] count_o
);
  logic [THREADS-1:0] fresh;
  logic add_q, last_v, out_fresh;
  logic [TW-1:0] thread_q, last_thread;
  logic [CW-1:0] inc_q, rd, old, sum, last, out_rd;
  thread_ram #(.W(CW), .DEPTH(THREADS)) u_acc (
    .clk_i(clk_i), .we_i(add_q), .waddr_i(thread_q), .wdata_i(sum), .re_i(1'b1), .raddr_i(thread_i), .rdata_o(rd));
  thread_ram #(.W(CW), .DEPTH(THREADS)) u_out (
    .clk_i(clk_i), .we_i(add_q), .waddr_i(thread_q), .wdata_i(sum), .re_i(re_i), .raddr_i(rthread_i),
    .rdata_o(out_rd));
  assign old = last_v && last_thread == thread_q ? last : fresh[thread_q] ? '0 : rd;
  always_comb
    for (int f = 0; f < F; f++) sum[32*f +: 32] = old[32*f +: 32] + inc_q[32*f +: 32];
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      fresh <= '1;
      add_q <= 1'b0;
      last_v <= 1'b0;
    end else begin
      add_q <= add_i;
      last_v <= add_q;
      if (add_q) fresh[thread_q] <= 1'b0;
      if (clear_i) fresh[clear_thread_i] <= 1'b1;
    end
  always_ff @(posedge clk_i) begin
    thread_q <= thread_i;
    inc_q <= inc_i;
    last_thread <= thread_q;
    last <= sum;
    if (re_i) out_fresh <= fresh[rthread_i];
  end
  assign count_o = out_fresh ? '0 : out_rd;
endmodule
