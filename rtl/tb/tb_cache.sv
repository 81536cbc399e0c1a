// tb_cache: test wrapper (not synthesized) of a DynRTP's memory interface: the four direct-mapped
// caches of the cycle model's defaults (kd nodes 4 KB / 8-byte lines, lists 2 KB / 4, matrices
// 6 KB / one packed triangle record of 4 ceil((12 (1+E+M) + 27) / 32) bytes, shading 4 KB / 16)
// on one memory port (rtl/mem_port.sv), each with 64 outstanding requests (the thread count: the
// cycle model has no limit). The C++ bench (tb_cache.cpp) is the requesters and the
// memory, and checks every response against the cycle model's caches.
module tb_cache #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int OUTSTANDING = 64
) (
  input  logic          clk_i,
  input  logic          rst_ni,
  input  logic          flush_i,
  input  logic [3:0]    req_valid_i,
  output logic [3:0]    req_ready_o,
  input  logic [31:0]   req_id_i,      // 8 bits per cache
  input  logic [127:0]  req_line_i,    // 32 bits per cache
  output logic [3:0]    rsp_valid_o,
  output logic [31:0]   rsp_id_o,
  output logic [3:0]    rsp_hit_o,
  output logic [63:0]   n_data_o,
  output logic [31:0]   l_data_o,
  output logic [MB*8-1:0] m_data_o,
  output logic [127:0]  s_data_o,
  output logic          mem_req_valid_o,
  output logic [31:0]   mem_req_addr_o,
  output logic [7:0]    mem_req_bytes_o,
  output logic [1:0]    mem_req_src_o,
  input  logic          mem_rsp_valid_i,
  input  logic [MB*8-1:0] mem_rsp_data_i
);
  localparam int MB = 4 * ((12 * (1 + E + M) + 27 + 31) / 32); // matrix line bytes
  localparam int LB [4] = '{8, 4, MB, 16};
  localparam int SZ [4] = '{4096, 2048, 6144, 4096};
  logic [3:0] mreq_valid, mreq_ready, mrsp_valid;
  logic [4*32-1:0] mreq_addr;
  logic [MB*8-1:0] mrsp_data;
  logic [64+32+8*MB+128-1:0] data_all;

  for (genvar c = 0; c < 4; c++) begin : g_cache
    localparam int OFF = c == 0 ? 0 : c == 1 ? 64 : c == 2 ? 96 : 96 + 8 * MB;
    cache_dm #(.LINE_BYTES(LB[c]), .SIZE_BYTES(SZ[c]), .OUTSTANDING(OUTSTANDING)) u_cache (
      .clk_i(clk_i), .rst_ni(rst_ni), .flush_i(flush_i),
      .req_valid_i(req_valid_i[c]), .req_ready_o(req_ready_o[c]), .req_id_i(req_id_i[c*8 +: 8]),
      .req_line_i(req_line_i[c*32 +: 32]), .req_idx_i($bits(u_cache.req_idx_i)'(req_line_i[c*32 +: 32] % 32'(SZ[c] / LB[c]))),
      .rsp_valid_o(rsp_valid_o[c]), .rsp_ready_i(1'b1), .rsp_id_o(rsp_id_o[c*8 +: 8]), .rsp_hit_o(rsp_hit_o[c]),
      .rsp_data_o(data_all[OFF +: 8*LB[c]]),
      .mem_req_valid_o(mreq_valid[c]), .mem_req_ready_i(mreq_ready[c]), .mem_req_addr_o(mreq_addr[c*32 +: 32]),
      .mem_rsp_valid_i(mrsp_valid[c]), .mem_rsp_data_i(mrsp_data[0 +: 8*LB[c]]));
  end
  assign n_data_o = data_all[0 +: 64];
  assign l_data_o = data_all[64 +: 32];
  assign m_data_o = data_all[96 +: 8*MB];
  assign s_data_o = data_all[96 + 8*MB +: 128];

  mem_port #(.N(4), .DW(8*MB)) u_port (
    .clk_i(clk_i), .rst_ni(rst_ni), .req_valid_i(mreq_valid), .req_ready_o(mreq_ready), .req_addr_i(mreq_addr),
    .req_bytes_i({8'(LB[3]), 8'(LB[2]), 8'(LB[1]), 8'(LB[0])}), .rsp_valid_o(mrsp_valid), .rsp_data_o(mrsp_data),
    .mem_req_valid_o(mem_req_valid_o), .mem_req_ready_i(1'b1), .mem_req_addr_o(mem_req_addr_o),
    .mem_req_bytes_o(mem_req_bytes_o), .mem_req_src_o(mem_req_src_o), .mem_rsp_valid_i(mem_rsp_valid_i),
    .mem_rsp_data_i(mem_rsp_data_i));
endmodule
