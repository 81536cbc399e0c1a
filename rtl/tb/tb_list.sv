// tb_list: test wrapper (not synthesized) around the list unit (rtl/list_unit.sv) at the paper's
// 64 threads; the C++ bench (tb_list.cpp) is its memory and checks every result against the C unit.
module tb_list #(
  parameter int E = 7,  // unused: the Makefile passes the fp24 format to every bench
  parameter int M = 16,
  parameter int THREADS = 64
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  input  logic                        valid_i,
  output logic                        ready_o,
  input  logic [$clog2(THREADS)-1:0]  thread_i,
  input  logic                        level_i,
  input  logic                        clear_i,
  input  logic [31:0]                 lists_i,
  input  logic [31:0]                 first_i,
  input  logic [31:0]                 k_i,
  input  logic [3:0]                  leaf_mask_i,
  input  logic [3:0]                  alive_i,
  output logic                        mem_req_o,
  input  logic                        mem_req_ready_i,
  output logic [31:0]                 mem_addr_o,
  input  logic                        mem_rsp_valid_i,
  input  logic [31:0]                 mem_rdata_i,
  output logic                        valid_o,
  input  logic                        ready_i,
  output logic [$clog2(THREADS)-1:0]  thread_o,
  output logic                        level_o,
  output logic [31:0]                 key_o,
  output logic [3:0]                  need_o,
  output logic [3:0]                  skip_o,
  output logic [31:0]                 k_o
);
  if (E + M < 0) begin : g_unused
  end
  list_unit #(.THREADS(THREADS)) u_list (.*);
endmodule
