// zz_pick_wrap: a measurement wrapper, not part of the design (kept out of rtl/, whose every module
// the DynRTP instantiates): trace_core's word port and packet output at THREADS threads, its inputs
// registered, the pick as before commit e6bdf47 (OLD = 1: lowest()'s priority loop) or as now (OLD =
// 0: rr_pick with no pointer). docs/synth.md's row, on a copy of the tree (synth.py reads rtl/*.sv):
//   cp -r rtl scripts /tmp/lvroot/ && cp scripts/zz_pick_wrap.sv /tmp/lvroot/rtl/ &&
//   python3 /tmp/lvroot/scripts/synth.py --levels zz_pick_wrap OLD=1   (12 LUT6 levels; OLD=0: 8)
module zz_pick_wrap #(parameter int THREADS = 64, parameter int OLD = 1, localparam int TW = $clog2(THREADS)) (
  input  logic clk_i, input logic rst_ni,
  input  logic [THREADS-1:0] mem_req_i, valid_i,
  input  logic [THREADS*32-1:0] addr_i, data_i,
  input  logic hdr_req_i, mem_req_ready_i, ready_i, mem_rsp_valid_i,
  output logic [THREADS-1:0] thr_ready_o, out_ready_o,
  output logic mem_req_valid_o, valid_o,
  output logic [31:0] mem_addr_o, data_o,
  output logic [TW:0] head_o);
  logic [THREADS-1:0] t_mem_req, t_valid, word_grant, out_grant;
  logic [31:0] t_addr [THREADS], t_data [THREADS];
  logic hdr_req;
  always_ff @(posedge clk_i) begin
    t_mem_req <= mem_req_i; t_valid <= valid_i; hdr_req <= hdr_req_i;
    for (int t = 0; t < THREADS; t++) begin t_addr[t] <= addr_i[t*32 +: 32]; t_data[t] <= data_i[t*32 +: 32]; end
  end
  function automatic logic [TW-1:0] lowest(input logic [THREADS-1:0] m);
    lowest = '0;
    for (int t = THREADS - 1; t >= 0; t--)
      if (m[t]) lowest = TW'(t);
  endfunction
  logic [TW-1:0] word_sel, out_sel;
  if (OLD) begin : g_old
    assign word_sel = lowest(t_mem_req);
    assign out_sel = lowest(t_valid);
    for (genvar t = 0; t < THREADS; t++) begin : g_t
      assign word_grant[t] = word_sel == TW'(t);
      assign out_grant[t] = out_sel == TW'(t) && valid_o;
    end
    assign valid_o = |t_valid;
  end else begin : g_new
    rr_pick #(.N(THREADS)) u_w (.req_i(t_mem_req), .after_i('0), .any_o(), .grant_o(word_grant), .index_o(word_sel), .after_o());
    rr_pick #(.N(THREADS)) u_o (.req_i(t_valid), .after_i('0), .any_o(valid_o), .grant_o(out_grant), .index_o(out_sel), .after_o());
  end
  localparam int QB = TW + 1;
  logic [TW:0] word_q [2**QB];
  logic [QB:0] word_wr, word_rd;
  logic word_take;
  assign mem_req_valid_o = (hdr_req || |t_mem_req) && word_wr - word_rd != (QB + 1)'(2**QB);
  assign mem_addr_o = hdr_req ? 32'd5 : t_addr[word_sel];
  assign word_take = mem_req_valid_o && mem_req_ready_i;
  assign head_o = word_q[word_rd[QB-1:0]];
  for (genvar t = 0; t < THREADS; t++) begin : g_r
    assign thr_ready_o[t] = !hdr_req && word_grant[t] && word_take;
  end
  assign out_ready_o = ready_i ? out_grant : '0;
  assign data_o = t_data[out_sel];
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin word_wr <= '0; word_rd <= '0; end
    else begin
      if (word_take) begin word_q[word_wr[QB-1:0]] <= hdr_req ? {1'b1, TW'(0)} : {1'b0, word_sel}; word_wr <= word_wr + 1'b1; end
      if (mem_rsp_valid_i) word_rd <= word_rd + 1'b1;
    end
endmodule
