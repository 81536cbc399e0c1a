// trav_node: the traversal unit's per-node decision for a packet of 4 rays (paper section 3;
// hls/units/trav_node.c). Per ray in mask_i: t_split = (split - O_axis) / D_axis, near side =
// left unless D_axis has its sign bit set, near = [tn, min(tf, t_split)], far =
// [max(tn, t_split), tf], child mask bits for non-empty intervals; rays outside the mask get
// [0, 0]. Datapath: 4 subtractors, 4 dividers (Table 2: 4 add, 4 div), 4 min, 4 max and 8
// interval comparators, all pipelined (rtl/f24_*.sv); the operands that join later wait in
// f24_pipe delay lines. Latency LATENCY = ADD_STAGES + DIV_STAGES + 2 CMP_STAGES (default
// 6 + 11 + 2 x 2 = 21), one node per cycle (II = 1); the clock is that of the operators
// (docs/synth.md). Handshake: valid/ready. ts_o, tn_q_o, tf_q_o: the slot's plane distances and
// its [tn, tf] at stage ADD_STAGES + DIV_STAGES, for trav_unit's clip chain (rtl/trav_clip.sv),
// which takes the 6 slab planes of a box in 6 slots back to back.
module trav_node #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int ADD_STAGES = 6,
  parameter int DIV_STAGES = 11,
  parameter int CMP_STAGES = 2
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic                    valid_i,
  output logic                    ready_o,
  input  logic [1:0]              axis_i,
  input  logic [E+M:0]            split_i,
  input  logic [3:0]              mask_i,
  input  logic [4*3*(E+M+1)-1:0]  o_i,      // ray i: words 3i .. 3i+2 (x, y, z)
  input  logic [4*3*(E+M+1)-1:0]  d_i,
  input  logic [4*(E+M+1)-1:0]    tn_i,
  input  logic [4*(E+M+1)-1:0]    tf_i,
  output logic                    valid_o,
  input  logic                    ready_i,
  output logic [3:0]              l_mask_o,
  output logic [3:0]              r_mask_o,
  output logic [3:0]              near_left_o,
  output logic [4*(E+M+1)-1:0]    l_tn_o,
  output logic [4*(E+M+1)-1:0]    l_tf_o,
  output logic [4*(E+M+1)-1:0]    r_tn_o,
  output logic [4*(E+M+1)-1:0]    r_tf_o,
  output logic [4*(E+M+1)-1:0]    ts_o,
  output logic [4*(E+M+1)-1:0]    tn_q_o,
  output logic [4*(E+M+1)-1:0]    tf_q_o
);
  localparam int W = 1 + E + M;
  localparam int LATENCY = ADD_STAGES + DIV_STAGES + 2 * CMP_STAGES;
  localparam int L_MM = LATENCY - CMP_STAGES;                    // min/max results
  logic [3:0] left_in, mask_q, left_q, mask_o, left_o, fl_le, fr_le;
  logic valid_q, en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;

  /* verilator lint_off PINCONNECTEMPTY */
  for (genvar i = 0; i < 4; i++) begin : g_ray
    logic [W-1:0] ok, dk, dk_q, diff, ts, tn_q, tf_q, tn_q2, tf_q2, near_tf, far_tn, ltn, ltf, rtn, rtf;
    /* verilator lint_off UNUSEDSIGNAL */
    logic [3:0] fl, fr; // {unordered, eq, le, lt}: le is used
    /* verilator lint_on UNUSEDSIGNAL */
    // the axis's component by a 3-way select on constant offsets (a variable offset times W maps
    // to a DSP multiplier, which hides a register from the LUT level count)
    assign ok = axis_i == 2'd0 ? o_i[3*i*W +: W] : axis_i == 2'd1 ? o_i[(3*i + 1)*W +: W] : o_i[(3*i + 2)*W +: W];
    assign dk = axis_i == 2'd0 ? d_i[3*i*W +: W] : axis_i == 2'd1 ? d_i[(3*i + 1)*W +: W] : d_i[(3*i + 2)*W +: W];
    assign left_in[i] = !dk[W-1];
    f24_add #(.E(E), .M(M), .STAGES(ADD_STAGES)) u_sub (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .a_i(split_i), .b_i(ok), .sub_i(1'b1), .valid_o(), .res_o(diff));
    f24_pipe #(.W(W), .STAGES(ADD_STAGES)) u_d_dk (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(1'b0),
      .data_i(dk), .valid_o(), .data_o(dk_q));
    f24_div #(.E(E), .M(M), .STAGES(DIV_STAGES)) u_div (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .a_i(diff), .b_i(dk_q), .valid_o(), .res_o(ts));
    f24_pipe #(.W(2 * W), .STAGES(ADD_STAGES + DIV_STAGES)) u_d_t (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i({tn_i[i*W +: W], tf_i[i*W +: W]}), .valid_o(), .data_o({tn_q, tf_q}));
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_min (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .a_i(tf_q), .b_i(ts), .valid_o(), .flags_o(), .min_o(near_tf), .max_o());
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_max (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .a_i(tn_q), .b_i(ts), .valid_o(), .flags_o(), .min_o(), .max_o(far_tn));
    f24_pipe #(.W(2 * W), .STAGES(CMP_STAGES)) u_d_t2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i({tn_q, tf_q}), .valid_o(), .data_o({tn_q2, tf_q2}));
    assign ltn = !mask_q[i] ? '0 : left_q[i] ? tn_q2 : far_tn;
    assign ltf = !mask_q[i] ? '0 : left_q[i] ? near_tf : tf_q2;
    assign rtn = !mask_q[i] ? '0 : left_q[i] ? far_tn : tn_q2;
    assign rtf = !mask_q[i] ? '0 : left_q[i] ? tf_q2 : near_tf;
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_cl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .a_i(ltn), .b_i(ltf), .valid_o(), .flags_o(fl), .min_o(), .max_o());
    f24_cmp #(.E(E), .M(M), .STAGES(CMP_STAGES)) u_cr (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .a_i(rtn), .b_i(rtf), .valid_o(), .flags_o(fr), .min_o(), .max_o());
    assign ts_o[i*W +: W] = ts;
    assign tn_q_o[i*W +: W] = tn_q;
    assign tf_q_o[i*W +: W] = tf_q;
    assign fl_le[i] = fl[1];
    assign fr_le[i] = fr[1];
    f24_pipe #(.W(4 * W), .STAGES(CMP_STAGES)) u_d_out (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en),
      .valid_i(1'b0), .data_i({ltn, ltf, rtn, rtf}), .valid_o(),
      .data_o({l_tn_o[i*W +: W], l_tf_o[i*W +: W], r_tn_o[i*W +: W], r_tf_o[i*W +: W]}));
  end
  /* verilator lint_on PINCONNECTEMPTY */

  // valid, mask and near side beside the datapath: to the min/max results, then to the output
  f24_pipe #(.W(8), .STAGES(L_MM)) u_ctl (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
    .data_i({mask_i, left_in}), .valid_o(valid_q), .data_o({mask_q, left_q}));
  f24_pipe #(.W(8), .STAGES(CMP_STAGES)) u_ctl2 (.clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_q),
    .data_i({mask_q, left_q}), .valid_o(valid_o), .data_o({mask_o, left_o}));
  assign l_mask_o = mask_o & fl_le;
  assign r_mask_o = mask_o & fr_le;
  assign near_left_o = mask_o & left_o;
endmodule
