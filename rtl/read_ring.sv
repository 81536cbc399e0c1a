// read_ring: the ring of reads of cache_read, answered in request order: a read takes the slot
// at the tail (take_i), its lookups carry {off, slot, part} as id, and when its first lookup is
// made (look_i) it says whether a second line is read (two_i); each lookup's response (rsp_*_i:
// the line, the id) is rotated by the read's offset and written into the slot's words that lie in
// that line, and the oldest slot leaves (out_valid_o) when all its lookups are back.
// Its own module so that the logic after the cache's response (rotation, bookkeeping) is mapped
// with a short critical path of its own: the response comes late (the cache's round-robin choice,
// then its table's multiplexers), and a synthesis run per module stretches every path of a
// module up to that module's longest (docs/synth.md, LUT6 levels).
// The words: word j of the read is the line's word (off + j) mod LW, from the second line when
// off + j >= LW: a shift of the repeated line by off words in log2 LW stages of 2-to-1
// multiplexers, each on one bit of the offset (two stages a LUT6); each word of the ring is a
// column of OUTSTANDING entries in distributed RAM, written at the responding slot and read at the
// oldest.
// Latency: out_valid_o in the cycle after the last lookup's response (combinational from the
// slot's flags); throughput one read and one response per cycle.
// Resources: WORDS x OUTSTANDING x 32 bits of LUT RAM, OUTSTANDING x 4 flip-flops (need, got),
// WORDS x 32 shifts of log2 LW stages.
module read_ring #(
  parameter int LW = 2,            // words per line
  parameter int WORDS = 2,         // words per read: 1 .. LW
  parameter int OUTSTANDING = 16,  // reads in flight (a power of two)
  localparam int SW = $clog2(OUTSTANDING),
  localparam int OW = LW > 1 ? $clog2(LW) : 1
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  output logic                 room_o,       // a read can be taken
  output logic [SW-1:0]        tail_o,       // the slot of the next read taken
  input  logic                 take_i,
  input  logic                 look_i,       // a read's first lookup is made
  input  logic [SW-1:0]        look_slot_i,
  input  logic                 two_i,        // ... and it reads a second line
  input  logic                 rsp_valid_i,  // a lookup's response
  input  logic [OW-1:0]        rsp_off_i,    // its id: the read's offset in the first line,
  input  logic [SW-1:0]        rsp_slot_i,   // its slot,
  input  logic                 rsp_part_i,   // first (0) or second (1) line
  input  logic [32*LW-1:0]     rsp_line_i,
  output logic                 out_valid_o,  // the oldest read, in request order; always taken
  output logic [32*WORDS-1:0]  out_data_o    // word j at bits 32 j
);
  logic [SW-1:0] head, tail;
  logic [SW:0] used;
  logic [1:0] need [OUTSTANDING], got [OUTSTANDING];
  assign room_o = used != (SW + 1)'(OUTSTANDING);
  assign tail_o = tail;
  assign out_valid_o = used != 0 && got[head] == need[head];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head <= '0;
      tail <= '0;
      used <= '0;
    end else begin
      if (take_i) tail <= tail + 1'b1;
      if (out_valid_o) head <= head + 1'b1;
      used <= used + (SW + 1)'(take_i) - (SW + 1)'(out_valid_o);
    end
  end

  // a read's lookups are known when its first is made: until then it waits for both parts
  always_ff @(posedge clk_i)
    for (int s = 0; s < OUTSTANDING; s++) begin
      if (look_i && look_slot_i == SW'(s)) need[s] <= two_i ? 2'b11 : 2'b01;
      else if (take_i && tail == SW'(s)) need[s] <= 2'b11;
      if (take_i && tail == SW'(s)) got[s] <= 2'b00;
      else if (rsp_valid_i && rsp_slot_i == SW'(s)) got[s][rsp_part_i] <= 1'b1;
    end

  logic [31:0] line_word [LW];
  for (genvar w = 0; w < LW; w++) begin : g_line
    assign line_word[w] = rsp_line_i[32*w +: 32];
  end
  for (genvar j = 0; j < WORDS; j++) begin : g_word
    logic [31:0] sh [OW + 1][1 << OW];
    logic [(1 << OW)-1:0] past [OW + 1];   // the word is from the second line
    always_comb begin
      for (int o = 0; o < (1 << OW); o++) begin
        sh[0][o] = line_word[(o + j) % LW];
        past[0][o] = o + j >= LW;
      end
      for (int b = 0; b < OW; b++)
        for (int o = 0; o < (1 << OW); o++) begin
          // stage b shifts by 2^b words: entry o takes entry o + 2^b (the entries beyond the
          // offsets that can be set are never selected)
          sh[b + 1][o] = rsp_off_i[b] && o + (1 << b) < (1 << OW) ? sh[b][o + (1 << b)] : sh[b][o];
          past[b + 1][o] = rsp_off_i[b] && o + (1 << b) < (1 << OW) ? past[b][o + (1 << b)] : past[b][o];
        end
    end
    logic [31:0] column [OUTSTANDING];
    always_ff @(posedge clk_i)
      if (rsp_valid_i && past[OW][0] == rsp_part_i) column[rsp_slot_i] <= sh[OW][0];
    assign out_data_o[32*j +: 32] = column[head];
  end
endmodule
