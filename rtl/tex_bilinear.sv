// tex_bilinear: the RGS's bilinear texture sample (paper section 3: bilinear filtering of 8-bit
// textures in the shading unit; hls/units/rgs_tex.c `rgs_sample_bilinear`, `rgs_bilinear_blend`;
// docs/shading.md), what `surface_at` does per texture it samples (base colour, emissive):
// texture coordinates (s, t) and the texture entry (width, height, texel address) in, the
// sample's R, G, B in Q12 out, bit for bit as the C.
//   axes     two `tex_axis` side by side (s over the width, t over the height): x0, x1, fx and
//            y0, y1, fy; the thread id, the address and the width travel beside the s axis
//   reads    the 4 texel words at address + y w + x in the C's order t00, t10, t01, t11, one
//            request a cycle on a memory port (word address out, word back; responses in order,
//            as `mem_port` returns them); the rows' y0 w and y1 w are two 32-bit products taken
//            when a sample enters the issuer (truncated to 32 bits as the C's uint32 sums)
//   blend    when the 4th word is back: per channel the bytes widened to Q12 (t << 4 | t >> 4),
//            top = c00 (256 - fx) + c10 fx, bottom likewise, (top (256 - fy) + bottom fy + 2^15)
//            >> 16 (integer multipliers of 12 x 9 bits and 21 x 9 bits)
// Up to OUTSTANDING samples wait for their texels (their fractions and thread ids in a FIFO).
// Handshake: valid/ready at the input, the memory request and response, and the output.
// Latency: the axes' (41 at the default operator depths, 38 at CVT 2) + 1 to the issuer, 4 request cycles and
// the memory's latency, + 1 for the blend register; throughput one sample per 4 cycles (the
// memory port's one word per cycle: 4 texel reads, as the C notes them). Resources: 2 `tex_axis`,
// 2 32 x 32-bit multipliers, 3 32-bit adders for the addresses, 12 small multipliers for the
// blend, the issuer's and collector's registers (about 8 x 32 + 4 x 24 bits), a FIFO of
// OUTSTANDING x (18 + TID_BITS) bits.
module tex_bilinear #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TID_BITS = 6,
  parameter int OUTSTANDING = 8,  // samples issued and not yet blended (a power of two)
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
  output logic                req_valid_o,
  input  logic                req_ready_i,
  output logic [31:0]         req_addr_o,
  input  logic                rsp_valid_i,
  output logic                rsp_ready_o,
  input  logic [31:0]         rsp_data_i,
  output logic                valid_o,
  input  logic                ready_i,
  output logic [TID_BITS-1:0] tid_o,
  output logic [3*16-1:0]     rgb_o      // R, G, B in Q12 from the low half-word up
);
  localparam int SIDE = TID_BITS + 64;
  localparam int PW = $clog2(OUTSTANDING);

  // ---- the two axes, advancing while their results can enter the issuer
  logic en_a, ax_valid, take;
  logic [31:0] x0, x1, y0, y1, a_addr, a_width;
  logic [8:0] fx, fy;
  logic [TID_BITS-1:0] a_tid;
  assign en_a = !ax_valid || take;
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

  // ---- the issuer: one sample's 4 texel addresses, one request a cycle
  logic busy_q, fifo_full, req_fire, last_req;
  logic [1:0] cnt_q;
  logic [31:0] row0_q, row1_q, x0_q, x1_q;
  assign req_fire = req_valid_o && req_ready_i;
  assign last_req = cnt_q == 2'd3 && req_fire;
  assign take = ax_valid && (!busy_q || last_req) && !fifo_full;
  assign req_valid_o = busy_q;
  assign req_addr_o = (cnt_q[1] ? row1_q : row0_q) + (cnt_q[0] ? x1_q : x0_q);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      busy_q <= 1'b0;
      cnt_q <= '0;
    end else begin
      if (take) busy_q <= 1'b1;
      else if (last_req) busy_q <= 1'b0;
      if (req_fire) cnt_q <= cnt_q + 2'd1;
    end
  end
  always_ff @(posedge clk_i) begin
    if (take) begin
      row0_q <= a_addr + y0 * a_width;
      row1_q <= a_addr + y1 * a_width;
      x0_q <= x0;
      x1_q <= x1;
    end
  end

  // ---- the fractions and thread ids of the samples whose texels are on their way
  logic [18+TID_BITS-1:0] fifo_q [OUTSTANDING];
  logic [PW:0] wr_q, rd_q;
  logic pop;
  assign fifo_full = wr_q - rd_q == (PW+1)'(OUTSTANDING);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wr_q <= '0;
      rd_q <= '0;
    end else begin
      if (take) wr_q <= wr_q + 1'b1;
      if (pop) rd_q <= rd_q + 1'b1;
    end
  end
  always_ff @(posedge clk_i) if (take) fifo_q[wr_q[PW-1:0]] <= {a_tid, fx, fy};

  // ---- the collector and the blend
  logic [1:0] rcnt_q;
  logic [31:0] tex_q [3];
  logic [8:0] hfx, hfy, hfx_c, hfy_c;  // the head sample's fractions and 256 minus them
  logic [TID_BITS-1:0] htid;
  logic [3*16-1:0] rgb;
  assign {htid, hfx, hfy} = fifo_q[rd_q[PW-1:0]];
  assign hfx_c = 9'd256 - hfx;
  assign hfy_c = 9'd256 - hfy;
  assign rsp_ready_o = !(rcnt_q == 2'd3 && valid_o && !ready_i);
  assign pop = rcnt_q == 2'd3 && rsp_valid_i && rsp_ready_o;
  for (genvar k = 0; k < 3; k++) begin : g_ch
    logic [11:0] c00, c10, c01, c11;  // the channel's bytes widened to Q12
    logic [31:0] top, bottom, sum;
    always_comb begin
      c00 = {tex_q[0][8*k +: 8], tex_q[0][8*k+4 +: 4]};
      c10 = {tex_q[1][8*k +: 8], tex_q[1][8*k+4 +: 4]};
      c01 = {tex_q[2][8*k +: 8], tex_q[2][8*k+4 +: 4]};
      c11 = {rsp_data_i[8*k +: 8], rsp_data_i[8*k+4 +: 4]};
      top = 32'(c00) * 32'(hfx_c) + 32'(c10) * 32'(hfx);
      bottom = 32'(c01) * 32'(hfx_c) + 32'(c11) * 32'(hfx);
      sum = top * 32'(hfy_c) + bottom * 32'(hfy) + 32'd32768;
    end
    assign rgb[16*k +: 16] = 16'(sum >> 16);
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rcnt_q <= '0;
      valid_o <= 1'b0;
    end else begin
      if (rsp_valid_i && rsp_ready_o) rcnt_q <= rcnt_q + 2'd1;
      if (pop) valid_o <= 1'b1;
      else if (ready_i) valid_o <= 1'b0;
    end
  end
  always_ff @(posedge clk_i) begin
    if (rsp_valid_i && rsp_ready_o && rcnt_q != 2'd3) tex_q[rcnt_q] <= rsp_data_i;
    if (pop) begin
      tid_o <= htid;
      rgb_o <= rgb;
    end
  end
endmodule
