// read_ring: the ring of reads of cache_read, answered in request order: a read takes the slot
// at the tail (take_i), its lookups carry {off, slot, part} as id, and when its first lookup is
// made (look_i) it says whether a second line is read (two_i); each lookup's response (rsp_*_i:
// the line, the id) is rotated by the read's offset and written into the slot's words that lie in
// that line, and the oldest slot leaves (out_valid_o) when all its lookups are back.
// Its own module so that the logic after the cache's response (rotation, bookkeeping) is mapped
// with a short critical path of its own: the response comes late (the cache's round-robin choice,
// then its table's multiplexers), and a synthesis run per module stretches every path of a
// module up to that module's longest (docs/synth.md, LUT6 levels).
// The response is registered (r_*) before its rotation, at no cycle: the bookkeeping takes it at
// once (a flag per slot and part, its clock enable decoded from the id in one LUT), so its read
// leaves in the cycle after it as before, and the registered response's words go both into the
// slot and, when its read leaves in that cycle, straight to out_data_o (a 2-to-1 multiplexer per
// word after the slot's LUT RAM). So nothing but that decoding follows the cache's pick and table
// multiplexer in one cycle: cache_read's deepest path 9 -> 6 LUT6 levels (2026-11-30; the
// rotation and the per-slot comparisons were on it).
// The words: word j of the read is the line's word (off + j) mod LW, from the second line when
// off + j >= LW: a shift of the repeated line by off words in log2 LW stages of 2-to-1
// multiplexers, each on one bit of the offset (two stages a LUT6); each word of the ring is a
// column of OUTSTANDING entries in distributed RAM, written at the responding slot and read at the
// oldest.
// Latency: out_valid_o in the cycle after the last lookup's response (combinational from the
// slot's flags); throughput one read and one response per cycle.
// Resources: WORDS x OUTSTANDING x 32 bits of LUT RAM, OUTSTANDING x 5 flip-flops (gen, got, single),
// the registered response (32 LW + log2 LW + log2 OUTSTANDING + 2 flip-flops), WORDS x 32 shifts
// of log2 LW stages and as many 2-to-1 multiplexers.
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
  logic [OUTSTANDING-1:0] single;
  logic [1:0] gen [OUTSTANDING], got [OUTSTANDING];
  assign room_o = used != (SW + 1)'(OUTSTANDING);
  assign tail_o = tail;
  assign out_valid_o = used != 0 && got[head][0] == gen[head][0] && (got[head][1] == gen[head][1] || single[head]);

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

  // per slot and part a generation, flipped as a read that took that part leaves, and the generation
  // whose part is in: a read leaves when its parts' flags equal their generations (the second's only
  // if it reads two lines, which its first lookup says, before any of its responses). A response
  // writes its flag (the clock enable its slot and part decoded: one LUT from its id, which comes
  // late; no comparison per slot, no clearing on that path)
  logic [2*OUTSTANDING-1:0] back;
  assign back = rsp_valid_i ? (2 * OUTSTANDING)'(1) << {rsp_slot_i, rsp_part_i} : '0;
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      for (int s = 0; s < OUTSTANDING; s++) begin
        gen[s] <= 2'b00;
        got[s] <= 2'b11;
      end
    end else begin
      for (int s = 0; s < OUTSTANDING; s++) begin
        if (out_valid_o && head == SW'(s)) gen[s] <= gen[s] ^ {!single[s], 1'b1};
        if (back[2 * s]) got[s][0] <= gen[s][0];
        if (back[2 * s + 1]) got[s][1] <= gen[s][1];
      end
    end
  always_ff @(posedge clk_i)
    for (int s = 0; s < OUTSTANDING; s++)
      if (look_i && look_slot_i == SW'(s)) single[s] <= !two_i;

  // the response registered: rotated and written into its slot in the next cycle
  logic r_valid, r_part;
  logic [OW-1:0] r_off;
  logic [SW-1:0] r_slot;
  logic [32*LW-1:0] r_line;
  always_ff @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) r_valid <= 1'b0;
    else r_valid <= rsp_valid_i;
  always_ff @(posedge clk_i)
    if (rsp_valid_i) begin
      r_part <= rsp_part_i;
      r_off <= rsp_off_i;
      r_slot <= rsp_slot_i;
      r_line <= rsp_line_i;
    end
  // the registered response's read leaves now: its words from it, not from the slot (a response's
  // read leaves at the earliest in the cycle after it, so the slot is not taken again before its
  // words are written)
  logic r_head;
  assign r_head = r_valid && r_slot == head;

  logic [31:0] line_word [LW];
  for (genvar w = 0; w < LW; w++) begin : g_line
    assign line_word[w] = r_line[32*w +: 32];
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
          sh[b + 1][o] = r_off[b] && o + (1 << b) < (1 << OW) ? sh[b][o + (1 << b)] : sh[b][o];
          past[b + 1][o] = r_off[b] && o + (1 << b) < (1 << OW) ? past[b][o + (1 << b)] : past[b][o];
        end
    end
    logic mine;   // the registered response holds this word of its read
    assign mine = r_valid && past[OW][0] == r_part;
    logic [31:0] column [OUTSTANDING];
    always_ff @(posedge clk_i)
      if (mine) column[r_slot] <= sh[OW][0];
    assign out_data_o[32*j +: 32] = r_head && mine ? sh[OW][0] : column[head];
  end
endmodule
