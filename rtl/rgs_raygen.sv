// rgs_raygen: the RGS's primary ray generation (paper sections 2.2 and 3, Figure 2 path a;
// hls/units/rgs.c rgs_primary, docs/shading.md). For a 2x2 pixel block with top-left pixel
// (x0, y0) it produces the 4-ray packet bit for bit as the C: ray i = pixel (x0 + i%2, y0 + i/2)
// (32-bit sums), pixel centre p = ((2x + 1)/2, (2y + 1)/2) as f24_mul(f24_from_i32(2x + 1), 1/2)
// computes it (the 32-bit 2x + 1 read as int32, so x >= 2^30 gives the C's negative centres; the
// halving is exact, so one f24_from_i32 converter with SCALE = -1 per coordinate), then through
// the transformation unit T_init = [U V W; O]:
//   perspective (camera word 0 != 1): origin O, direction xform_vector(T_init, (px, py, 1));
//   orthographic (word 0 == 1):       origin xform_point(T_init, (px, py, 0)), direction W;
// active bit i = x < width && y < height; tmin 0, tmax +Inf. This is the configuration with
// SAARCOR_CFG_ORTHOGRAPHIC = 1 (hls/config.h); a profile without orthographic cameras never
// loads kind 1.
// Camera: the 16 words of the camera block (kind, width, height, profile, O, U, V, W;
// docs/memory-image.md) are loaded once per frame through the camera-load port (one word per
// cycle, any order; the profile word is not needed here and is dropped); a load is accepted only
// while no block is held or in flight, so every packet sees one camera.
// Datapath: two f24_from_i32 (CVT_STAGES), one xform_unit (9 mul, 9 add), the packet collector.
// One ray enters the transformation unit per cycle: a packet every 4 cycles (the origin of a
// perspective packet and the direction of an orthographic one are camera words, no step; the
// cycle model charges TRACE_PACKET + 1 = 5 steps, docs/cycle-model.md). A block is taken while its
// predecessor issues its last ray, so back-to-back blocks leave no gap.
// Latency: block accepted to packet valid 1 + CVT_STAGES + LATENCY_XF + 4 cycles (default
// 1 + 3 + 22 + 4 = 30; 29 at CVT 2 until 2026-11-29); throughput one packet per 4 cycles (one ray per cycle).
// Handshakes: valid/ready on the camera port, the block input and the packet output; a stalled
// packet output stops the converters and the transformation unit (one enable).
// Resources: the xform_unit, two converters, 12 camera words + 2 x 32-bit size registers,
// 4 x 3 result words and 4 active bits in the collector; Yosys 0.23 synth_xilinx at e7m16:
// 7257 LUTs, 5057 FFs, 27 DSP48E1 (the xform_unit alone: 7004, 4232, 27; docs/synth.md).
module rgs_raygen #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int ADD_STAGES = 6,
  parameter int MUL_STAGES = 4,
  parameter int CVT_STAGES = 3
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // camera-load port
  input  logic                  cam_valid_i,
  output logic                  cam_ready_o,
  input  logic [3:0]            cam_idx_i,   // word of the camera block
  input  logic [31:0]           cam_word_i,
  // blocks
  input  logic                  blk_valid_i,
  output logic                  blk_ready_o,
  input  logic [31:0]           blk_x_i,
  input  logic [31:0]           blk_y_i,
  // packets: ray i in word group i (ray 0 in the low words)
  output logic                  pkt_valid_o,
  input  logic                  pkt_ready_i,
  output logic [3:0]            pkt_active_o,
  output logic [4*3*(E+M+1)-1:0] pkt_o_o,
  output logic [4*3*(E+M+1)-1:0] pkt_d_o,
  output logic [4*(E+M+1)-1:0]  pkt_tmin_o,
  output logic [4*(E+M+1)-1:0]  pkt_tmax_o
);
  localparam int W = 1 + E + M;
  localparam int LATENCY_XF = MUL_STAGES + 3 * ADD_STAGES;
  localparam logic [W-1:0] ONE = {2'b00, {(E-1){1'b1}}, {M{1'b0}}};
  localparam logic [W-1:0] POS_INF = {1'b0, {E{1'b1}}, {M{1'b0}}};

  // ---- camera registers: kind == 1, width, height, O U V W (words 4..15)
  logic ortho_q;
  logic [31:0] width_q, height_q;
  logic [W-1:0] cam_q [4:15];
  localparam int PW = $clog2(CVT_STAGES + LATENCY_XF + 9) + 1;
  logic [PW-1:0] pending_q; // rays issued whose packet has not left yet (at most the pipeline's + 8)
  logic busy_q;            // a block is held
  assign cam_ready_o = !busy_q && pending_q == 0;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ortho_q <= 1'b0;
      width_q <= '0;
      height_q <= '0;
    end else if (cam_valid_i && cam_ready_o) begin
      case (cam_idx_i)
        4'd0: ortho_q <= cam_word_i == 32'd1;
        4'd1: width_q <= cam_word_i;
        4'd2: height_q <= cam_word_i;
        default: ;
      endcase
    end
  end
  always_ff @(posedge clk_i) begin
    if (cam_valid_i && cam_ready_o && cam_idx_i >= 4'd4)
      cam_q[cam_idx_i] <= cam_word_i[W-1:0];
  end

  // T_init: row r = (U[r], V[r], W[r], O[r]), row 0 in the low words
  logic [12*W-1:0] t_init;
  for (genvar r = 0; r < 3; r++) begin : g_t
    assign t_init[(4*r+0)*W +: W] = cam_q[7 + r];
    assign t_init[(4*r+1)*W +: W] = cam_q[10 + r];
    assign t_init[(4*r+2)*W +: W] = cam_q[13 + r];
    assign t_init[(4*r+3)*W +: W] = cam_q[4 + r];
  end

  // ---- issue: one ray of the held block per cycle while the pipeline advances
  logic en;                    // the enable of converters and transformation unit (xform's ready_o)
  logic [31:0] bx_q, by_q, x, y;
  logic [1:0] lane_q;
  logic issue, take, act;
  assign issue = busy_q && en;
  assign blk_ready_o = !busy_q || (issue && lane_q == 2'd3);
  assign take = blk_valid_i && blk_ready_o;
  assign x = bx_q + 32'(lane_q[0]);
  assign y = by_q + 32'(lane_q[1]);
  assign act = x < width_q && y < height_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      busy_q <= 1'b0;
      lane_q <= '0;
    end else begin
      if (issue) lane_q <= lane_q + 2'd1;
      if (take) busy_q <= 1'b1;
      else if (issue && lane_q == 2'd3) busy_q <= 1'b0;
    end
  end
  always_ff @(posedge clk_i) begin
    if (take) begin
      bx_q <= blk_x_i;
      by_q <= blk_y_i;
    end
  end

  // ---- pixel centres (2x + 1) * 2^-1, then T_init
  logic cv_valid;
  logic [W-1:0] px, py, pz;
  /* verilator lint_off PINCONNECTEMPTY */
  f24_from_i32 #(.E(E), .M(M), .SCALE(-1), .STAGES(CVT_STAGES)) u_cx (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(issue), .a_i({x[30:0], 1'b1}), .valid_o(cv_valid), .res_o(px));
  f24_from_i32 #(.E(E), .M(M), .SCALE(-1), .STAGES(CVT_STAGES)) u_cy (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .a_i({y[30:0], 1'b1}), .valid_o(), .res_o(py));
  assign pz = ortho_q ? '0 : ONE;

  logic xf_valid, xf_ready, act_xf;
  logic [3*W-1:0] xf_r;
  xform_unit #(.E(E), .M(M), .ADD_STAGES(ADD_STAGES), .MUL_STAGES(MUL_STAGES)) u_xf (.clk_i(clk_i), .rst_ni(rst_ni),
    .valid_i(cv_valid), .ready_o(en), .m_i(t_init), .v_i({pz, py, px}), .point_i(ortho_q), .valid_o(xf_valid),
    .ready_i(xf_ready), .r_o(xf_r));
  // the active bit beside converter and transformation unit
  f24_pipe #(.W(1), .STAGES(CVT_STAGES + LATENCY_XF)) u_act (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
    .valid_i(1'b0), .data_i(act), .valid_o(), .data_o(act_xf));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- collector: 4 results make the packet
  logic [1:0] slot_q;
  logic [3*W-1:0] res_q [0:3];
  logic [3:0] act_q;
  logic pkt_valid_q, put, out;
  assign xf_ready = !pkt_valid_q || pkt_ready_i;
  assign put = xf_valid && xf_ready;
  assign out = pkt_valid_q && pkt_ready_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      slot_q <= '0;
      pkt_valid_q <= 1'b0;
      pending_q <= '0;
    end else begin
      if (put) slot_q <= slot_q + 2'd1;
      if (put && slot_q == 2'd3) pkt_valid_q <= 1'b1;
      else if (out) pkt_valid_q <= 1'b0;
      pending_q <= pending_q + PW'(issue) - (out ? PW'(4) : PW'(0));
    end
  end
  always_ff @(posedge clk_i) begin
    if (put) begin
      res_q[slot_q] <= xf_r;
      act_q[slot_q] <= act_xf;
    end
  end

  assign pkt_valid_o = pkt_valid_q;
  assign pkt_active_o = act_q;
  for (genvar i = 0; i < 4; i++) begin : g_ray
    assign pkt_o_o[3*W*i +: 3*W] = ortho_q ? res_q[i] : {cam_q[6], cam_q[5], cam_q[4]};
    assign pkt_d_o[3*W*i +: 3*W] = ortho_q ? {cam_q[15], cam_q[14], cam_q[13]} : res_q[i];
    assign pkt_tmin_o[W*i +: W] = '0;
    assign pkt_tmax_o[W*i +: W] = POS_INF;
  end
endmodule
