// trav_clip: the [n, f] chain of a clip (hls/units/trav_unit.c clip_box) over the distances of its
// 6 slab planes, which trav_node computes in 6 slots back to back (pass p: axis p / 2, its lo plane
// if p is even, else its hi plane). Per axis k, per ray: n = max(n, neg ? t_hi : t_lo),
// f = min(f, neg ? t_lo : t_hi) (neg: the sign bit of the ray's direction component, so that -0
// is negative), axis 0, 1, 2 in turn with the running value as the first operand, as clip_box's
// f24q_max / f24q_min do, so that the NaN and zero rules give its bits; then le = n <= f.
// Only this chain depends on the plane before: an axis's step starts when its hi plane's distances
// come (the lo plane's wait a cycle in a register) and its result is back CMP_STAGES = 2 cycles
// later (with 1 stage it waits a cycle in a register), just as the next axis's hi plane comes,
// so the 6 planes flow without a gap (the
// comparators run every cycle; only the cycles that line up with a step are read).
// Inputs: pass_i, neg_i, ts_i with valid_i as trav_node's distances come (its stage ADD_STAGES +
// DIV_STAGES); tn_i, tf_i: the interval before the box, read with pass 1. Outputs: 2 CMP_STAGES
// cycles after pass 5's distances (with trav_node's defaults: trav_node's LATENCY after pass 5's
// slot, beside its outputs), valid for that cycle only (no handshake: a fixed-latency chain).
// Latency 2 CMP_STAGES after pass 5 (4), one plane per cycle (a clip per 6 cycles); CMP_STAGES
// at most 2.
// Resources: 4 max, 4 min, 4 le comparators (f24_cmp), a plane's distances and the result's
// interval in registers.
module trav_clip #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int CMP_STAGES = 2
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic                    valid_i,  // a clip's plane distances
  input  logic [2:0]              pass_i,
  input  logic [3:0]              neg_i,    // per ray: the axis's direction component is negative
  input  logic [4*(E+M+1)-1:0]    ts_i,
  input  logic [4*(E+M+1)-1:0]    tn_i,
  input  logic [4*(E+M+1)-1:0]    tf_i,
  output logic [4*(E+M+1)-1:0]    tn_o,
  output logic [4*(E+M+1)-1:0]    tf_o,
  output logic [3:0]              le_o
);
  localparam int W = 1 + E + M;
  if (CMP_STAGES > 2) begin : g_stages_check
    $error("trav_clip: an axis's step must end within the 2 cycles between two axes' hi planes (CMP_STAGES <= 2)");
  end

  logic [4*W-1:0] ts_lo;            // the axis's lo plane, a cycle before its hi plane
  always_ff @(posedge clk_i) if (valid_i && !pass_i[0]) ts_lo <= ts_i;
  logic [4*W-1:0] n_run, f_run;     // the chain's results
  logic [4*W-1:0] n_fb, f_fb;       // the same when the next axis's step starts (2 cycles after)
  if (CMP_STAGES == 2) begin : g_fb
    assign {n_fb, f_fb} = {n_run, f_run};
  end else begin : g_fb_wait
    always_ff @(posedge clk_i) {n_fb, f_fb} <= {n_run, f_run};
  end
  /* verilator lint_off PINCONNECTEMPTY */
  for (genvar i = 0; i < 4; i++) begin : g_ray
    logic [W-1:0] lo, hi, n_in, f_in;
    /* verilator lint_off UNUSEDSIGNAL */
    logic [3:0] fl; // {unordered, eq, le, lt}: le is used
    /* verilator lint_on UNUSEDSIGNAL */
    assign lo = ts_lo[i*W +: W];
    assign hi = ts_i[i*W +: W];
    // axis 0 starts from the interval before the box, the others from the step before
    assign n_in = pass_i == 3'd1 ? tn_i[i*W +: W] : n_fb[i*W +: W];
    assign f_in = pass_i == 3'd1 ? tf_i[i*W +: W] : f_fb[i*W +: W];
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_max (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
      .valid_i(1'b0), .a_i(n_in), .b_i(neg_i[i] ? hi : lo), .valid_o(), .flags_o(), .min_o(),
      .max_o(n_run[i*W +: W]));
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_min (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
      .valid_i(1'b0), .a_i(f_in), .b_i(neg_i[i] ? lo : hi), .valid_o(), .flags_o(), .min_o(f_run[i*W +: W]),
      .max_o());
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_le (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1),
      .valid_i(1'b0), .a_i(n_run[i*W +: W]), .b_i(f_run[i*W +: W]), .valid_o(), .flags_o(fl), .min_o(),
      .max_o());
    assign le_o[i] = fl[1];
  end
  f24_pipe #(.W(8 * W), .STAGES(CMP_STAGES)) u_d_t (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(1'b0),
    .data_i({n_run, f_run}), .valid_o(), .data_o({tn_o, tf_o}));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
