// rgs_normal: a hit's interpolated vertex normal and its zero test (paper section 3, Figure 2 path
// g; the part of hls/units/rgs_surface.c `rgs_surface_at` with vertex normals:
// `rgs_vertex_normals`' `shade_rec_normals`, `rgs_lerp_normal`, `f24_is_zero(rgs_dot3(vn, vn))`),
// bit for bit as the C, as a stream: the hits follow each other through the pipelined units, so
// that a `rgs_surface` can start the next hit's normal while the last one's is under way (its chain,
// about 88 cycles, is longer than a hit's reads). Since 2026-11-30 one serves the SURF_UNITS surface
// units of `rgs_units` (behind an `rgs_arb`, the unit's index as the thread id): a unit gives a hit
// every 40 to 80 cycles, the decoder takes one every 3.
//   decode  the record's 3 codes (42 bits each from bit 0 of its normal words) one a cycle, straight
//           from the input, which is held until the third (`shade_rec_decode`)
//   lerp    once a hit's 3 normals are out, its 3 components one a cycle (`rgs_lerp`: the
//           component c of the 3 normals, weights u, v; the thread id beside)
//   dot     once its 3 components are out, the squared length (`f24_dot3`): zero_o where its
//           exponent is zero (the caller then takes the geometric normal)
// Latency 2 + decode (44) + 3 + lerp (22) + dot (16) = 87 cycles from the first code's cycle (86 with
// CVT 2) at the default operator depths; throughput a hit every 3 cycles (its 3 codes; ready_o with
// the third); results in input order, with their thread id. No back pressure at the output: the
// units run without stalls and the caller has room for every result it asked for (`rgs_surface`
// asks only while its queue of NRM_SLOTS results has room for it); a hit starts only while fewer
// than DEPTH are inside, which bounds the internal queues.
// Resources: one each of `shade_rec_decode`, `rgs_lerp`, `f24_dot3`; the decoded normals of a hit
// twice (collected, interpolated: 18 W bits), the components (2 W), the barycentrics' queue
// (DEPTH x (2 W + TID_BITS)) and the normals waiting for their test (DEPTH x (3 W + TID_BITS)) in
// LUT RAM (flip-flops on the iCE40); the input (126 + 2 W bits) is the caller's register.
module rgs_normal #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int CVT_STAGES = 3,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int SQRT_STAGES = 9,
  parameter int DIV_STAGES = 11,
  parameter int TID_BITS = 2,
  parameter int DEPTH = 8          // hits inside (a power of 2)
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 valid_i,  // held until ready_o (the third code's cycle)
  output logic                 ready_o,
  input  logic [TID_BITS-1:0]  tid_i,
  input  logic [125:0]         codes_i,  // vertex k's code at bit 42 k (the record's normal words)
  input  logic [E+M:0]         u_i,
  input  logic [E+M:0]         v_i,
  output logic                 valid_o,
  output logic [TID_BITS-1:0]  tid_o,
  output logic [3*(E+M+1)-1:0] n_o,      // the interpolated normal, x, y, z from the low word up
  output logic                 zero_o    // its squared length has a zero exponent
);
  localparam int W = 1 + E + M;
  localparam int V = 3 * W;
  localparam int CW = $clog2(DEPTH + 1);

  // ---- input: a hit's 3 codes into the decoder, one a cycle, from the held input ----
  logic [1:0] k_q;
  logic [CW-1:0] inside_q;  // started and not yet given out
  logic start, dec_valid;
  // a hit starts while fewer than DEPTH are inside (its barycentrics' queue then has room too)
  assign start = valid_i && k_q == 2'd0 && inside_q != CW'(DEPTH);
  assign dec_valid = start || (valid_i && k_q != 2'd0);
  assign ready_o = k_q == 2'd2;

  logic dec_ovalid;
  logic [V-1:0] dec_n;
  /* verilator lint_off PINCONNECTEMPTY */
  shade_rec_decode #(.E(E), .M(M), .TID_BITS(1), .CVT_STAGES(CVT_STAGES), .MUL_STAGES(MUL_STAGES),
    .ADD_STAGES(ADD_STAGES), .SQRT_STAGES(SQRT_STAGES), .DIV_STAGES(DIV_STAGES)) u_dec (
    .clk_i, .rst_ni, .valid_i(dec_valid), .ready_o(), .tid_i(1'b0), .code_i(codes_i[42*k_q +: 42]),
    .valid_o(dec_ovalid), .ready_i(1'b1), .tid_o(), .n_o(dec_n));

  // the barycentrics and thread ids wait in order for their hit's interpolation
  logic [TID_BITS+2*W-1:0] uv_head;
  logic uv_pop;
  sync_fifo #(.W(TID_BITS + 2 * W), .DEPTH(DEPTH)) u_uv (
    .clk_i, .rst_ni, .valid_i(start), .ready_o(), .data_i({tid_i, v_i, u_i}),
    .valid_o(), .ready_i(uv_pop), .data_o(uv_head));

  // ---- a hit's 3 decoded normals collected, then its 3 components interpolated one a cycle (the
  // next hit's 3rd normal comes 3 cycles after this one's at the earliest: the copy is free then) ----
  logic [1:0] dn_q, lk_q;
  logic [V-1:0] nc_q [2], nl_q [3];
  logic lerp_on_q, dec_last;
  assign dec_last = dec_ovalid && dn_q == 2'd2;
  assign uv_pop = lerp_on_q && lk_q == 2'd2;
  logic lerp_ovalid;
  logic [W-1:0] lerp_r;
  logic [TID_BITS-1:0] lerp_tid;
  rgs_lerp #(.E(E), .M(M), .TID_BITS(TID_BITS), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_lerp (
    .clk_i, .rst_ni, .valid_i(lerp_on_q), .ready_o(), .tid_i(uv_head[2*W +: TID_BITS]), .a_i(nl_q[0][W*lk_q +: W]),
    .b_i(nl_q[1][W*lk_q +: W]), .c_i(nl_q[2][W*lk_q +: W]), .u_i(uv_head[0 +: W]), .v_i(uv_head[W +: W]),
    .valid_o(lerp_ovalid), .ready_i(1'b1), .tid_o(lerp_tid), .r_o(lerp_r));

  // ---- the components collected, the squared length; the normal and its thread id wait beside it
  // in order and leave with its test ----
  logic [1:0] cn_q;
  logic [W-1:0] comp_q [2];
  logic [V-1:0] n_full;
  logic dot_issue, dot_ovalid;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [W-1:0] dot_r;  // its exponent: the zero test
  /* verilator lint_on UNUSEDSIGNAL */
  assign n_full = {lerp_r, comp_q[1], comp_q[0]};
  assign dot_issue = lerp_ovalid && cn_q == 2'd2;
  f24_dot3 #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_dot (
    .clk_i, .rst_ni, .en_i(1'b1), .valid_i(dot_issue), .a_i(n_full), .b_i(n_full),
    .valid_o(dot_ovalid), .res_o(dot_r));
  sync_fifo #(.W(TID_BITS + V), .DEPTH(DEPTH)) u_wait (
    .clk_i, .rst_ni, .valid_i(dot_issue), .ready_o(), .data_i({lerp_tid, n_full}),
    .valid_o(), .ready_i(dot_ovalid), .data_o({tid_o, n_o}));
  /* verilator lint_on PINCONNECTEMPTY */
  assign valid_o = dot_ovalid;
  assign zero_o = dot_r[W-2:M] == '0;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      k_q <= '0;
      inside_q <= '0;
      dn_q <= '0;
      lk_q <= '0;
      lerp_on_q <= 1'b0;
      cn_q <= '0;
    end else begin
      inside_q <= inside_q + CW'(start) - CW'(valid_o);
      if (dec_valid) k_q <= k_q == 2'd2 ? 2'd0 : k_q + 2'd1;
      if (dec_ovalid) begin
        dn_q <= dec_last ? 2'd0 : dn_q + 2'd1;
        if (!dec_last) nc_q[dn_q[0]] <= dec_n;
      end
      if (dec_last) begin  // the hit's interpolation starts
        nl_q[0] <= nc_q[0];
        nl_q[1] <= nc_q[1];
        nl_q[2] <= dec_n;
        lerp_on_q <= 1'b1;
        lk_q <= '0;
      end else if (lerp_on_q) begin
        lk_q <= lk_q + 2'd1;
        if (lk_q == 2'd2) lerp_on_q <= 1'b0;
      end
      if (lerp_ovalid) begin
        cn_q <= cn_q == 2'd2 ? 2'd0 : cn_q + 2'd1;
        if (cn_q != 2'd2) comp_q[cn_q[0]] <= lerp_r;
      end
    end
  end
endmodule
