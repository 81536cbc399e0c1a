// f24_pipe: STAGES pipeline registers (data and valid) with a clock enable, the delay line that
// gives every operator and unit its parameterized latency, and the pipeline cut between two segments
// of an operator (STAGES of 0, 1 or more registers there). STAGES = 0 is a wire. Synthesis with
// retiming (synth_* -retime) may move the registers into the combinational logic before them.
module f24_pipe #(
  parameter int W = 24,
  parameter int STAGES = 1
) (
  /* verilator lint_off UNUSEDSIGNAL */
  input  logic         clk_i,      // unused when STAGES = 0
  input  logic         rst_ni,
  input  logic         en_i,
  /* verilator lint_on UNUSEDSIGNAL */
  input  logic         valid_i,
  input  logic [W-1:0] data_i,
  output logic         valid_o,
  output logic [W-1:0] data_o
);
  if (STAGES == 0) begin : g_wire
    assign valid_o = valid_i;
    assign data_o = data_i;
  end else begin : g_regs
    logic [W-1:0] data_q [0:STAGES-1];
    logic [STAGES-1:0] valid_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        valid_q <= '0;
      end else if (en_i) begin
        valid_q[0] <= valid_i;
        for (int s = 1; s < STAGES; s++) valid_q[s] <= valid_q[s-1];
      end
    end
    always_ff @(posedge clk_i) if (en_i) data_q[0] <= data_i;
    // a register per stage (not a procedural loop, which Verilator leaves rolled and then cannot
    // take for a delayed array assignment beyond its unroll count of 64 stages)
    for (genvar s = 1; s < STAGES; s++) begin : g_stage
      always_ff @(posedge clk_i) if (en_i) data_q[s] <= data_q[s-1];
    end
    assign valid_o = valid_q[STAGES-1];
    assign data_o = data_q[STAGES-1];
  end
endmodule
