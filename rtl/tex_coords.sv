// tex_coords: the texel coordinates of the RGS's bilinear texture sample (paper section 3: bilinear
// filtering of 8-bit textures in the shading unit; hls/units/rgs_tex.c `rgs_sample_bilinear` up to
// its reads, docs/shading.md): texture coordinates (s, t) and the texture entry (width, height,
// texel address) in, the two texel rows' word addresses, the two columns and the fractions out, bit
// for bit as the C. The first half of the sample (`tex_bilinear` until 2026-11-30); `tex_fetch` reads the 4
// texels and blends them.
// rgs_units has one for its SURF_UNITS surface units (behind an rgs_arb, the unit's index as the
// thread id): a unit asks for a sample every few hundred cycles, this takes one a cycle.
//   axes     two `tex_axis` side by side (s over the width, t over the height): x0, x1, fx and
//            y0, y1, fy; the thread id, the address and the width travel beside the s axis
//   rows     address + y0 w and address + y1 w: two 32-bit products and sums, truncated to 32 bits
//            as the C's uint32 arithmetic, into the output register with x0, x1, fx, fy
// Handshake: valid/ready at the input and the output; the axes advance while their result can go
// into the output register (ready_i = 1: they never stall).
// Latency: the axes' (41 at the default operator depths) + 1 (the rows' register). Throughput: one
// sample per cycle (II = 1).
// Resources: 2 `tex_axis`, 2 32 x 32-bit multipliers (the low 32 bits) and 2 32-bit adders, the
// output register (4 x 32 + 18 + TID_BITS bits).
module tex_coords #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TID_BITS = 6,
  parameter int CVT_STAGES = 3,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int CMP_STAGES = 2,
  parameter int TOI_STAGES = 2,
  parameter int MOD_STAGES = 16
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  output logic                ready_o,
  input  logic [TID_BITS-1:0] tid_i,
  input  logic [E+M:0]        s_i,
  input  logic [E+M:0]        t_i,
  input  logic [31:0]         width_i,   // the texture entry's words 0..2
  input  logic [31:0]         height_i,
  input  logic [31:0]         addr_i,
  output logic                valid_o,
  input  logic                ready_i,
  output logic [TID_BITS-1:0] tid_o,
  output logic [31:0]         row0_o,    // address + y0 width, address + y1 width (words)
  output logic [31:0]         row1_o,
  output logic [31:0]         x0_o,      // the columns
  output logic [31:0]         x1_o,
  output logic [8:0]          fx_o,      // the fractions in Q8 (0..256)
  output logic [8:0]          fy_o
);
  localparam int SIDE = TID_BITS + 64;

  // ---- the two axes, advancing while their result can go into the output register
  logic en_a, load, ax_valid;
  logic [31:0] x0, x1, y0, y1, a_addr, a_width;
  logic [8:0] fx, fy;
  logic [TID_BITS-1:0] a_tid;
  assign load = !valid_o || ready_i;
  assign en_a = !ax_valid || load;
  assign ready_o = en_a;
  /* verilator lint_off PINCONNECTEMPTY */
  tex_axis #(.E(E), .M(M), .SIDE_W(SIDE), .CVT_STAGES(CVT_STAGES), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
    .CMP_STAGES(CMP_STAGES), .TOI_STAGES(TOI_STAGES), .MOD_STAGES(MOD_STAGES)) u_s (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en_a), .valid_i(valid_i), .s_i(s_i), .n_i(width_i), .side_i({tid_i, addr_i, width_i}), .valid_o(ax_valid),
    .i0_o(x0), .i1_o(x1), .frac_o(fx), .side_o({a_tid, a_addr, a_width}));
  tex_axis #(.E(E), .M(M), .SIDE_W(1), .CVT_STAGES(CVT_STAGES), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES),
    .CMP_STAGES(CMP_STAGES), .TOI_STAGES(TOI_STAGES), .MOD_STAGES(MOD_STAGES)) u_t (.clk_i(clk_i), .rst_ni(rst_ni),
    .en_i(en_a), .valid_i(valid_i), .s_i(t_i), .n_i(height_i), .side_i(1'b0), .valid_o(), .i0_o(y0), .i1_o(y1),
    .frac_o(fy), .side_o());
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- the rows' addresses
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) valid_o <= 1'b0;
    else if (load) valid_o <= ax_valid;
  end
  always_ff @(posedge clk_i) begin
    if (load && ax_valid) begin
      tid_o <= a_tid;
      row0_o <= a_addr + y0 * a_width;
      row1_o <= a_addr + y1 * a_width;
      x0_o <= x0;
      x1_o <= x1;
      fx_o <= fx;
      fy_o <= fy;
    end
  end
endmodule
