// tile_ctrl: the tile controller's block sequence for one pipe (paper section 3, the DynRTC's
// controller; tb/cycle/cycle_sim.c next_block with controller_refill). A frame (a region
// [x0, x1) x [y0, y1) of the image, already clipped to it, and the tile edge) is covered by tiles
// of tile x tile pixels in row-major order from the region's corner; each tile is handed out as
// its 2x2 blocks in row-major order, blocks whose top-left pixel lies outside the region
// skipped. One pipe receives every tile in order, so the sequence is a pure function of the
// region and the edge and is the cycle model's order of rgs_block_begin calls (--pipes 1). With
// several pipes the controller deals the same tile sequence out to the pipes' queues
// (TILE_QUEUE deep, topped up in pipe order at every epoch boundary), and which pipe gets which
// tile depends on how fast each drains its queue: that scheduling is not part of this module;
// each pipe would run this block sequence over the tiles it receives.
// Counters instead of the C's divisions: the next block is the next one in the row if it starts
// inside the tile and the region, else the first of the next row (likewise), else the first block
// of the next tile in the row of tiles, else of the next row of tiles, else the frame is done;
// the skipped blocks form the tail of a row and the tail rows of a tile, so no cycle is lost to
// them. Sums are 33 bits wide: the order is the C's for regions ending below 2^32 - tile (the C's
// tile count wraps beyond; validated images are at most 65536 pixels wide).
// Handshakes: frame_valid_i/frame_ready_o (ready while idle) takes the region and the edge (even,
// 2 .. 4096 as --tile); blk_valid_o/blk_ready_i one block per cycle; done_o pulses for one cycle
// after the frame's last block is taken (the cycle after the frame is taken for an empty region).
// Latency 1 cycle from the frame to its first block, throughput 1 block per cycle.
// Resources: 7 x 32-bit registers, 33-bit adders and comparators, 2 x 13-bit offset counters;
// Yosys 0.23: synth_xilinx 409 LUTs, 265 FFs; synth_ice40 925 LUT4, 263 FFs.
module tile_ctrl (
  input  logic        clk_i,
  input  logic        rst_ni,
  input  logic        frame_valid_i,
  output logic        frame_ready_o,
  input  logic [31:0] x0_i,
  input  logic [31:0] y0_i,
  input  logic [31:0] x1_i,
  input  logic [31:0] y1_i,
  input  logic [12:0] tile_i,
  output logic        blk_valid_o,
  input  logic        blk_ready_i,
  output logic [31:0] blk_x_o,
  output logic [31:0] blk_y_o,
  output logic        done_o
);
  logic busy_q, done_q;
  logic [31:0] x0_q, x1_q, y1_q, tx_q, ty_q, x_q, y_q;   // region, tile origin, block
  logic [12:0] tile_q, bx_q, by_q;                      // edge, block offset in the tile
  logic next_col, next_row, next_tile, next_tile_row;

  assign frame_ready_o = !busy_q;
  assign blk_valid_o = busy_q;
  assign blk_x_o = x_q;
  assign blk_y_o = y_q;
  assign done_o = done_q;

  always_comb begin
    next_col = 14'(bx_q) + 14'd2 < 14'(tile_q) && 33'(x_q) + 33'd2 < 33'(x1_q);
    next_row = 14'(by_q) + 14'd2 < 14'(tile_q) && 33'(y_q) + 33'd2 < 33'(y1_q);
    next_tile = 33'(tx_q) + 33'(tile_q) < 33'(x1_q);
    next_tile_row = 33'(ty_q) + 33'(tile_q) < 33'(y1_q);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      busy_q <= 1'b0;
      done_q <= 1'b0;
    end else begin
      done_q <= 1'b0;
      if (frame_valid_i && frame_ready_o) begin
        busy_q <= x0_i < x1_i && y0_i < y1_i;
        done_q <= !(x0_i < x1_i && y0_i < y1_i);
      end else if (busy_q && blk_ready_i && !next_col && !next_row && !next_tile && !next_tile_row) begin
        busy_q <= 1'b0;
        done_q <= 1'b1;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (frame_valid_i && frame_ready_o) begin
      x0_q <= x0_i;
      x1_q <= x1_i;
      y1_q <= y1_i;
      tile_q <= tile_i;
      tx_q <= x0_i;
      ty_q <= y0_i;
      x_q <= x0_i;
      y_q <= y0_i;
      bx_q <= '0;
      by_q <= '0;
    end else if (busy_q && blk_ready_i) begin
      if (next_col) begin
        x_q <= x_q + 32'd2;
        bx_q <= bx_q + 13'd2;
      end else if (next_row) begin
        x_q <= tx_q;
        y_q <= y_q + 32'd2;
        bx_q <= '0;
        by_q <= by_q + 13'd2;
      end else if (next_tile) begin
        tx_q <= tx_q + 32'(tile_q);
        x_q <= tx_q + 32'(tile_q);
        y_q <= ty_q;
        bx_q <= '0;
        by_q <= '0;
      end else if (next_tile_row) begin
        tx_q <= x0_q;
        ty_q <= ty_q + 32'(tile_q);
        x_q <= x0_q;
        y_q <= ty_q + 32'(tile_q);
        bx_q <= '0;
        by_q <= '0;
      end
    end
  end
endmodule
