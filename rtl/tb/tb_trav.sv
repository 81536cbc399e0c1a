// tb_trav: test wrapper (not synthesized) around the traversal unit (rtl/trav_unit.sv) at the
// paper's 64 threads and stacks of TRACE_STACK = 64 entries; the C++ bench (tb_trav.cpp) is its
// kd-node memory and checks every result against the C unit.
module tb_trav #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int THREADS = 64,
  parameter int DEPTH = 64
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  input  logic                        valid_i,
  output logic                        ready_o,
  input  logic [$clog2(THREADS)-1:0]  thread_i,
  input  logic                        level_i,
  input  logic [1:0]                  kind_i,
  input  logic [4*3*(E+M+1)-1:0]      o_i,
  input  logic [4*3*(E+M+1)-1:0]      d_i,
  input  logic [4*(E+M+1)-1:0]        tn_i,
  input  logic [4*(E+M+1)-1:0]        tf_i,
  input  logic [4*(E+M+1)-1:0]        best_i,
  input  logic [3:0]                  mask_i,
  input  logic [6*(E+M+1)-1:0]        box_i,
  input  logic [31:0]                 nodes_i,
  output logic                        node_req_valid_o,
  input  logic                        node_req_ready_i,
  output logic [31:0]                 node_addr_o,
  input  logic                        node_rsp_valid_i,
  input  logic [31:0]                 node_w0_i,
  input  logic [31:0]                 node_w1_i,
  output logic                        valid_o,
  input  logic                        ready_i,
  output logic [$clog2(THREADS)-1:0]  thread_o,
  output logic                        level_o,
  output logic [1:0]                  kind_o,
  output logic [3:0]                  mask_o,
  output logic [4*(E+M+1)-1:0]        tn_o,
  output logic [4*(E+M+1)-1:0]        tf_o,
  output logic [31:0]                 node_o,
  output logic                        have_cur_o,
  output logic                        leaf_o,
  output logic                        list_o,
  output logic [31:0]                 leaf_first_o,
  output logic [31:0]                 leaf_count_o,
  output logic [3:0]                  leaf_mask_o,
  output logic [4*(E+M+1)-1:0]        leaf_tn_o,
  output logic [$clog2(DEPTH+1)-1:0]  sp_o,
  output logic                        lost_o,
  output logic                        restarted_o
);
  trav_unit #(.E(E), .M(M), .THREADS(THREADS), .DEPTH(DEPTH)) u_trav (.*);
endmodule
