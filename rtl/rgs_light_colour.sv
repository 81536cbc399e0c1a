// rgs_light_colour: a light's colour scaled to a maximum component of one, in Q12 (paper section
// 3: the lights of the fixed-function shading; hls/units/rgs_light.c `rgs_light_colour`,
// docs/shading.md: C = colour / its largest component), bit for bit as the C: m = max(max(r, g), b)
// (2 `f24_cmp`, the C's f24_max), each component q(c / m) (3 `f24_div`, 3 `q12_of`), all 0 unless
// 0 < m (`f24_cmp`). Once per light and packet, beside `rgs_light`; the thread id travels with
// the valid bit.
// Latency LATENCY = max(2 CMP + DIV + Q, 3 CMP) with Q = MUL + ADD + TOI (default 27) cycles, one
// colour per cycle (II = 1); handshake valid/ready, the pipeline advances when the output is free
// or taken. Resources: 3 comparators, 3 dividers, 3 `q12_of`, delay lines for the colour (2 CMP).
module rgs_light_colour #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TID_BITS = 6,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2,
  parameter int TOI_STAGES = 2
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 valid_i,
  output logic                 ready_o,
  input  logic [TID_BITS-1:0]  tid_i,
  input  logic [3*(E+M+1)-1:0] colour_i,  // the light record's words 1..3 (R from the low word up)
  output logic                 valid_o,
  input  logic                 ready_i,
  output logic [TID_BITS-1:0]  tid_o,
  output logic [3*16-1:0]      q_o        // R, G, B in Q12 from the low half-word up
);
  localparam int W = 1 + E + M;
  localparam int TQ = 2 * CMP_STAGES + DIV_STAGES + MUL_STAGES + ADD_STAGES + TOI_STAGES;
  localparam int TP = 3 * CMP_STAGES;
  localparam int LATENCY = TQ > TP ? TQ : TP;

  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;

  /* verilator lint_off PINCONNECTEMPTY */
  logic [W-1:0] m01, b_q, m;
  logic [2*W-1:0] rg_q;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [3:0] pos_flags;  // lt only
  /* verilator lint_on UNUSEDSIGNAL */
  logic pos_q;
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_m01 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(colour_i[0 +: W]), .b_i(colour_i[W +: W]), .valid_o(), .flags_o(), .min_o(), .max_o(m01));
  f24_pipe #(.W(W), .STAGES(CMP_STAGES)) u_d_b (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(colour_i[2*W +: W]), .valid_o(), .data_o(b_q));
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_m (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(m01), .b_i(b_q), .valid_o(), .flags_o(), .min_o(), .max_o(m));
  f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_pos (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i('0), .b_i(m), .valid_o(), .flags_o(pos_flags), .min_o(), .max_o());
  f24_pipe #(.W(1), .STAGES(LATENCY - TP)) u_d_pos (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(pos_flags[0]), .valid_o(), .data_o(pos_q));
  f24_pipe #(.W(2 * W), .STAGES(2 * CMP_STAGES)) u_d_rg (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(colour_i[0 +: 2*W]), .valid_o(), .data_o(rg_q));
  for (genvar k = 0; k < 3; k++) begin : g_ch
    logic [W-1:0] c, ratio;
    logic [15:0] q, q_q;
    if (k < 2) begin : g_rg
      assign c = rg_q[k*W +: W];
    end else begin : g_b
      f24_pipe #(.W(W), .STAGES(CMP_STAGES)) u_d_b2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
        .data_i(b_q), .valid_o(), .data_o(c));
    end
    f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_div (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .a_i(c), .b_i(m), .valid_o(), .res_o(ratio));
    q12_of #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES), .TOI_STAGES(TOI_STAGES)) u_q (
      .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0), .x_i(ratio), .valid_o(), .q_o(q));
    f24_pipe #(.W(16), .STAGES(LATENCY - TQ)) u_d_q (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .data_i(q), .valid_o(), .data_o(q_q));
    assign q_o[16*k +: 16] = pos_q ? q_q : '0;
  end
  f24_pipe #(.W(TID_BITS), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
    .data_i(tid_i), .valid_o(valid_o), .data_o(tid_o));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
