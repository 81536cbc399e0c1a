// f24_cmp: pipelined fp24 comparator with minimumNumber/maximumNumber, docs/fp24.md
// (hls/fp24/f24_compare.c, f24_minmax.c). Each operand maps to a two's-complement order key (zero
// for exponent 0, so -0 == +0 and subnormal encodings equal zero); one key comparator gives
// lt/le/eq; NaN makes them false. min/max return the other operand for one NaN, the default NaN
// for two, -0 before +0, and canonical zeros. Two combinational segments with STAGES pipeline
// registers spread evenly over the cuts after them (PULP FPnew style; the last cut always gets
// one, so the outputs are registered):
//   1 NaN tests, order keys, canonical zeros
//   2 key comparator, min/max select
// Latency STAGES cycles (default 2, >= 60 MHz on iCE40 HX8K at e7m16, docs/synth.md), II = 1.
// Resources: two (W+1)-bit negators, one (W+1)-bit key comparator, two W-bit muxes.
module f24_cmp #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int STAGES = 2
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  output logic         valid_o,
  output logic [3:0]   flags_o,  // {unordered, eq, le, lt}
  output logic [E+M:0] min_o,
  output logic [E+M:0] max_o
);
  localparam int W = 1 + E + M;
  localparam int K = 2;          // segments
  localparam logic [E-1:0] EMAX = '1;
  localparam logic [W-1:0] DEFAULT_NAN = {1'b0, EMAX, 1'b1, {(M-1){1'b0}}};

  function automatic logic signed [W:0] key(input logic [W-1:0] x);
    logic [W:0] mag;
    mag = x[W-2:M] == 0 ? '0 : {2'b00, x[W-2:0]};
    key = x[W-1] ? -$signed(mag) : $signed(mag);
  endfunction

  function automatic logic [W-1:0] canonical(input logic [W-1:0] x);
    canonical = x[W-2:M] == 0 ? {x[W-1], {(W-1){1'b0}}} : x;
  endfunction

  // ---- segment 1: NaN tests, keys, canonical operands
  logic a_nan1, b_nan1;
  logic signed [W:0] ka1, kb1;
  logic [W-1:0] ca1, cb1;
  always_comb begin
    a_nan1 = a_i[W-2:M] == EMAX && a_i[M-1:0] != 0;
    b_nan1 = b_i[W-2:M] == EMAX && b_i[M-1:0] != 0;
    ka1 = key(a_i);
    kb1 = key(b_i);
    ca1 = canonical(a_i);
    cb1 = canonical(b_i);
  end

  localparam int B1 = 2 + 2 * (W + 1) + 2 * W;
  logic v1;
  logic [B1-1:0] d1;
  f24_pipe #(.W(B1), .STAGES(1 * STAGES / K)) u_c1 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i),
    .data_i({a_nan1, b_nan1, ka1, kb1, ca1, cb1}), .valid_o(v1), .data_o(d1)
  );

  // ---- segment 2: compare, select
  logic a_nan, b_nan, a_first, lt, le, eq, unordered;
  logic signed [W:0] ka, kb;
  logic [W-1:0] ca, cb, mn, mx;
  always_comb begin
    {a_nan, b_nan, ka, kb, ca, cb} = d1;
    unordered = a_nan || b_nan;
    lt = !unordered && ka < kb;
    le = !unordered && ka <= kb;
    eq = !unordered && ka == kb;
    a_first = lt || (eq && ca[W-1]);    // -0 before +0
    if (a_nan) begin
      mn = b_nan ? DEFAULT_NAN : cb;
      mx = mn;
    end else if (b_nan) begin
      mn = ca;
      mx = ca;
    end else begin
      mn = a_first ? ca : cb;
      mx = a_first ? cb : ca;
    end
  end

  f24_pipe #(.W(4 + 2 * W), .STAGES(STAGES - 1 * STAGES / K)) u_c2 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(v1), .data_i({unordered, eq, le, lt, mn, mx}),
    .valid_o(valid_o), .data_o({flags_o, min_o, max_o})
  );
endmodule
