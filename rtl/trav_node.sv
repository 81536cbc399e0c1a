// trav_node: the traversal unit's per-node decision for a packet of 4 rays (paper section 3;
// hls/units/trav_node.c). Per ray in mask_i: t_split = (split - O_axis) / D_axis, near side =
// left unless D_axis has its sign bit set, near = [tn, min(tf, t_split)], far =
// [max(tn, t_split), tf], child mask bits for non-empty intervals; rays outside the mask get
// [0, 0]. Datapath: 4 subtractors, 4 dividers (Table 2: 4 add, 4 div), 4 min, 4 max and 8
// interval comparators. Latency LATENCY (default: adder 3 + divider 6 + min/max 1 + comparator
// 1 = 11), one node per cycle (II = 1). Handshake: valid/ready.
module trav_node #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int LATENCY = 11
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
  output logic [4*(E+M+1)-1:0]    r_tf_o
);
  localparam int W = 1 + E + M;
  /* verilator lint_off UNUSEDSIGNAL */
  logic nc_lt_o [64], nc_le_o [64], nc_eq_o [64], nc_unordered_o [64];
  logic [E+M:0] nc_min_o [64], nc_max_o [64]; // comparator outputs this datapath does not use
  /* verilator lint_on UNUSEDSIGNAL */
  logic [3:0] l_mask, r_mask, near_left;
  logic [4*W-1:0] l_tn, l_tf, r_tn, r_tf;

  for (genvar i = 0; i < 4; i++) begin : g_ray
    logic [W-1:0] ok, dk, diff, ts, tn, tf, near_tf, far_tn, ltn, ltf, rtn, rtf;
    /* verilator lint_off UNUSEDSIGNAL */
    logic [3:0] fl, fr; // {unordered, eq, le, lt}: le is used
    /* verilator lint_on UNUSEDSIGNAL */
    logic left;
    assign ok = o_i[(3*i + 32'(axis_i))*W +: W];
    assign dk = d_i[(3*i + 32'(axis_i))*W +: W];
    assign tn = tn_i[i*W +: W];
    assign tf = tf_i[i*W +: W];
    f24_add_core #(.E(E), .M(M)) u_sub (.a_i(split_i), .b_i(ok), .sub_i(1'b1), .res_o(diff));
    f24_div_core #(.E(E), .M(M)) u_div (.a_i(diff), .b_i(dk), .res_o(ts));
    f24_cmp_core #(.E(E), .M(M)) u_min (.a_i(tf), .b_i(ts), .lt_o(nc_lt_o[0]), .le_o(nc_le_o[1]), .eq_o(nc_eq_o[2]), .unordered_o(nc_unordered_o[3]),
                                        .min_o(near_tf), .max_o(nc_max_o[4]));
    f24_cmp_core #(.E(E), .M(M)) u_max (.a_i(tn), .b_i(ts), .lt_o(nc_lt_o[5]), .le_o(nc_le_o[6]), .eq_o(nc_eq_o[7]), .unordered_o(nc_unordered_o[8]),
                                        .min_o(nc_min_o[9]), .max_o(far_tn));
    assign left = !dk[W-1];
    assign ltn = !mask_i[i] ? '0 : left ? tn : far_tn;
    assign ltf = !mask_i[i] ? '0 : left ? near_tf : tf;
    assign rtn = !mask_i[i] ? '0 : left ? far_tn : tn;
    assign rtf = !mask_i[i] ? '0 : left ? tf : near_tf;
    f24_cmp_core #(.E(E), .M(M)) u_cl (.a_i(ltn), .b_i(ltf), .lt_o(fl[0]), .le_o(fl[1]), .eq_o(fl[2]),
                                       .unordered_o(fl[3]), .min_o(nc_min_o[10]), .max_o(nc_max_o[11]));
    f24_cmp_core #(.E(E), .M(M)) u_cr (.a_i(rtn), .b_i(rtf), .lt_o(fr[0]), .le_o(fr[1]), .eq_o(fr[2]),
                                       .unordered_o(fr[3]), .min_o(nc_min_o[12]), .max_o(nc_max_o[13]));
    assign l_mask[i] = mask_i[i] && fl[1];
    assign r_mask[i] = mask_i[i] && fr[1];
    assign near_left[i] = mask_i[i] && left;
    assign l_tn[i*W +: W] = ltn;
    assign l_tf[i*W +: W] = ltf;
    assign r_tn[i*W +: W] = rtn;
    assign r_tf[i*W +: W] = rtf;
  end

  logic en;
  assign en = ready_i || !valid_o;
  assign ready_o = en;
  f24_pipe #(.W(12 + 16 * W), .STAGES(LATENCY)) u_pipe (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en), .valid_i(valid_i),
    .data_i({l_mask, r_mask, near_left, l_tn, l_tf, r_tn, r_tf}),
    .valid_o(valid_o), .data_o({l_mask_o, r_mask_o, near_left_o, l_tn_o, l_tf_o, r_tn_o, r_tf_o})
  );
endmodule
