// tb_core: test wrapper (not synthesized) around the ray tracing core (rtl/trace_core.sv) with 8
// threads and 4 traversal contexts (so that the traversal unit also refuses issues); the C++ bench
// (tb_core.cpp) is its memory (the word, kd-node and list read ports) and checks every packet's
// hits and counters against trace_begin/trace_step.
module tb_core #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int THREADS = 8,
  localparam int RW = (12 * (1 + E + M) + 27 + 3 + 31) / 32  // the word port's words per response
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  input  logic                        flush_i,
  input  logic                        valid_i,
  output logic                        ready_o,
  input  logic [$clog2(THREADS)-1:0]  thread_i,
  input  logic [2:0]                  flags_i,
  input  logic [3:0]                  active_i,
  input  logic [4*3*(E+M+1)-1:0]      o_i,
  input  logic [4*3*(E+M+1)-1:0]      d_i,
  input  logic [4*(E+M+1)-1:0]        tmin_i,
  input  logic [4*(E+M+1)-1:0]        tmax_i,
  output logic                        valid_o,
  input  logic                        ready_i,
  output logic [$clog2(THREADS)-1:0]  thread_o,
  output logic [4*32-1:0]             inst_o,
  output logic [4*32-1:0]             tri_o,
  output logic [4*(E+M+1)-1:0]        t_o,
  output logic [4*(E+M+1)-1:0]        u_o,
  output logic [4*(E+M+1)-1:0]        v_o,
  output logic [4*(E+M+1)-1:0]        cos_o,
  output logic [10*32-1:0]            count_o,
  output logic [$clog2(THREADS):0]    inflight_o,
  output logic                        mem_req_valid_o,
  input  logic                        mem_req_ready_i,
  output logic [31:0]                 mem_addr_o,
  input  logic                        mem_rsp_valid_i,
  input  logic [32*RW-1:0]            mem_rdata_i,
  output logic                        node_req_valid_o,
  input  logic                        node_req_ready_i,
  output logic [31:0]                 node_addr_o,
  input  logic                        node_rsp_valid_i,
  input  logic [31:0]                 node_w0_i,
  input  logic [31:0]                 node_w1_i,
  output logic                        list_req_o,
  input  logic                        list_req_ready_i,
  output logic [31:0]                 list_addr_o,
  input  logic                        list_rsp_valid_i,
  input  logic [31:0]                 list_rdata_i,
  output logic [5:0]                  issue_o
);
  trace_core #(.E(E), .M(M), .THREADS(THREADS)) u_core (.*);
endmodule
