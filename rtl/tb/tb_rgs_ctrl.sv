// tb_rgs_ctrl: test wrapper (not synthesized) around rgs_ctrl, the RGS's per-block control
// (rtl/rgs_ctrl.sv), with tags of 6 bits, and the shared units it uses (rgs_units with one
// controller: the frame set-up, ray generation, lights, accumulation), their two read ports merged
// by a mem_port onto the bench's one; the C++ bench (tb_rgs_ctrl.cpp) is its memory and its ray
// tracing core and checks every packet, pixel and primary hit against the C model.
module tb_rgs_ctrl #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  input  logic [3:0]                max_depth_i,
  input  logic                      shadows_i,
  input  logic                      blk_valid_i,
  output logic                      blk_ready_o,
  input  logic [5:0]                blk_tag_i,
  input  logic [31:0]               blk_x_i,
  input  logic [31:0]               blk_y_i,
  output logic                      tr_valid_o,
  input  logic                      tr_ready_i,
  output logic [5:0]                tr_tag_o,
  output logic [2:0]                tr_flags_o,
  output logic [3:0]                tr_active_o,
  output logic [4*3*(E+M+1)-1:0]    tr_o_o,
  output logic [4*3*(E+M+1)-1:0]    tr_d_o,
  output logic [4*(E+M+1)-1:0]      tr_tmin_o,
  output logic [4*(E+M+1)-1:0]      tr_tmax_o,
  input  logic                      hit_valid_i,
  output logic                      hit_ready_o,
  input  logic [4*32-1:0]           hit_inst_i,
  input  logic [4*32-1:0]           hit_tri_i,
  input  logic [4*(E+M+1)-1:0]      hit_t_i,
  input  logic [4*(E+M+1)-1:0]      hit_u_i,
  input  logic [4*(E+M+1)-1:0]      hit_v_i,
  input  logic [4*(E+M+1)-1:0]      hit_cos_i,
  output logic                      mem_req_valid_o,
  input  logic                      mem_req_ready_i,
  output logic [31:0]               mem_addr_o,
  input  logic                      mem_rsp_valid_i,
  input  logic [127:0]              mem_rdata_i,   // a line of 4 words
  output logic                      px_valid_o,
  input  logic                      px_ready_i,
  output logic [5:0]                px_tag_o,
  output logic [4*24-1:0]           px_rgb_o,
  output logic [4*32-1:0]           px_inst_o,
  output logic [4*32-1:0]           px_tri_o,
  output logic [4*(E+M+1)-1:0]      px_t_o,
  output logic [4*(E+M+1)-1:0]      px_u_o,
  output logic [4*(E+M+1)-1:0]      px_v_o,
  output logic [4*(E+M+1)-1:0]      px_cos_o,
  output logic [4:0]                st_o,       // the control's state: the bench's cycles per state
  output logic [4:0]                sst_o,      // rgs_surface's state (its cycles per state in SURF)
  output logic                      stk_wr_o,   // a task's first word written into the stack memory
  output logic                      stk_pop_o   // S_NEXT with the stack's top as the next task
);
  assign st_o = u_dut.st;
  assign stk_wr_o = u_dut.wr_q && u_dut.wc_q == '0;
  assign stk_pop_o = st_o == 5'd2 && !u_dut.nxt_q && u_dut.sp_q != '0;  // S_NEXT (to S_TRACE: the bench)
  assign sst_o = u_units.g_sf[0].u_surface.st;
  localparam int W = 1 + E + M, V = 3 * W;
  localparam int SF_DW = 67 + 2 * V + 4 * W, SR_DW = 205 + 3 * V + 2 * W, LI_DW = 40 + 5 * V + 2 * W, AL_DW = 178, AC_DW = 393 + 3 * V + 2 * W;
  // the controller's reads and the set-up's (rgs_units) on the bench's one line port
  logic [1:0] rd_valid, rd_ready, rd_rsp;
  logic [63:0] rd_addr;
  // rgs_units with one controller
  logic frame_ok;
  logic [31:0] n_lights, light_base;
  logic [4:0] profile;
  logic gen_req, gen_ack, gen_valid, li_req, li_ack, li_valid, lc_req, lc_ack, lc_valid, al_req, al_ack, al_valid;
  logic ac_req, ac_ack, ac_valid, li_active, ac_ract, ac_tact;
  logic sf_req, sf_ack, sf_valid;
  logic [SF_DW-1:0] sf_data;
  logic [SR_DW-1:0] sf_res;
  logic [63:0] gen_data;
  logic [3:0] gen_active;
  logic [4*V-1:0] gen_o, gen_d;
  logic [LI_DW-1:0] li_data;
  logic [1:0] li_ray, al_ray, ac_ray;
  logic [V-1:0] li_o, li_d, lc_data, ac_ro, ac_rd, ac_to, ac_td;
  logic [W-1:0] li_tmin, li_tmax;
  logic [15:0] li_diff, li_spec;
  logic [47:0] lc_q, al_dif, al_hil, ac_acc, ac_rw, ac_tw;
  logic [AL_DW-1:0] al_data;
  logic [AC_DW-1:0] ac_data;
  /* verilator lint_off PINCONNECTEMPTY */
  mem_port #(.N(2), .DW(128), .DEPTH(16)) u_reads (
    .clk_i(clk_i), .rst_ni(rst_ni), .req_valid_i(rd_valid), .req_ready_o(rd_ready), .req_addr_i(rd_addr),
    .req_bytes_i({2{8'd16}}), .rsp_valid_o(rd_rsp), .rsp_data_o(), .mem_req_valid_o(mem_req_valid_o),
    .mem_req_ready_i(mem_req_ready_i), .mem_req_addr_o(mem_addr_o), .mem_req_bytes_o(), .mem_req_src_o(),
    .mem_rsp_valid_i(mem_rsp_valid_i), .mem_rsp_data_i(mem_rdata_i));
  /* verilator lint_on PINCONNECTEMPTY */
  rgs_units #(.E(E), .M(M), .N(1), .SURF_UNITS(1)) u_units (
    .clk_i(clk_i), .rst_ni(rst_ni), .mem_req_valid_o(rd_valid[1]), .mem_req_ready_i(rd_ready[1]),
    .mem_addr_o(rd_addr[63:32]), .mem_rsp_valid_i(rd_rsp[1]), .mem_rdata_i(mem_rdata_i), .frame_ok_o(frame_ok),
    .n_lights_o(n_lights), .light_base_o(light_base), .profile_o(profile),
    .sf_req_i(sf_req), .sf_data_i(sf_data), .sf_ack_o(sf_ack), .sf_valid_o(sf_valid), .sf_res_o(sf_res),
    .gen_req_i(gen_req), .gen_data_i(gen_data), .gen_ack_o(gen_ack), .gen_valid_o(gen_valid),
    .gen_active_o(gen_active), .gen_o_o(gen_o), .gen_d_o(gen_d),
    .li_req_i(li_req), .li_data_i(li_data), .li_ack_o(li_ack), .li_valid_o(li_valid), .li_ray_o(li_ray),
    .li_o_o(li_o), .li_d_o(li_d), .li_tmin_o(li_tmin), .li_tmax_o(li_tmax), .li_active_o(li_active),
    .li_diff_o(li_diff), .li_spec_o(li_spec),
    .lc_req_i(lc_req), .lc_data_i(lc_data), .lc_ack_o(lc_ack), .lc_valid_o(lc_valid), .lc_q_o(lc_q),
    .al_req_i(al_req), .al_data_i(al_data), .al_ack_o(al_ack), .al_valid_o(al_valid), .al_ray_o(al_ray),
    .al_dif_o(al_dif), .al_hil_o(al_hil),
    .ac_req_i(ac_req), .ac_data_i(ac_data), .ac_ack_o(ac_ack), .ac_valid_o(ac_valid), .ac_ray_o(ac_ray),
    .ac_acc_o(ac_acc), .ac_ro_o(ac_ro), .ac_rd_o(ac_rd), .ac_rw_o(ac_rw), .ac_ract_o(ac_ract), .ac_to_o(ac_to),
    .ac_td_o(ac_td), .ac_tw_o(ac_tw), .ac_tact_o(ac_tact));
  rgs_ctrl #(.E(E), .M(M), .TAG_BITS(6)) u_dut (
    .clk_i(clk_i), .rst_ni(rst_ni), .max_depth_i(max_depth_i), .shadows_i(shadows_i),
    .frame_ok_i(frame_ok), .n_lights_i(n_lights), .light_base_i(light_base), .profile_i(profile),
    .sf_req_o(sf_req), .sf_ack_i(sf_ack), .sf_data_o(sf_data), .sf_valid_i(sf_valid), .sf_res_i(sf_res),
    .gen_req_o(gen_req), .gen_ack_i(gen_ack), .gen_data_o(gen_data), .gen_valid_i(gen_valid),
    .gen_active_i(gen_active), .gen_o_i(gen_o), .gen_d_i(gen_d),
    .li_req_o(li_req), .li_ack_i(li_ack), .li_data_o(li_data), .li_valid_i(li_valid), .li_ray_i(li_ray),
    .li_o_i(li_o), .li_d_i(li_d), .li_tmin_i(li_tmin), .li_tmax_i(li_tmax), .li_active_i(li_active),
    .li_diff_i(li_diff), .li_spec_i(li_spec),
    .lc_req_o(lc_req), .lc_ack_i(lc_ack), .lc_data_o(lc_data), .lc_valid_i(lc_valid), .lc_q_i(lc_q),
    .al_req_o(al_req), .al_ack_i(al_ack), .al_data_o(al_data), .al_valid_i(al_valid), .al_ray_i(al_ray),
    .al_dif_i(al_dif), .al_hil_i(al_hil),
    .ac_req_o(ac_req), .ac_ack_i(ac_ack), .ac_data_o(ac_data), .ac_valid_i(ac_valid), .ac_ray_i(ac_ray),
    .ac_acc_i(ac_acc), .ac_ro_i(ac_ro), .ac_rd_i(ac_rd), .ac_rw_i(ac_rw), .ac_ract_i(ac_ract), .ac_to_i(ac_to),
    .ac_td_i(ac_td), .ac_tw_i(ac_tw), .ac_tact_i(ac_tact),
    .blk_valid_i(blk_valid_i),
    .blk_ready_o(blk_ready_o), .blk_tag_i(blk_tag_i), .blk_x_i(blk_x_i), .blk_y_i(blk_y_i), .tr_valid_o(tr_valid_o),
    .tr_ready_i(tr_ready_i), .tr_tag_o(tr_tag_o), .tr_flags_o(tr_flags_o), .tr_active_o(tr_active_o),
    .tr_o_o(tr_o_o), .tr_d_o(tr_d_o), .tr_tmin_o(tr_tmin_o), .tr_tmax_o(tr_tmax_o), .hit_valid_i(hit_valid_i),
    .hit_ready_o(hit_ready_o), .hit_inst_i(hit_inst_i), .hit_tri_i(hit_tri_i), .hit_t_i(hit_t_i), .hit_u_i(hit_u_i),
    .hit_v_i(hit_v_i), .hit_cos_i(hit_cos_i), .mem_req_valid_o(rd_valid[0]), .mem_req_ready_i(rd_ready[0]),
    .mem_addr_o(rd_addr[31:0]), .mem_rsp_valid_i(rd_rsp[0]), .mem_rdata_i(mem_rdata_i), .px_valid_o(px_valid_o),
    .px_ready_i(px_ready_i), .px_tag_o(px_tag_o), .px_rgb_o(px_rgb_o), .px_inst_o(px_inst_o), .px_tri_o(px_tri_o),
    .px_t_o(px_t_o), .px_u_o(px_u_o), .px_v_o(px_v_o), .px_cos_o(px_cos_o));
endmodule
