// rgs_add_light: the light of a visible light source added to a ray's Q12 diffuse and highlight
// sums (paper section 3: the lights' contributions, each after its shadow ray; hls/units/rgs_light.c
// `rgs_add_light`, called by `add_light` for each ray the shadow packet found unoccluded), bit for
// bit as the C: per channel k, diffuse_k + q(diff colour_k) and highlight_k + q(spec colour_k),
// each sum saturated at 65535 (6 `q12_mul`, 6 17-bit adders with saturation). The thread id
// travels with the valid bit.
// Latency 1 cycle (the sums registered), one ray per cycle; handshake valid/ready, the register
// loads when the output is free or taken. Resources: 6 16 x 16-bit multipliers, 6 adders, 102
// flip-flops (sums, thread id, valid).
module rgs_add_light #(
  parameter int TID_BITS = 6
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  output logic                ready_o,
  input  logic [TID_BITS-1:0] tid_i,
  input  logic [3*16-1:0]     diffuse_i,    // the sums so far, R, G, B from the low half-word up
  input  logic [3*16-1:0]     highlight_i,
  input  logic [15:0]         diff_i,       // the light's weights at the ray (rgs_light)
  input  logic [15:0]         spec_i,
  input  logic [3*16-1:0]     colour_i,     // the light's colour (rgs_light_colour)
  output logic                valid_o,
  input  logic                ready_i,
  output logic [TID_BITS-1:0] tid_o,
  output logic [3*16-1:0]     diffuse_o,
  output logic [3*16-1:0]     highlight_o
);
  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;

  logic [3*16-1:0] diffuse, highlight;
  for (genvar k = 0; k < 3; k++) begin : g_ch
    logic [15:0] dc, sc;
    logic [16:0] ds, hs;
    q12_mul u_dc (.a_i(diff_i), .b_i(colour_i[16*k +: 16]), .p_o(dc));
    q12_mul u_sc (.a_i(spec_i), .b_i(colour_i[16*k +: 16]), .p_o(sc));
    assign ds = 17'(diffuse_i[16*k +: 16]) + 17'(dc);
    assign hs = 17'(highlight_i[16*k +: 16]) + 17'(sc);
    assign diffuse[16*k +: 16] = ds[16] ? 16'hFFFF : ds[15:0];
    assign highlight[16*k +: 16] = hs[16] ? 16'hFFFF : hs[15:0];
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) valid_o <= 1'b0;
    else if (en) valid_o <= valid_i;
  end
  always_ff @(posedge clk_i) begin
    if (en) begin
      tid_o <= tid_i;
      diffuse_o <= diffuse;
      highlight_o <= highlight;
    end
  end
endmodule
