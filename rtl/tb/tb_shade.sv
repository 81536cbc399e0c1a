// tb_shade: test wrapper (not synthesized) around the RGS's shading datapath: the decoding of the
// compact shading record's vertex normals (shade_rec_decode). The C++ bench (tb_shade.cpp) drives
// valid_i and ready_i with gaps and back pressure and checks every result against the C model.
module tb_shade #(
  parameter int E = 7,
  parameter int M = 16
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 n_valid_i,
  output logic                 n_ready_o,
  input  logic [5:0]           n_tid_i,
  input  logic [41:0]          n_code_i,
  output logic                 n_valid_o,
  input  logic                 n_ready_i,
  output logic [5:0]           n_tid_o,
  output logic [3*(E+M+1)-1:0] n_o
);
  shade_rec_decode #(.E(E), .M(M), .TID_BITS(6)) u_dec (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(n_valid_i),
    .ready_o(n_ready_o), .tid_i(n_tid_i), .code_i(n_code_i), .valid_o(n_valid_o), .ready_i(n_ready_i),
    .tid_o(n_tid_o), .n_o(n_o));
endmodule
