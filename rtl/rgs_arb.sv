// rgs_arb: N requesters onto one pipelined unit of the RGS (rgs_units: the block controllers'
// operands into the shared rgs_raygen, rgs_light, rgs_light_colour, rgs_add_light, rgs_accum; a
// surface unit's controllers into it, with HOLD; the surface units into the shared rgs_frame,
// rgs_normal and tex_coords). Not a paper unit and no C function: the C steps one block at a time, so there is
// nothing to arbitrate; the pick only decides which controller's operand enters the unit in a cycle,
// never what it computes (each operand carries its controller's index as the unit's thread id).
// Round robin (rr_pick on the mask of the requesters after the last one taken), so a controller
// streaming its 4 rays through a unit alternates with the others instead of holding it.
// Latency 1: the pick and the operand are registered (valid_o, index_o, data_o come from
// flip-flops), so the pick's levels (request to operand: 5 LUT6 at N = 8) do not add to the unit's
// first stage (an 8-level unit behind a combinational arbiter made 13; rtl/README.md "LUT6
// levels"); one operand per cycle: the register takes the next pick while the unit takes the one
// it holds (ready_i).
// Handshake: req_i / ack_o per requester (ack: its operand was taken into the register this
// cycle), valid_o / ready_i to the unit. HOLD: the next pick is the first requester at or after the one taken last, so a
// controller keeps the unit while it offers operands (its packet's 4 rays into a surface unit,
// which takes a hit per 40 to 80 cycles: one controller done early rather than all late).
// Resources: rr_pick (2 LUT6 levels), an N-to-1 multiplexer of DW bits on its index
// (Yosys synth_xilinx at N = 8: 564 LUT6 for DW = 178, 1374 for 448), N flip-flops of the pointer,
// DW + log2 N + 1 of the output register.
module rgs_arb #(
  parameter int N = 8,
  parameter int DW = 32,
  parameter bit HOLD = 1'b0,         // keep the grant on the requester taken last while it requests
  localparam int NW = N > 1 ? $clog2(N) : 1
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic [N-1:0]    req_i,
  input  logic [N*DW-1:0] data_i,    // requester k's operand at bits DW k
  output logic [N-1:0]    ack_o,
  output logic            valid_o,
  input  logic            ready_i,
  output logic [NW-1:0]   index_o,   // the unit's thread id: whose operand it is
  output logic [DW-1:0]   data_o
);
  logic [N-1:0] after_q, after, grant;
  logic any, take;
  logic [NW-1:0] index;
  rr_pick #(.N(N)) u_pick (.req_i(req_i), .after_i(after_q), .any_o(any), .grant_o(grant), .index_o(index),
    .after_o(after));
  assign take = any && (!valid_o || ready_i);  // the register is empty or hands its operand on
  assign ack_o = take ? grant : '0;
  // an array read on the index: an N-to-1 multiplexer (about 3 LUT6 a bit at N = 8); the part-select
  // data_i[DW*index +: DW] mapped to a shifter of up to 34 LUT6 a bit
  logic [DW-1:0] ops [N];
  for (genvar k = 0; k < N; k++) begin : g_ops
    assign ops[k] = data_i[DW*k +: DW];
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      after_q <= '0;
      valid_o <= 1'b0;
    end else begin
      if (take) after_q <= HOLD ? after | grant : after;  // at or after it: held
      if (!valid_o || ready_i) valid_o <= any;
    end
  end
  always_ff @(posedge clk_i) begin
    if (take) begin
      index_o <= index;
      data_o <= ops[index];
    end
  end
endmodule
