// rr_pick: a round-robin pick among N requesters, in few LUT levels (no priority chain): the
// first requester at or after the pointer, cyclically. The pointer is kept by the owner as the
// mask of the requesters after the one picked last (after_i; all ones, or all zeros, before the
// first pick), so that no comparator per requester is needed; the next mask is after_o.
// The lowest requester after the pointer, else the lowest requester: both at once as the lowest set
// bit of the doubled vector {req, req & after} (c & -c on one 2N-bit carry chain, no N-input OR
// deciding between the halves), the grant the OR of its halves; the index follows from the one-hot
// grant by OR trees. The grant is 2 LUT6 levels from req_i and after_i (docs/synth.md).
// Used by the thread scheduler (one per unit), by the caches' response selection and, with no
// pointer (after_i = 0: the lowest requester), by trace_core's word port and packet output.
// Combinational. Resources: a 2N-bit carry chain (isolation) and an N-bit one (the next mask), an
// N-input OR, log2 N OR trees of N/2 inputs.
module rr_pick #(
  parameter int N = 16,
  localparam int NW = N > 1 ? $clog2(N) : 1
) (
  input  logic [N-1:0]  req_i,
  input  logic [N-1:0]  after_i,
  output logic          any_o,
  output logic [N-1:0]  grant_o,   // one-hot; zero if no request
  output logic [NW-1:0] index_o,   // of the grant
  output logic [N-1:0]  after_o    // the requesters above the granted one
);
  logic [2*N-1:0] cand, low;
  always_comb begin
    cand = {req_i, req_i & after_i};
    low = cand & (~cand + (2 * N)'(1));
    grant_o = low[N-1:0] | low[2*N-1:N];
    after_o = ~((grant_o << 1) - N'(1));
    index_o = '0;
    for (int i = 0; i < N; i++)
      if (grant_o[i]) index_o = index_o | NW'(i);
  end
  assign any_o = |req_i;
endmodule
