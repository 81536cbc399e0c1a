// tex_fetch: the texel reads and the blend of the RGS's bilinear texture sample (paper section 3:
// bilinear filtering of 8-bit textures in the shading unit; hls/units/rgs_tex.c
// `rgs_sample_bilinear` from its reads on, `rgs_bilinear_blend`; docs/shading.md): the texel rows'
// word addresses, the columns and the fractions (`tex_coords`) in, the sample's R, G, B in Q12 out,
// bit for bit as the C. The second half of the sample (`tex_bilinear` until 2026-11-30); each
// rgs_surface has one on its own line port, the shared `tex_coords` in rgs_units before it.
//   reads    the 4 texel words at row + x in the C's order t00, t10, t01, t11 (row0 + x0, row0 + x1,
//            row1 + x0, row1 + x1), one request a cycle on a memory port (word address out, word
//            back; responses in order, as `mem_port` returns them)
//   blend    when the 4th word is back: per channel the bytes widened to Q12 (t << 4 | t >> 4),
//            top = c00 (256 - fx) + c10 fx, bottom likewise, (top (256 - fy) + bottom fy + 2^15)
//            >> 16 (integer multipliers of 12 x 9 bits and 21 x 9 bits)
// Up to OUTSTANDING samples wait for their texels (their fractions and thread ids in a FIFO).
// Handshake: valid/ready at the input, the memory request and response, and the output.
// Latency: 1 to the issuer, 4 request cycles and the memory's latency, + 1 for the blend register;
// throughput one sample per 4 cycles (the memory port's one word per cycle: 4 texel reads, as the
// C notes them). Resources: a 32-bit adder for the address, 12 small multipliers for the blend, the
// issuer's and collector's registers (about 7 x 32 bits), a FIFO of OUTSTANDING x (18 + TID_BITS)
// bits.
module tex_fetch #(
  parameter int TID_BITS = 6,
  parameter int OUTSTANDING = 8  // samples issued and not yet blended (a power of two)
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  output logic                ready_o,
  input  logic [TID_BITS-1:0] tid_i,
  input  logic [31:0]         row0_i,
  input  logic [31:0]         row1_i,
  input  logic [31:0]         x0_i,
  input  logic [31:0]         x1_i,
  input  logic [8:0]          fx_i,
  input  logic [8:0]          fy_i,
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
  localparam int PW = $clog2(OUTSTANDING);

  // ---- the issuer: one sample's 4 texel addresses, one request a cycle
  logic busy_q, fifo_full, req_fire, last_req, take;
  logic [1:0] cnt_q;
  logic [31:0] row0_q, row1_q, x0_q, x1_q;
  assign req_fire = req_valid_o && req_ready_i;
  assign last_req = cnt_q == 2'd3 && req_fire;
  assign ready_o = (!busy_q || last_req) && !fifo_full;
  assign take = valid_i && ready_o;
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
      row0_q <= row0_i;
      row1_q <= row1_i;
      x0_q <= x0_i;
      x1_q <= x1_i;
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
  always_ff @(posedge clk_i) if (take) fifo_q[wr_q[PW-1:0]] <= {tid_i, fx_i, fy_i};

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
