// rgs_lerp: the barycentric interpolation of a hit's vertex attributes, u A + v B + (1 - u - v) C,
// one component per cycle (paper section 3: interpolated normals and texture coordinates;
// hls/units/rgs_geom.c `rgs_lerp`, called by `surface_at` for the 3 components of the decoded
// vertex normals and the 2 of each texture coordinate set), bit for bit as the C's
// ((u A + v B) + ((1 - u) - v) C): 3 `f24_mul`, 3 `f24_add` (two of them subtracting). The weight
// chain (1 - u) - v and u A + v B run side by side; the thread id travels with the valid bit.
// Latency LATENCY = 3 ADD_STAGES + MUL_STAGES (default 22) cycles, one component per cycle
// (II = 1); handshake valid/ready, the pipeline advances when the output is free or taken.
// Resources: 3 multipliers, 3 adders, delay lines for v (ADD), C (2 ADD) and u A + v B (ADD).
module rgs_lerp #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TID_BITS = 6,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  output logic                ready_o,
  input  logic [TID_BITS-1:0] tid_i,
  input  logic [E+M:0]        a_i,     // the attribute at vertices A, B, C
  input  logic [E+M:0]        b_i,
  input  logic [E+M:0]        c_i,
  input  logic [E+M:0]        u_i,     // the hit's barycentrics
  input  logic [E+M:0]        v_i,
  output logic                valid_o,
  input  logic                ready_i,
  output logic [TID_BITS-1:0] tid_o,
  output logic [E+M:0]        r_o
);
  localparam int W = 1 + E + M;
  localparam int BIAS = (1 << (E - 1)) - 1;
  localparam logic [W-1:0] ONE = {1'b0, E'(BIAS), {M{1'b0}}};
  localparam int LATENCY = 3 * ADD_STAGES + MUL_STAGES;

  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;

  /* verilator lint_off PINCONNECTEMPTY */
  logic [W-1:0] ua, vb, uavb, uavb_q, w1, v_q, w2, c_q, wc;
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_ua (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(u_i), .b_i(a_i), .valid_o(), .res_o(ua));
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_vb (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(v_i), .b_i(b_i), .valid_o(), .res_o(vb));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_uavb (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(ua), .b_i(vb), .sub_i(1'b0), .valid_o(), .res_o(uavb));
  f24_pipe #(.W(W), .STAGES(ADD_STAGES)) u_d_uavb (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(uavb), .valid_o(), .data_o(uavb_q));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_w1 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(ONE), .b_i(u_i), .sub_i(1'b1), .valid_o(), .res_o(w1));
  f24_pipe #(.W(W), .STAGES(ADD_STAGES)) u_d_v (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(v_i), .valid_o(), .data_o(v_q));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_w2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(w1), .b_i(v_q), .sub_i(1'b1), .valid_o(), .res_o(w2));
  f24_pipe #(.W(W), .STAGES(2 * ADD_STAGES)) u_d_c (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .data_i(c_i), .valid_o(), .data_o(c_q));
  f24_mul #(.E(E), .M(M), .STAGES(MUL_STAGES)) u_wc (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(w2), .b_i(c_q), .valid_o(), .res_o(wc));
  f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_r (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
    .a_i(uavb_q), .b_i(wc), .sub_i(1'b0), .valid_o(), .res_o(r_o));
  f24_pipe #(.W(TID_BITS), .STAGES(LATENCY)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
    .data_i(tid_i), .valid_o(valid_o), .data_o(tid_o));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
