// tb_fifo: test wrapper (not synthesized) around sync_fifo (rtl/sync_fifo.sv): at each of the
// depths 2, 4 and 64 one queue of each storage form (BLOCK_RAM = 0: LUT RAM read combinationally;
// 1: block RAM read ahead into its registered output, with the bypass), both driven by the same
// inputs; the C++ bench (tb_fifo.cpp) checks every output of both every cycle against a deque.
// Word k (32 bits) of the data ports and bit k of the others belong to depth k.
module tb_fifo #(
  parameter int E = 7,  // unused: the Makefile passes the fp24 format to every bench
  parameter int M = 16
) (
  input  logic          clk_i,
  input  logic          rst_ni,
  input  logic [2:0]    valid_i,
  output logic [2:0]    lut_ready_o,
  output logic [2:0]    bram_ready_o,
  input  logic [95:0]   data_i,
  output logic [2:0]    lut_valid_o,
  output logic [2:0]    bram_valid_o,
  input  logic [2:0]    ready_i,
  output logic [95:0]   lut_data_o,
  output logic [95:0]   bram_data_o
);
  if (E + M < 0) begin : g_unused
  end
  for (genvar k = 0; k < 3; k++) begin : g_depth
    localparam int D = k == 0 ? 2 : k == 1 ? 4 : 64;
    sync_fifo #(.W(32), .DEPTH(D), .BLOCK_RAM(1'b0)) u_lut (.clk_i(clk_i), .rst_ni(rst_ni),
      .valid_i(valid_i[k]), .ready_o(lut_ready_o[k]), .data_i(data_i[32*k +: 32]), .valid_o(lut_valid_o[k]),
      .ready_i(ready_i[k]), .data_o(lut_data_o[32*k +: 32]));
    sync_fifo #(.W(32), .DEPTH(D), .BLOCK_RAM(1'b1)) u_bram (.clk_i(clk_i), .rst_ni(rst_ni),
      .valid_i(valid_i[k]), .ready_o(bram_ready_o[k]), .data_i(data_i[32*k +: 32]), .valid_o(bram_valid_o[k]),
      .ready_i(ready_i[k]), .data_o(bram_data_o[32*k +: 32]));
  end
endmodule
