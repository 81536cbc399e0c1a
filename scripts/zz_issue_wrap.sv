// zz_issue_wrap: a measurement wrapper, not part of the design (kept out of rtl/, whose every module
// the DynRTP instantiates): trace_core's issue of the traversal (or list) unit at THREADS threads as
// rtl/trace_core.sv has it since its issue FIFOs: thread_sched's pick (one unit), the thread's grant
// (the pick's one-hot while the FIFO has room), a refused issue raised again, and the operands of
// the picked thread (K bits of each thread's, through the 64-to-1 multiplexer) into a two-entry
// sync_fifo. The threads' requests and slots are registered here; their operands (op_i: trace_thread's
// output ports, measured apart) and the unit's ready (unit_ready_i: the unit's ready_o) are not, so
// that `synth.py --ports` shows each input's levels into the registers apart. On a copy of the tree
// (synth.py reads rtl/*.sv):
//   cp -r rtl scripts /tmp/lvroot/ && cp scripts/zz_issue_wrap.sv /tmp/lvroot/rtl/ &&
//   python3 /tmp/lvroot/scripts/synth.py --levels zz_issue_wrap --hier
module zz_issue_wrap #(parameter int THREADS = 64, parameter int K = 4, localparam int TW = $clog2(THREADS)) (
  input  logic clk_i, input logic rst_ni,
  input  logic [THREADS-1:0] req_i,
  input  logic [THREADS*4-1:0] slots_i,
  input  logic [THREADS*K-1:0] op_i,
  input  logic unit_ready_i,
  output logic [THREADS-1:0] grant_o,
  output logic valid_o,
  output logic [TW+K-1:0] op_o);
  logic [THREADS-1:0] req, req_q, issue_grant, set;
  logic [THREADS*4-1:0] slots;
  logic issue_valid, issue_ready, accept;
  logic [TW-1:0] sel;
  always_ff @(posedge clk_i) begin
    req <= req_i;
    slots <= slots_i;
    req_q <= req;
  end
  assign accept = issue_valid && issue_ready;
  assign set = (req & ~req_q) | (issue_valid && !accept ? issue_grant : '0);
  assign grant_o = issue_ready ? issue_grant : '0;
  /* verilator lint_off PINCONNECTEMPTY */
  thread_sched #(.THREADS(THREADS), .UNITS(1), .SLOT_BITS(4)) u_sched (
    .clk_i(clk_i), .rst_ni(rst_ni), .set_i(set), .slots_i(slots), .issue_valid_o(issue_valid),
    .issue_thread_o(sel), .issue_grant_o(issue_grant), .issue_slots_o());
  /* verilator lint_on PINCONNECTEMPTY */
  sync_fifo #(.W(TW + K), .DEPTH(2)) u_issue (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(accept), .ready_o(issue_ready), .data_i({sel, op_i[sel*K +: K]}),
    .valid_o(valid_o), .ready_i(unit_ready_i), .data_o(op_o));
endmodule
