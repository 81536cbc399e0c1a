// line_reader: a burst of n consecutive words read through a line port (not a paper unit: the
// RGS's reads of hls/units/rgs_surface.c `rgs_surface_at` and rgs.c `rgs_step`, a record at a time,
// as the paper's shading unit reads its cache's lines). The RGS's port onto the shading cache
// (cache_read, 16-byte lines) names a line by its first word's address and answers the whole line
// (LW words), so a burst of n words from word address a takes ceil((a mod LW + n) / LW) requests
// and responses instead of n: the instance word, the object's words 2..7, a shading record, a
// matrix, a material each in 1 to 5 lines. Word k of the burst (address a + k) is word
// (a mod LW + k) mod LW of response (a mod LW + k) / LW; only the burst's n words are written, so
// the buffer holds what a word-by-word burst left there.
// Protocol: start_i (only while done_o) takes addr_i and n_i (0 .. MAXW; 0: no request, done); req_valid_o /
// req_ready_i (the port takes the request) with the line's first word address req_addr_o;
// rsp_valid_i: the next of this reader's responses (in request order, always taken), rsp_line_i its
// words (word j at bits 32 j). done_o: every response of the burst is in, words_o (word k at bits
// 32 k) holds them from the cycle after the last one until the next burst's responses.
// Latency: the port's; throughput one line request and one response per cycle.
// Resources: MAXW x 32 bits of buffer, each word an LW-way multiplexer chosen by the burst's offset
// and an enable (the response's number equal to a constant of the offset, k below n); a 32-bit
// address counter, two line counters and the offset and length (about 50 flip-flops).
module line_reader #(
  parameter int MAXW = 16,  // the longest burst in words
  parameter int LW = 4,     // words per line (a power of two)
  localparam int NW = $clog2(MAXW + 1),
  localparam int OW = LW > 1 ? $clog2(LW) : 1,
  localparam int CW = $clog2((MAXW + 2 * LW - 2) / LW + 1)  // lines of a burst
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              start_i,
  input  logic [31:0]       addr_i,    // word address of the burst's first word
  input  logic [NW-1:0]     n_i,       // words
  output logic              req_valid_o,
  input  logic              req_ready_i,
  output logic [31:0]       req_addr_o,
  input  logic              rsp_valid_i,
  input  logic [32*LW-1:0]  rsp_line_i,
  output logic              done_o,
  output logic [32*MAXW-1:0] words_o
);
  if ((LW & (LW - 1)) != 0) begin : g_check
    $error("line_reader: LW a power of two (the offset is the address's low bits)");
  end
  logic [OW-1:0] off_q;
  logic [NW-1:0] n_q;
  logic [CW-1:0] req_left_q, rsp_left_q, rsp_no_q;
  logic [31:0] addr_q;
  logic [OW-1:0] off;
  assign off = LW > 1 ? OW'(addr_i) : '0;
  assign req_valid_o = req_left_q != '0;
  assign req_addr_o = addr_q;
  assign done_o = rsp_left_q == '0;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      req_left_q <= '0;
      rsp_left_q <= '0;
    end else if (start_i) begin  // no line for no word (a shading record of 0 words)
      req_left_q <= n_i == '0 ? '0 : CW'((32'(off) + 32'(n_i) + LW - 1) / LW);
      rsp_left_q <= n_i == '0 ? '0 : CW'((32'(off) + 32'(n_i) + LW - 1) / LW);
    end else begin
      if (req_valid_o && req_ready_i) req_left_q <= req_left_q - 1'b1;
      if (rsp_valid_i && !done_o) rsp_left_q <= rsp_left_q - 1'b1;
    end
  end

  always_ff @(posedge clk_i) begin
    if (start_i) begin
      addr_q <= addr_i & ~32'(LW - 1);
      off_q <= off;
      n_q <= n_i;
      rsp_no_q <= '0;
    end else begin
      if (req_valid_o && req_ready_i) addr_q <= addr_q + 32'(LW);
      if (rsp_valid_i && !done_o) rsp_no_q <= rsp_no_q + 1'b1;
    end
  end

  // word k of the burst: from response (off + k) / LW, its word (off + k) mod LW
  for (genvar k = 0; k < MAXW; k++) begin : g_word
    logic [31:0] pos;
    assign pos = 32'(off_q) + 32'(k);
    always_ff @(posedge clk_i)
      if (rsp_valid_i && !done_o && NW'(k) < n_q && CW'(pos / LW) == rsp_no_q)
        words_o[32*k +: 32] <= rsp_line_i[32*(pos % LW) +: 32];
  end
endmodule
