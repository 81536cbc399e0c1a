// shade_rec_decode: one vertex normal of the compact shading record decoded to a unit fp24 vector
// (paper section 3, the RGS's shading; hls/units/shade_rec.c `shade_rec_normal`, the record's
// layout in hls/units/shade_rec.h and docs/memory-image.md), the first step of `surface_at`'s
// `rgs_vertex_normals` (hls/units/rgs_surface.c): a hit decodes the 3 normals of its triangle, one
// a cycle.
// The 42-bit octahedral code (x in bits 0..20, y in 21..41, signed) is unfolded in integers:
// |x|, |y|, z = 2^20 - 1 - |x| - |y| and, for z < 0 (the lower hemisphere), x and y folded over
// the diagonals (4 adders of 22 bits, 2 sign muxes; registered in front of the converters, so that
// the unfolding and a converter's first segment are not one path of 16 LUT6 levels);
// then 3 `f24_from_i32` (SCALE 0), 1 / sqrt((x x + y y) + z z) in the C's order (`f24_inv_length`:
// `f24_dot3`, `f24_sqrt`, `f24_div`) and the 3 products
// with the converted components (3 `f24_mul`; the components wait in an `f24_pipe`). The code
// x = -2^20 (SHADE_NO_NORMAL: the vertex has no normal) gives (+0, +0, +0) as the C does.
// The thread id (TID_BITS) travels beside the datapath with the valid bit.
// Latency LATENCY = 1 + CVT_STAGES + 2 MUL_STAGES + 2 ADD_STAGES + SQRT_STAGES + DIV_STAGES
// (default 1 + 3 + 8 + 12 + 9 + 11 = 44; 43 with CVT 2 until 2026-11-29, 42 before the unfolding's register) cycles, one normal per cycle (II = 1); handshake valid/ready,
// the pipeline advances when the output is free or taken. Resources (the operators'): 3 int-to-fp24
// converters, 6 multipliers, 2 adders, 1 square root, 1 divider, the integer unfolding, delay
// lines for the components (3 W bits x (MUL + 2 ADD + SQRT + DIV) stages), the missing flag and the thread id (LATENCY stages).
module shade_rec_decode #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TID_BITS = 6,
  parameter int CVT_STAGES = 3,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int SQRT_STAGES = 9,
  parameter int DIV_STAGES = 11
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 valid_i,
  output logic                 ready_o,
  input  logic [TID_BITS-1:0]  tid_i,
  input  logic [41:0]          code_i,  // x in bits 0..20, y in 21..41 (two's complement)
  output logic                 valid_o,
  input  logic                 ready_i,
  output logic [TID_BITS-1:0]  tid_o,
  output logic [3*(E+M+1)-1:0] n_o      // x, y, z from the low word up
);
  localparam int W = 1 + E + M;
  localparam int OCT = 21;                    // SHADE_OCT_BITS
  localparam int LEN_STAGES = MUL_STAGES + 2 * ADD_STAGES;
  localparam int LATENCY = 1 + CVT_STAGES + 2 * MUL_STAGES + 2 * ADD_STAGES + SQRT_STAGES + DIV_STAGES;
  localparam logic signed [31:0] OCT_ONE = (32'sd1 <<< (OCT - 1)) - 32'sd1;

  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;

  // ---- the octahedral unfolding (shade_rec_normal's integers)
  logic signed [31:0] x, y, ax, ay, z;
  /* verilator lint_off UNUSEDSIGNAL */
  logic signed [31:0] fx, fy;  // |fx|, |fy| <= 2^20: their low UW bits go on
  /* verilator lint_on UNUSEDSIGNAL */
  logic missing;
  always_comb begin
    x = 32'(signed'(code_i[OCT-1:0]));
    y = 32'(signed'(code_i[2*OCT-1:OCT]));
    missing = x < -OCT_ONE;
    ax = x < 0 ? -x : x;
    ay = y < 0 ? -y : y;
    z = OCT_ONE - ax - ay;
    fx = x;
    fy = y;
    if (z < 0) begin  // lower hemisphere: folded over the diagonals
      fx = x < 0 ? ay - OCT_ONE : OCT_ONE - ay;
      fy = y < 0 ? ax - OCT_ONE : OCT_ONE - ax;
    end
  end

  // the unfolded components registered: the unfolding (8 LUT6 levels from the code) and a
  // converter's first segment (8) are one path without it, 16 levels in the RGS (docs/synth.md)
  localparam int UW = OCT + 1;                // bits of an unfolded component (signed): |z| <= 2^20 + 1
  logic [3*UW-1:0] comp_q;
  /* verilator lint_off PINCONNECTEMPTY */
  f24_pipe #(.W(3 * UW), .STAGES(1)) u_unfold (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i({UW'(z), UW'(fy), UW'(fx)}), .valid_o(), .data_o(comp_q));

  logic missing_q;
  logic [3*W-1:0] n;
  logic [W-1:0] n_q [3];
  logic [W-1:0] prod [3];
  logic [W-1:0] inv;
  logic [31:0] comp [3];
  for (genvar k = 0; k < 3; k++) begin : g_sext
    assign comp[k] = 32'(signed'(comp_q[k*UW +: UW]));
  end
  for (genvar k = 0; k < 3; k++) begin : g_comp
    f24_from_i32 #(.E(E), .M(M), .SCALE(0), .STAGES(CVT_STAGES)) u_cvt (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .a_i(comp[k]), .valid_o(), .res_o(n[k*W +: W]));
    // the component waits for 1 / length
    f24_pipe #(.W(W), .STAGES(LEN_STAGES + SQRT_STAGES + DIV_STAGES)) u_d_n (.clk_i(clk_i), .rst_ni(rst_ni),
      .en_i(en), .valid_i(1'b0), .data_i(n[k*W +: W]), .valid_o(), .data_o(n_q[k]));
    f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_scale (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .a_i(n_q[k]), .b_i(inv), .valid_o(), .res_o(prod[k]));
    assign n_o[k*W +: W] = missing_q ? '0 : prod[k];
  end
  f24_inv_length #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES), .SQRT_STAGES(SQRT_STAGES),
    .DIV_STAGES(DIV_STAGES)) u_inv (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .v_i(n), .valid_o(),
    .len_o(), .inv_o(inv));

  // valid, the thread id and the missing flag beside the datapath; a missing normal is +0
  f24_pipe #(.W(TID_BITS + 1), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(valid_i), .data_i({tid_i, missing}), .valid_o(valid_o), .data_o({tid_o, missing_q}));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
