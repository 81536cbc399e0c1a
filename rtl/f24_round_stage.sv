// f24_round_stage: the last segment of the pipelined adder, multiplier, divider and square root:
// the shared rounder (f24_round_pack) on the unrounded result, or the special result (NaN, Inf,
// zero) the operator decided in its first segment, then the operator's remaining STAGES registers.
// Latency STAGES (0: combinational), one result per cycle; resources: one f24_round_pack, a W-bit
// multiplexer and STAGES x (W + 1) flip-flops.
module f24_round_stage #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int STAGES = 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                en_i,
  input  logic                valid_i,
  input  logic                spec_i,      // the result is spec_res_i, not the rounded one
  input  logic [E+M:0]        spec_res_i,
  input  logic                sign_i,
  input  logic signed [E+2:0] exp_i,
  input  logic [30:0]         sig_i,       // f24_round_pack's unrounded significand
  output logic                valid_o,
  output logic [E+M:0]        res_o
);
  logic [E+M:0] rounded;
  f24_round_pack #(.E(E), .M(M)) u_round (.sign_i(sign_i), .exp_i(exp_i), .sig_i(sig_i), .res_o(rounded));
  f24_pipe #(.W(E + M + 1), .STAGES(STAGES)) u_out (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(en_i), .valid_i(valid_i), .data_i(spec_i ? spec_res_i : rounded),
    .valid_o(valid_o), .data_o(res_o)
  );
endmodule
