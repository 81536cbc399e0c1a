// f24_cmp_core: fp24 comparator and minimumNumber/maximumNumber, combinational (docs/fp24.md,
// hls/fp24/f24_compare.c, f24_minmax.c). Each operand maps to a two's-complement order key
// (zero for exponent 0, so -0 == +0 and subnormal encodings equal zero); one key comparator
// gives lt/le/eq; NaN makes them false. min/max return the other operand for one NaN, the
// default NaN for two, -0 before +0, and canonical zeros.
module f24_cmp_core #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  output logic         lt_o,
  output logic         le_o,
  output logic         eq_o,
  output logic         unordered_o,
  output logic [E+M:0] min_o,
  output logic [E+M:0] max_o
);
  localparam int W = 1 + E + M;
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

  logic a_nan, b_nan, a_first;
  logic signed [W:0] ka, kb;
  logic [W-1:0] ca, cb;

  always_comb begin
    a_nan = a_i[W-2:M] == EMAX && a_i[M-1:0] != 0;
    b_nan = b_i[W-2:M] == EMAX && b_i[M-1:0] != 0;
    ka = key(a_i);
    kb = key(b_i);
    unordered_o = a_nan || b_nan;
    lt_o = !unordered_o && ka < kb;
    le_o = !unordered_o && ka <= kb;
    eq_o = !unordered_o && ka == kb;
    ca = canonical(a_i);
    cb = canonical(b_i);
    a_first = lt_o || (eq_o && ca[W-1]);    // -0 before +0
    if (a_nan) begin
      min_o = b_nan ? DEFAULT_NAN : cb;
      max_o = min_o;
    end else if (b_nan) begin
      min_o = ca;
      max_o = ca;
    end else begin
      min_o = a_first ? ca : cb;
      max_o = a_first ? cb : ca;
    end
  end
endmodule
