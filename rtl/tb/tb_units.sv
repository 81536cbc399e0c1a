// tb_units: test wrapper (not synthesized) around the three datapath units, each with its own
// input stream: transformation unit, intersection unit, traversal node decision. The C++ bench
// (tb_units.cpp) holds ready_i high and checks every result against the C model.
module tb_units #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic                    x_valid_i,
  input  logic [12*(E+M+1)-1:0]   x_m_i,
  input  logic [3*(E+M+1)-1:0]    x_v_i,
  input  logic                    x_point_i,
  output logic                    x_valid_o,
  output logic [3*(E+M+1)-1:0]    x_r_o,
  input  logic                    i_valid_i,
  input  logic [3*(E+M+1)-1:0]    i_o_i,
  input  logic [3*(E+M+1)-1:0]    i_d_i,
  input  logic [E+M:0]            i_te_i,
  input  logic [E+M:0]            i_tmin_i,
  input  logic [E+M:0]            i_tmax_i,
  input  logic [2:0]              i_shared_i,
  output logic                    i_valid_o,
  output logic                    i_hit_o,
  output logic [E+M:0]            i_t_o,
  output logic [E+M:0]            i_u_o,
  output logic [E+M:0]            i_v_o,
  output logic [E+M:0]            i_cos_o,
  input  logic                    t_valid_i,
  input  logic [1:0]              t_axis_i,
  input  logic [E+M:0]            t_split_i,
  input  logic [3:0]              t_mask_i,
  input  logic [4*3*(E+M+1)-1:0]  t_o_i,
  input  logic [4*3*(E+M+1)-1:0]  t_d_i,
  input  logic [4*(E+M+1)-1:0]    t_tn_i,
  input  logic [4*(E+M+1)-1:0]    t_tf_i,
  output logic                    t_valid_o,
  output logic [3:0]              t_l_mask_o,
  output logic [3:0]              t_r_mask_o,
  output logic [3:0]              t_near_left_o,
  output logic [4*(E+M+1)-1:0]    t_l_tn_o,
  output logic [4*(E+M+1)-1:0]    t_l_tf_o,
  output logic [4*(E+M+1)-1:0]    t_r_tn_o,
  output logic [4*(E+M+1)-1:0]    t_r_tf_o
);
  /* verilator lint_off PINCONNECTEMPTY */
  xform_unit #(.E(E), .M(M)) u_x (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(x_valid_i), .ready_o(), .m_i(x_m_i),
                                  .v_i(x_v_i), .point_i(x_point_i), .valid_o(x_valid_o), .ready_i(1'b1), .r_o(x_r_o));
  isect_unit #(.E(E), .M(M)) u_i (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(i_valid_i), .ready_o(), .o_i(i_o_i),
                                  .d_i(i_d_i), .te_i(i_te_i), .tmin_i(i_tmin_i), .tmax_i(i_tmax_i),
                                  .shared_i(i_shared_i), .valid_o(i_valid_o), .ready_i(1'b1),
                                  .hit_o(i_hit_o), .t_o(i_t_o), .u_o(i_u_o), .v_o(i_v_o), .cos_o(i_cos_o));
  trav_node #(.E(E), .M(M)) u_t (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(t_valid_i), .ready_o(), .axis_i(t_axis_i),
                                 .split_i(t_split_i), .mask_i(t_mask_i), .o_i(t_o_i), .d_i(t_d_i), .tn_i(t_tn_i),
                                 .tf_i(t_tf_i), .valid_o(t_valid_o), .ready_i(1'b1), .l_mask_o(t_l_mask_o),
                                 .r_mask_o(t_r_mask_o), .near_left_o(t_near_left_o), .l_tn_o(t_l_tn_o),
                                 .l_tf_o(t_l_tf_o), .r_tn_o(t_r_tn_o), .r_tf_o(t_r_tf_o));
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
