// rgs_surface: the surface the RGS shades at a hit (paper sections 2.2 and 3, Figure 2 path g:
// the shading's reads and the surface's geometry and colours; hls/units/rgs_surface.c
// `rgs_surface_at`), bit for bit as the C, in two stages that work on consecutive surfaces at once
// (a front reading the next hits' records while the back shades the one before; the frame and the
// conversions beside the back, see Latency):
//   front   the reads, in two stages that work on consecutive hits at once (the first's reads go
//           before the second's: they start the normals' chains):
//           first (f_): the instance's object index (word 12), the object descriptor's words
//           2..7 (triangle and shading record addresses, flags), the triangle's shading record
//           (shade_rec_words(flags) words, up to 19); with vertex normals the record's 3 codes
//           and u, v go out to `rgs_normal` (nrm_ ports: outside, rgs_units shares one among its
//           surface units) from the second stage's registers, from the cycle after the hit moves
//           there until rgs_units' arbiter takes them (decoded,
//           interpolated as `rgs_lerp_normal`, the squared length's zero test as the C's
//           `f24_is_zero(rgs_dot3(n, n))`: a stream, the next hits' behind);
//           second (h_): the instance's words 0..11 (the world-to-object 3x3, which only the frame
//           needs), without vertex normals the geometric normal (values 8..10 of the triangle
//           record, F24_RECORD_SPAN(8, 3) words), the material's 16 words (address: the object's
//           material or the record tail's), into its registers, which the back takes when idle;
//           each burst's address comes from the words before, so a stage's go one after another
//   back    normal: with vertex normals its hit's from `rgs_normal` (in order): if its squared
//           length is zero, the geometric normal read here; without vertex normals the front's
//   frame   d^, n^ facing the ray, t_hat, P, entering (`rgs_frame`, outside: rgs_units shares one
//           among its surface units): the geometry issued on the fr_ ports, its result (in the
//           order of issue) joins the surface at the output while the next steps and surfaces go on
//   material  unlit, the highlight exponent k (shader word 0, bits 26..29), the index of
//           refraction and the kd, kr, kt, ks fields (words 13..15) for the accumulation
//   colours  9 conversions to Q12 on one `q12_of`, one a cycle from the back's taking the hit (u,
//           v, the base and emissive factors, metallic); vertex colours (`modulate_colours`:
//           weights q(u), q(v), 1 - both, the bytes widened, the C's uint32 arithmetic); per texture
//           (base colour, then emissive) if its index is below the header's texture count and the
//           object has texture coordinates: s, t interpolated (`rgs_lerp`), the entry's 4 words
//           read, the sample's texel coordinates from `tex_coords` (tx_ ports: outside, rgs_units
//           shares one among its surface units; asked from registers), `tex_fetch` reading its 4
//           texels through the same read port and blending them (the two: the C's
//           `rgs_sample_bilinear`), the colour times the sample (`q_mul`); the tint (1 - m) + m
//           base with m clamped to one (`q_mul`, `q_add`)
// An inactive ray or a miss gives the invalid surface (all zero) without a read. T_R is wiring
// (d^, n^ and the ray's origin, which the caller keeps). The header's words the C reads as
// constants (the instance, object, material and texture regions' starts, the texture count) are
// inputs: the block control loads them once per frame.
// Reads: a line port (the shading cache's 16-byte lines, LW = 4 words): valid/ready request of the
// line's first word address, the response is the whole line, in order (valid, no back pressure:
// the unit takes one every cycle). Each of the three readers (the front's two stages, the back) is
// a `line_reader`: a burst of n words from word address a takes ceil((a mod LW + n) / LW) line
// requests, the words it needs taken from each line (a flat hit's instance word, object words 2..7
// and record about 1 + 2 + 3 lines instead of 1 + 6 + 10 words). tex_fetch's texel reads are
// words: its request's line goes out, the word's offset in it waits in the source FIFO beside the
// stage and picks the word from the response. The back's requests go first (its surface is the
// older one), then the front's first stage's, then its second's; a FIFO of SRC_DEPTH x (2 + 2)
// bits notes each request's stage (and a texel's offset) for its response.
// A surface's words are the C's (op reads), in the C's order but for a geometric normal that the
// back reads after the material (vertex normals interpolated to zero length); the two stages'
// reads interleave; a line also brings the words beside the burst's, which are not kept.
// Latency: about 20 + the reads up to the record (3 bursts of 1, 2 and 1 to 5 lines, each waiting
// for the one before: its address comes from the words of the one before) + `rgs_normal` (1 in the
// second stage's registers + 1 in rgs_units' arbiter + 87 + 1 in its queue here, only with vertex
// normals; without: the geometric normal's and the material's reads) + the conversions' tail (about 20 from the back's taking it) + per texture
// lerp 24 + entry 4 + the sample: 1 in the request's register, 1 in rgs_units' arbiter, tex_coords
// 42, tex_fetch 1 + 4 requests + the memory + 1) + the frame (118, + 1 behind rgs_units' arbiter,
// + the cycles it waits there for other surface units' operands or stalls on their results),
// which the next surfaces' steps overlap.
// Throughput: a surface per its front's reads (3 dependent bursts of lines: about 15 to 25 cycles
// for a flat hit with a memory answering in 1 to 4 cycles) while the back's part is shorter (about 10 cycles untextured once
// its normal is there); the second stage holds a hit until the back takes it, the first one
// until the second is free, so with vertex normals a hit's normal chain overlaps the next hit's
// reads and the record reads of the one after (whose chain starts as the second stage takes it);
// up to SLOTS surfaces
// between the frame's issue and the output; a miss or an inactive ray passes both stages in a
// cycle each. Results leave in
// the order the surfaces came in, with their thread id.
// Resources: one each of `rgs_lerp` (texture coordinates), `q12_of`, `tex_fetch` (the frame, the
// normals and the texture samples' coordinates are outside); a queue of NRM_SLOTS = 2 normals (3 W + 1 bits); 6 `q12_mul` (a texture's modulation, the
// tint); per stage (the front's two
// and the back) the ray and hit (about 0.4 Kbit) and the record (19 words: the first stage's in
// its reader's buffer); the back a 16-word buffer (the material's) and the matrix (9 W bits), the
// front's second stage the matrix; three `line_reader`s (their buffers: the first stage's 19 words,
// the object's words and then the record, the second stage's 16, the back's 4: a geometric normal
// or a texture entry; each buffer word a 4-way multiplexer of the line); the output queue (SLOTS x
// (TID_BITS + W + 234) bits: the fields of the surfaces in the frame); the request FIFO (SRC_DEPTH
// x 4 bits); a 608-bit funnel shifter for the record's tail fields.
module rgs_surface #(
  parameter int E = 7,
  parameter int M = 16,
  parameter int TID_BITS = 6,
  parameter int MUL_STAGES = 4,
  parameter int ADD_STAGES = 6,
  parameter int TOI_STAGES = 2,
  parameter int SLOTS = 4,        // surfaces between the frame's issue and the output (a power of 2)
  parameter int SRC_DEPTH = 32,   // reads under way (a power of 2; more wait)
  parameter int LW = 4            // words per line of the read port (the shading cache's 16 bytes)
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  // the header's words (docs/memory-image.md): region starts and the texture count
  input  logic [31:0]          inst_base_i,
  input  logic [31:0]          obj_base_i,
  input  logic [31:0]          mat_base_i,
  input  logic [31:0]          tex_base_i,
  input  logic [31:0]          n_tex_i,
  // a ray and its hit (trace_core's result fields)
  input  logic                 valid_i,
  output logic                 ready_o,
  input  logic [TID_BITS-1:0]  tid_i,
  input  logic                 active_i,
  input  logic [3*(E+M+1)-1:0] o_i,
  input  logic [3*(E+M+1)-1:0] d_i,
  input  logic [31:0]          inst_i,
  input  logic [31:0]          tri_i,
  input  logic [E+M:0]         t_i,
  input  logic [E+M:0]         u_i,
  input  logic [E+M:0]         v_i,
  input  logic [E+M:0]         cos_n_i,
  // line read port: a request names a line by its first word's address, the response is its LW words
  output logic                 mem_req_valid_o,
  input  logic                 mem_req_ready_i,
  output logic [31:0]          mem_addr_o,
  input  logic                 mem_rsp_valid_i,
  input  logic [32*LW-1:0]     mem_rdata_i,
  // the frame's operand (rgs_frame's inputs but the thread id; fr_ready_i: taken this cycle) and
  // its results for this unit, in the order of its operands (fr_ready_o: taken this cycle)
  output logic                 fr_valid_o,
  input  logic                 fr_ready_i,
  output logic [3*(E+M+1)-1:0] fr_o_o,
  output logic [3*(E+M+1)-1:0] fr_d_o,
  output logic [E+M:0]         fr_t_o,
  output logic [E+M:0]         fr_cos_n_o,
  output logic [3*(E+M+1)-1:0] fr_n_o,
  output logic [9*(E+M+1)-1:0] fr_w2o_o,
  input  logic                 fr_valid_i,
  output logic                 fr_ready_o,
  input  logic [3*(E+M+1)-1:0] fr_d_i,
  input  logic [3*(E+M+1)-1:0] fr_n_i,
  input  logic                 fr_entering_i,
  input  logic [E+M:0]         fr_t_hat_i,
  input  logic [3*(E+M+1)-1:0] fr_p_i,
  // a hit's vertex normal (rgs_normal's inputs but the thread id; nrm_ready_i: taken this cycle)
  // and its results for this unit, in the order of its hits (into a queue of NRM_SLOTS, which
  // nrm_valid_o never overfills)
  output logic                 nrm_valid_o,
  input  logic                 nrm_ready_i,
  output logic [125:0]         nrm_codes_o,
  output logic [E+M:0]         nrm_u_o,
  output logic [E+M:0]         nrm_v_o,
  input  logic                 nrm_valid_i,
  input  logic [3*(E+M+1)-1:0] nrm_n_i,
  input  logic                 nrm_zero_i,
  // a texture sample's coordinates (tex_coords' inputs but the thread id; tx_ready_i: taken this
  // cycle) and its result for this unit (one sample under way at a time: tex_fetch takes it as it comes)
  output logic                 tx_valid_o,
  input  logic                 tx_ready_i,
  output logic [E+M:0]         tx_s_o,
  output logic [E+M:0]         tx_t_o,
  output logic [31:0]          tx_width_o,
  output logic [31:0]          tx_height_o,
  output logic [31:0]          tx_addr_o,
  input  logic                 tx_valid_i,
  input  logic [31:0]          tx_row0_i,
  input  logic [31:0]          tx_row1_i,
  input  logic [31:0]          tx_x0_i,
  input  logic [31:0]          tx_x1_i,
  input  logic [8:0]           tx_fx_i,
  input  logic [8:0]           tx_fy_i,
  // the surface (hls/units/rgs.h `surface`, and the material's fields the accumulation needs)
  output logic                 valid_o,
  input  logic                 ready_i,
  output logic [TID_BITS-1:0]  tid_o,
  output logic                 sf_valid_o,
  output logic [3*(E+M+1)-1:0] p_o,
  output logic [3*(E+M+1)-1:0] d_o,
  output logic [3*(E+M+1)-1:0] n_o,
  output logic [E+M:0]         t_hat_o,
  output logic                 entering_o,
  output logic [31:0]          mat_o,
  output logic                 unlit_o,
  output logic [3:0]           k_o,
  output logic [E+M:0]         eta_o,       // material word 13, the shader fields of words 14, 15
  output logic [12:0]          kd_o,
  output logic [12:0]          kr_o,
  output logic [12:0]          kt_o,
  output logic [12:0]          ks_o,
  output logic [3*16-1:0]      base_o,      // Q12 R, G, B from the low half-word up
  output logic [3*16-1:0]      emission_o,
  output logic [3*16-1:0]      tint_o
);
  localparam int W = 1 + E + M;
  localparam int V = 3 * W;
  // hls/units/f24_record.h: the triangle record (12 values, 3 x 9-bit vertex low parts, 3 edge
  // flags) and the instance record (whole triangle records holding 17 words)
  localparam int TRI_WORDS = (12 * W + 27 + 3 + 31) / 32;
  localparam int INST_WORDS = TRI_WORDS * ((17 + TRI_WORDS - 1) / TRI_WORDS);
  localparam int GN_WORD = 8 * W / 32;                         // the geometric normal: values 8..10
  localparam int GN_SPAN = (11 * W - 1) / 32 - GN_WORD + 1;
  localparam int GN_SHIFT = 8 * W % 32;
  localparam int REC_MAX = 19;                                  // SHADE_MAX_WORDS
  localparam int BUF = 16;
  localparam logic [31:0] NO_HIT = 32'hFFFFFFFF;
  localparam logic [15:0] ONE = 16'd4096;

  // the back's states (the order tb_rgs_ctrl's histogram names them; S_INST, S_OBJ, S_REC and S_MAT
  // are the front's now, S_LERPN and S_DOT rgs_normal's: unused here)
  typedef enum logic [4:0] {
    S_IDLE, S_INST, S_OBJ, S_REC, S_NORM, S_LERPN, S_DOT, S_GN, S_FRAME, S_MAT, S_Q, S_TEX, S_TLERP, S_TENTRY,
    S_TSAMPLE, S_TINT
  } state_t;
  state_t st;
  typedef enum logic [2:0] { F_IDLE, F_INST, F_OBJ, F_REC, F_MISS } fstate_t;
  typedef enum logic [2:0] { H_EMPTY, H_W2O, H_GN, H_MAT, H_FULL } hstate_t;
  hstate_t h_st;
  fstate_t f_st;

  // ---- the transaction's inputs ----
  logic [TID_BITS-1:0] tid_q;
  logic [V-1:0] o_q, d_q;
  logic [31:0] tri_q;
  logic [W-1:0] t_q, u_q, v_q, cos_q;

  // ---- the front: a hit's reads, the instance's 13 words, the object's 6, the record, the
  // geometric normal if the object has no vertex normals, the material's 16, into its own
  // registers, while the back works on the surface before; the back takes them (f_take) ----
  logic [TID_BITS-1:0] f_tid;
  logic f_hit;
  logic [V-1:0] f_o, f_d;
  logic [31:0] f_tri, f_tri_base, f_flags, f_inst_addr;
  logic [W-1:0] f_t, f_u, f_v, f_cos;
  // the first stage's reads: one buffer for the instance word, the object's 6 words and the record
  logic [31:0] f_buf [REC_MAX], f_rd_at;
  logic [4:0] f_rd_n;
  logic f_start, f_done, f_take;
  // the front's second stage (h_): a hit whose record is read (its normal's chain started) reads
  // its matrix, geometric normal and material while the first stage (f_) reads the next hit's
  // instance, object and record, so the next chains start without waiting for these reads
  logic [TID_BITS-1:0] h_tid;
  logic h_hit, h_load;
  logic [V-1:0] h_o, h_d, h_n;
  logic [31:0] h_tri, h_tri_base, h_flags, h_mat_addr;
  logic [W-1:0] h_t, h_u, h_v, h_cos;
  logic [V*3-1:0] h_w2o;
  logic [31:0] h_buf [BUF], h_rec [REC_MAX], h_rd_at;
  logic [4:0] h_rd_n;
  logic h_start, h_done;
  // the first stage's hit (with its record, its normal's chain starting) or miss moves on
  assign h_load = h_st == H_EMPTY && (f_st == F_MISS || f_st == F_REC && f_done);

  // ---- the back's reads (a zero interpolated normal's geometric normal, a texture's entry) ----
  localparam int BBUF = GN_SPAN > 4 ? GN_SPAN : 4;  // the back's bursts: a normal or a texture entry
  localparam int BNW = $clog2(BBUF + 1);
  logic [31:0] buf_q [BUF], rec_q [REC_MAX], b_buf [BBUF], b_rd_at;
  logic [BNW-1:0] b_rd_n;
  logic b_start, burst_done, tex_port;
  logic tex_req_valid;
  /* verilator lint_off UNUSEDSIGNAL */
  logic tex_rsp_ready;  // always set: the sample's result is taken at once, so the texels are too
  /* verilator lint_on UNUSEDSIGNAL */
  logic [31:0] tex_req_addr;
  assign tex_port = st == S_TSAMPLE;

  // ---- the line port, shared: the back's requests first (its surface is the older one); the
  // responses come in request order, so a FIFO of each request's side (2: the back) routes them,
  // with a texel read's word in its line (tex_fetch reads words) ----
  localparam int OW = LW > 1 ? $clog2(LW) : 1;
  logic b_req, f_req, h_req, src_room, rsp_b, rsp_f, rsp_h, port_go, b_rd_req;
  logic [31:0] b_rd_addr, f_rd_addr, h_rd_addr, tex_word;
  logic [1:0] src_head;  // 2: the back, 1: the front's first stage, 0: its second
  logic [OW-1:0] tex_off, tex_off_head;
  assign b_req = tex_port ? tex_req_valid : b_rd_req;
  assign mem_req_valid_o = (b_req || f_req || h_req) && src_room;
  assign mem_addr_o = b_req ? (tex_port ? tex_req_addr & ~32'(LW - 1) : b_rd_addr) : f_req ? f_rd_addr : h_rd_addr;
  assign port_go = src_room && mem_req_ready_i;  // a request offered now is taken
  assign tex_off = OW'(tex_req_addr & 32'(LW - 1));
  /* verilator lint_off PINCONNECTEMPTY */
  sync_fifo #(.W(2 + OW), .DEPTH(SRC_DEPTH)) u_src (
    .clk_i, .rst_ni, .valid_i(mem_req_valid_o && mem_req_ready_i), .ready_o(src_room),
    .data_i({tex_off, b_req ? 2'd2 : f_req ? 2'd1 : 2'd0}),
    .valid_o(), .ready_i(mem_rsp_valid_i), .data_o({tex_off_head, src_head})
  );
  /* verilator lint_on PINCONNECTEMPTY */
  assign rsp_b = mem_rsp_valid_i && src_head == 2'd2;
  assign rsp_f = mem_rsp_valid_i && src_head == 2'd1;
  assign rsp_h = mem_rsp_valid_i && src_head == 2'd0;
  assign tex_word = mem_rdata_i[32*tex_off_head +: 32];

  // the three burst readers: the back's (not while the texture sample owns the port), the front's
  // first stage's, its second's, in that priority on the port
  logic [32*BBUF-1:0] b_words;
  logic [32*REC_MAX-1:0] f_words;
  logic [32*BUF-1:0] h_words;
  line_reader #(.MAXW(BBUF), .LW(LW)) u_b_rd (
    .clk_i, .rst_ni, .start_i(b_start), .addr_i(b_rd_at), .n_i(b_rd_n), .req_valid_o(b_rd_req),
    .req_ready_i(!tex_port && port_go), .req_addr_o(b_rd_addr), .rsp_valid_i(!tex_port && rsp_b), .rsp_line_i(mem_rdata_i),
    .done_o(burst_done), .words_o(b_words));
  line_reader #(.MAXW(REC_MAX), .LW(LW)) u_f_rd (
    .clk_i, .rst_ni, .start_i(f_start), .addr_i(f_rd_at), .n_i(f_rd_n), .req_valid_o(f_req),
    .req_ready_i(!b_req && port_go), .req_addr_o(f_rd_addr), .rsp_valid_i(rsp_f), .rsp_line_i(mem_rdata_i),
    .done_o(f_done), .words_o(f_words));
  line_reader #(.MAXW(BUF), .LW(LW)) u_h_rd (
    .clk_i, .rst_ni, .start_i(h_start), .addr_i(h_rd_at), .n_i(h_rd_n), .req_valid_o(h_req),
    .req_ready_i(!b_req && !f_req && port_go), .req_addr_o(h_rd_addr), .rsp_valid_i(rsp_h), .rsp_line_i(mem_rdata_i),
    .done_o(h_done), .words_o(h_words));
  for (genvar k = 0; k < BBUF; k++) begin : g_b_buf
    assign b_buf[k] = b_words[32*k +: 32];
  end
  for (genvar k = 0; k < REC_MAX; k++) begin : g_f_buf
    assign f_buf[k] = f_words[32*k +: 32];
  end
  for (genvar k = 0; k < BUF; k++) begin : g_h_buf
    assign h_buf[k] = h_words[32*k +: 32];
  end

  // ---- the object's flags and the record's fields (shade_rec.h) ----
  /* verilator lint_off UNUSEDSIGNAL */
  logic [31:0] flags_q;  // bits 0, 1, 3, 4, 5 and the object's material in 16..31 (bit 2: the traversal's)
  /* verilator lint_on UNUSEDSIGNAL */
  logic [31:0] tri_base_q;
  logic [V*3-1:0] w2o_q;   // m[k][r] at word 3k + r
  logic has_n, has_tc, one_mat, has_col, has_euv;
  assign has_n = flags_q[0];
  assign has_tc = flags_q[1];
  assign one_mat = flags_q[3];
  assign has_col = flags_q[4];
  assign has_euv = flags_q[5];

  // words of a record for the flags f (shade_rec_words)
  /* verilator lint_off UNUSEDSIGNAL */
  function automatic logic [4:0] rec_words(input logic [5:0] f);  // f[2] is not the record's
  /* verilator lint_on UNUSEDSIGNAL */
    logic [31:0] bits;
    bits = (f[3] ? 32'd0 : 32'd16) + 32'(6 * W) * ((f[1] ? 32'd1 : 32'd0) + (f[5] ? 32'd1 : 32'd0)) +
           (f[4] ? 32'd72 : 32'd0);
    rec_words = 5'((f[0] ? 32'd4 : 32'd0) + (bits + 32'd31) / 32'd32);
  endfunction
  // as a table of the 64 flag values (a LUT6 a bit): its adders in front of the record address's
  // product made that path 9 LUT6 levels into the reader
  logic [4:0] rw_tab [64];
  for (genvar f = 0; f < 64; f++) begin : g_rw
    assign rw_tab[f] = rec_words(6'(f));
  end

  logic [32*REC_MAX-1:0] rec_flat, tail;
  for (genvar k = 0; k < REC_MAX; k++) begin : g_rec
    assign rec_flat[32*k +: 32] = rec_q[k];
  end
  assign tail = has_n ? rec_flat >> 128 : rec_flat;
  logic [31:0] mat_bits, colour_at;
  assign mat_bits = one_mat ? 32'd0 : 32'd16;
  assign colour_at = mat_bits + 32'(6 * W) * ((has_tc ? 32'd1 : 32'd0) + (has_euv ? 32'd1 : 32'd0));
  function automatic logic [31:0] tail_field(input logic [32*REC_MAX-1:0] tl, input logic [31:0] at);
    tail_field = 32'(tl >> at);
  endfunction

  // ---- the units ----
  logic [1:0] in_q, out_q;   // operations issued and results collected in the current state
  logic [3:0] qin_q, qout_q; // the conversions
  // the interpolated vertex normals (rgs_normal, outside: rgs_units shares one among its surface
  // units), a stream of the front's hits (its records' codes, u, v) in order, asked for from the
  // second stage's registers (h_rec, h_u, h_v) from the cycle after a hit with vertex normals loads
  // there (h_nrm_q) until rgs_units' arbiter takes it; the back does not take the hit before
  // (f_take). The request is registers only and its acknowledge feeds no load, so the path through
  // the arbiter's req -> ack stays within 8 LUT6 levels (9 when the ack gated h_load and the second
  // stage's burst). The results wait in a queue of NRM_SLOTS for the back, which takes its hit's
  // normal and zero test in S_NORM. A unit has at most 2 under way (its second stage's hit, its
  // back's), and asks only while fewer than NRM_SLOTS are (nrm_cnt_q), so the queue has room for
  // every result (rgs_normal has no back pressure)
  localparam int NRM_SLOTS = 2;
  logic nrm_ovalid, nrm_zero, nrm_take, nrm_room_q, h_nrm_q;
  logic [1:0] nrm_cnt_q, nrm_cnt;  // asked for and not yet taken by the back
  logic [V-1:0] nrm_n, n_q;
  assign nrm_codes_o = {h_rec[3][29:0], h_rec[2], h_rec[1], h_rec[0]};  // the 3 codes in the record's 4 normal words
  assign {nrm_u_o, nrm_v_o} = {h_u, h_v};
  assign nrm_valid_o = h_nrm_q && nrm_room_q;
  assign nrm_take = st == S_NORM && nrm_ovalid;
  /* verilator lint_off PINCONNECTEMPTY */
  sync_fifo #(.W(V + 1), .DEPTH(NRM_SLOTS)) u_nrm_q (
    .clk_i, .rst_ni, .valid_i(nrm_valid_i), .ready_o(), .data_i({nrm_zero_i, nrm_n_i}),
    .valid_o(nrm_ovalid), .ready_i(nrm_take), .data_o({nrm_zero, nrm_n}));
  /* verilator lint_on PINCONNECTEMPTY */
  assign nrm_cnt = nrm_cnt_q + 2'(nrm_valid_o && nrm_ready_i) - 2'(nrm_take);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      nrm_cnt_q <= '0;
      nrm_room_q <= 1'b1;
      h_nrm_q <= 1'b0;
    end else begin
      nrm_cnt_q <= nrm_cnt;
      nrm_room_q <= nrm_cnt != 2'(NRM_SLOTS);
      if (h_load) h_nrm_q <= f_st == F_REC && f_flags[0];
      else if (nrm_ready_i) h_nrm_q <= 1'b0;
    end
  end

  /* verilator lint_off PINCONNECTEMPTY */
  // the interpolation of a texture's s and t (tail coordinates i, 2+i, 4+i)
  logic tsel_q;              // the texture: 0 base colour, 1 emissive
  logic [31:0] uv_at;
  assign uv_at = mat_bits + (has_euv && tsel_q ? 32'(6 * W) : 32'd0);
  logic lerp_valid, lerp_ready, lerp_ovalid;
  logic [W-1:0] la, lb, lc, lerp_r, lr_q [3];
  // the texture's s (i = 0) and t (i = 1) at the 3 vertices, out of the record's tail into free-
  // running registers (the variable shift and rgs_lerp's first stage were 11 LUT6 levels in one
  // cycle): tsel_q and the record are stable from the S_TEX cycle before S_TLERP on
  logic [W-1:0] uvf_q [2][3];
  always_ff @(posedge clk_i) begin
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 3; j++) uvf_q[i][j] <= W'(tail_field(tail, uv_at + 32'(W) * 32'(2 * j + i)));
  end
  assign lerp_valid = st == S_TLERP && in_q != 2'd2;
  assign la = uvf_q[in_q[0]][0];
  assign lb = uvf_q[in_q[0]][1];
  assign lc = uvf_q[in_q[0]][2];
  rgs_lerp #(.E(E), .M(M), .TID_BITS(1), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES)) u_lerp (
    .clk_i(clk_i), .rst_ni(rst_ni), .valid_i(lerp_valid), .ready_o(lerp_ready), .tid_i(1'b0), .a_i(la), .b_i(lb),
    .c_i(lc), .u_i(u_q), .v_i(v_q), .valid_o(lerp_ovalid), .ready_i(1'b1), .tid_o(), .r_o(lerp_r));

  // the frame (rgs_frame, outside: rgs_units shares one among its surface units): the geometry
  // goes out in S_FRAME (fr_ready_i: taken), the results come back in the order of issue
  assign fr_valid_o = st == S_FRAME;
  assign {fr_o_o, fr_d_o, fr_t_o, fr_cos_n_o, fr_n_o, fr_w2o_o} = {o_q, d_q, t_q, cos_q, n_q, w2o_q};

  // the 9 conversions to Q12, off the sequence's path: issued one a cycle from the back's taking a
  // hit on (its normal's chain or the frame's issue meanwhile), u, v, then the material's factors
  // (words base 0..2, emission 4..6, metallic 10, which the front read); the results in that order
  // into qres_q 7, 8, then 0..6 (S_Q waits for the last)
  logic [31:0] tex_idx_q [2];
  logic [W-1:0] q_x;
  logic q_valid, q_ovalid;
  logic [15:0] q_r, qres_q [9];
  logic [3:0] q_word;
  always_comb begin
    unique case (qin_q)
      4'd2: q_word = 4'd0;
      4'd3: q_word = 4'd1;
      4'd4: q_word = 4'd2;
      4'd5: q_word = 4'd4;
      4'd6: q_word = 4'd5;
      4'd7: q_word = 4'd6;
      default: q_word = 4'd10;
    endcase
  end
  assign q_valid = st != S_IDLE && qin_q < 4'd9;
  assign q_x = qin_q == 4'd0 ? u_q : qin_q == 4'd1 ? v_q : buf_q[q_word][W-1:0];
  q12_of #(.E(E), .M(M), .MUL_STAGES(MUL_STAGES), .ADD_STAGES(ADD_STAGES), .TOI_STAGES(TOI_STAGES)) u_q12 (
    .clk_i(clk_i), .rst_ni(rst_ni), .en_i(1'b1), .valid_i(q_valid), .x_i(q_x),
    .valid_o(q_ovalid), .q_o(q_r));

  // the texture sample: its coordinates from tex_coords (outside: rgs_units shares one among its
  // surface units), asked for from registers (the s, t interpolated, the entry's words) from the
  // cycle after the entry is read (tx_req_q) until rgs_units' arbiter takes them (the acknowledge
  // only clears the request: 8 LUT6 levels); the result goes straight into tex_fetch, idle since the
  // unit's sample before, which reads the 4 texels on this unit's line port and blends them
  logic tx_req_q, tx_ovalid;
  logic [47:0] tx_rgb;
  assign tx_valid_o = tx_req_q;
  assign {tx_s_o, tx_t_o, tx_width_o, tx_height_o, tx_addr_o} = {lr_q[0], lr_q[1], b_buf[0], b_buf[1], b_buf[2]};
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) tx_req_q <= 1'b0;
    else if (st == S_TENTRY && burst_done) tx_req_q <= 1'b1;
    else if (tx_ready_i) tx_req_q <= 1'b0;
  end
  tex_fetch #(.TID_BITS(1)) u_tex (.clk_i(clk_i), .rst_ni(rst_ni), .valid_i(tx_valid_i), .ready_o(), .tid_i(1'b0),
    .row0_i(tx_row0_i), .row1_i(tx_row1_i), .x0_i(tx_x0_i), .x1_i(tx_x1_i), .fx_i(tx_fx_i), .fy_i(tx_fy_i),
    .req_valid_o(tex_req_valid), .req_ready_i(tex_port && port_go), .req_addr_o(tex_req_addr),
    .rsp_valid_i(tex_port && rsp_b), .rsp_ready_o(tex_rsp_ready), .rsp_data_i(tex_word),
    .valid_o(tx_ovalid), .ready_i(1'b1), .tid_o(), .rgb_o(tx_rgb));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- Q12 products (q_mul): the texture's modulation on 3 multipliers, the tint on 3 more ----
  logic [15:0] base_q [3], emis_q [3], qm_a [3], qm_p [3];
  for (genvar k = 0; k < 3; k++) begin : g_qm
    assign qm_a[k] = tsel_q ? emis_q[k] : base_q[k];
    q12_mul u_qm (.a_i(qm_a[k]), .b_i(tx_rgb[16*k +: 16]), .p_o(qm_p[k]));
  end

  // vertex colours (modulate_colours): the C's uint32 sums and product (q_mul of a factor that can
  // exceed 16 bits for barycentrics outside [0, 1])
  function automatic logic [15:0] q_sat32(input logic [31:0] x);
    q_sat32 = x < 32'd65535 ? x[15:0] : 16'hFFFF;
  endfunction
  function automatic logic [31:0] q_byte(input logic [7:0] b);
    q_byte = {20'd0, b, 4'd0} | {28'd0, b[7:4]};
  endfunction
  // Three free-running register stages (the vertex's bytes out of the record; the weighted sum;
  // the factor's product), so that no part of the chain has more than 8 LUT6 levels (12 in one):
  // their inputs (rec_q, flags_q from the back's taking the hit; u, v and the base factor from the
  // conversions) are stable at least 4 cycles before S_Q takes vc_q (qout_q reaches 9 four
  // results after the last base factor's), so they add no cycle.
  logic [31:0] wa, wb, wc;
  logic [11:0] cb_q [3][3];  // vertex j's channel k, widened to Q12
  logic [31:0] sum_q [3];
  logic [15:0] vc_q [3];
  assign wa = {16'd0, qres_q[7]};
  assign wb = {16'd0, qres_q[8]};
  assign wc = wa + wb < 32'(ONE) ? 32'(ONE) - wa - wb : 32'd0;
  always_ff @(posedge clk_i) begin
    for (int k = 0; k < 3; k++) begin
      for (int j = 0; j < 3; j++) cb_q[j][k] <= 12'(q_byte(8'(tail_field(tail, colour_at + 32'(24 * j + 8 * k)))));
      sum_q[k] <= wa * 32'(cb_q[0][k]) + wb * 32'(cb_q[1][k]) + wc * 32'(cb_q[2][k]);
      vc_q[k] <= q_sat32(({16'd0, qres_q[k]} * ((sum_q[k] + 32'd2048) >> 12) + 32'd2048) >> 12);
    end
  end

  // the texture to sample: its index below the header's count, and texture coordinates
  logic tex_used;
  assign tex_used = tex_idx_q[tsel_q] < n_tex_i && has_tc;
  logic [15:0] metal_c;
  assign metal_c = qres_q[6] < ONE ? qres_q[6] : ONE;

  // ---- outputs: a queue of SLOTS surfaces in order, the frame's results beside ----
  // The frame (118 cycles) runs while the material, its colours and the next surfaces' reads and
  // normals are worked on: a hit's geometry goes into rgs_frame as soon as its normal is known, and
  // the rest of its surface (tid, the material's fields, its colours) joins the queue when they are
  // done; a miss or an inactive ray joins at once without the frame. The frame's results come in
  // issue order, so its oldest one belongs to the queue's first hit: the head leaves with it (a hit)
  // or alone (a miss; the frame waits meanwhile).
  logic unlit_q;
  logic [31:0] mat_q;
  logic [3:0] k_q;
  logic [W-1:0] eta_q;
  logic [12:0] kd_q, kr_q, kt_q, ks_q;
  localparam int QW = TID_BITS + 1 + 32 + 1 + 4 + W + 4 * 13 + 3 * 48;
  logic [QW-1:0] q_in, q_head;
  logic q_push, q_room, q_any, q_hit;
  // the C's tint (1 - m) + q_mul(m, base) into a free-running register (its product, sum and
  // saturation into the queue's input were 9 LUT6 levels in S_TINT's one cycle): the metallic
  // factor is there from S_Q on, the base colour's last write (S_Q, or its texture's sample) is a
  // cycle or more (S_TEX) before S_TINT
  logic [47:0] base_v, emis_v, tint_v;
  for (genvar k = 0; k < 3; k++) begin : g_pack
    logic [15:0] tint_p;
    q12_mul u_tint (.a_i(qres_q[6]), .b_i(base_q[k]), .p_o(tint_p));
    always_ff @(posedge clk_i) tint_v[16*k +: 16] <= q_sat32({16'd0, ONE - metal_c} + {16'd0, tint_p});
    assign base_v[16*k +: 16] = base_q[k];
    assign emis_v[16*k +: 16] = emis_q[k];
  end
  // a miss joins as the back takes it from the front, with zero fields; a hit at the end of its
  // colours (S_TINT)
  assign f_take = st == S_IDLE && h_st == H_FULL && !h_nrm_q && q_room;  // its normal asked for
  assign q_push = st == S_TINT || (f_take && !h_hit);
  assign q_in = st == S_TINT ? {tid_q, 1'b1, mat_q, unlit_q, k_q, eta_q, kd_q, kr_q, kt_q, ks_q, base_v, emis_v, tint_v}
                             : {h_tid, (QW - TID_BITS)'(0)};
  sync_fifo #(.W(QW), .DEPTH(SLOTS)) u_queue (
    .clk_i, .rst_ni, .valid_i(q_push), .ready_o(q_room), .data_i(q_in),
    .valid_o(q_any), .ready_i(ready_i && (!q_hit || fr_valid_i)), .data_o(q_head)
  );
  assign q_hit = q_head[QW-TID_BITS-1];
  assign valid_o = q_any && (!q_hit || fr_valid_i);
  assign fr_ready_o = q_any && q_hit && ready_i;
  assign ready_o = f_st == F_IDLE;
  assign {tid_o, sf_valid_o, mat_o, unlit_o, k_o, eta_o, kd_o, kr_o, kt_o, ks_o, base_o, emission_o, tint_o} = q_head;
  assign p_o = q_hit ? fr_p_i : '0;
  assign d_o = q_hit ? fr_d_i : '0;
  assign n_o = q_hit ? fr_n_i : '0;
  assign t_hat_o = q_hit ? fr_t_hat_i : '0;
  assign entering_o = q_hit && fr_entering_i;

  // ---- the front's sequence ----
  logic [31:0] rec_addr, h_mat_at;
  assign rec_addr = f_buf[1] + 32'(rw_tab[f_buf[5][5:0]]) * f_tri;
  // the material: the object's (flags 16..31) or the record tail's first 16 bits
  assign h_mat_at = mat_base_i + 32'd16 * (h_flags[3] ? {16'd0, h_flags[31:16]}
                                                       : {16'd0, h_rec[h_flags[0] ? 4 : 0][15:0]});

  // the front's bursts, started in the cycle their address is known (each from the words before)
  always_comb begin
    f_start = 1'b0;
    f_rd_at = inst_base_i + 32'(INST_WORDS) * inst_i + 32'd12;
    f_rd_n = 5'd1;
    unique case (f_st)
      // the instance's object index (word 12) alone first: the object's, the record's reads and
      // the normal's chain wait on it, the matrix (words 0..11) only on the frame
      F_IDLE: f_start = valid_i && active_i && inst_i != NO_HIT;
      F_INST: begin
        f_start = f_done;
        f_rd_at = obj_base_i + 32'd16 * f_buf[0] + 32'd2;
        f_rd_n = 5'd6;
      end
      F_OBJ: begin
        f_start = f_done;
        f_rd_at = rec_addr;
        f_rd_n = rw_tab[f_buf[5][5:0]];
      end
      default: ;
    endcase
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) f_st <= F_IDLE;
    else begin
      unique case (f_st)
        F_IDLE:
          if (valid_i) begin
            f_tid <= tid_i;
            f_o <= o_i;
            f_d <= d_i;
            f_tri <= tri_i;
            f_t <= t_i;
            f_u <= u_i;
            f_v <= v_i;
            f_cos <= cos_n_i;
            f_hit <= active_i && inst_i != NO_HIT;
            f_inst_addr <= inst_base_i + 32'(INST_WORDS) * inst_i;
            f_st <= active_i && inst_i != NO_HIT ? F_INST : F_MISS;
          end
        F_INST: if (f_done) f_st <= F_OBJ;
        F_OBJ:
          if (f_done) begin
            f_tri_base <= f_buf[0];
            f_flags <= f_buf[5];
            f_st <= F_REC;
          end
        F_REC, F_MISS: if (h_load) f_st <= F_IDLE;  // into the second stage
        default: f_st <= F_IDLE;
      endcase
    end
  end

  // the second stage's bursts: the matrix, without vertex normals the geometric normal, the material
  always_comb begin
    h_start = 1'b0;
    h_rd_at = h_mat_at;
    h_rd_n = 5'd16;
    unique case (h_st)
      H_EMPTY: begin
        h_start = h_load && f_st == F_REC;
        h_rd_at = f_inst_addr;  // the instance's matrix (the word 12 read, 13 in all)
        h_rd_n = 5'd12;
      end
      H_W2O: begin
        h_start = h_done;
        if (!h_flags[0]) begin  // no vertex normals: the geometric normal, as the C reads it next
          h_rd_at = h_tri_base + 32'(TRI_WORDS) * h_tri + 32'(GN_WORD);
          h_rd_n = 5'(GN_SPAN);
        end
      end
      H_GN: h_start = h_done;
      default: ;
    endcase
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) h_st <= H_EMPTY;
    else begin
      unique case (h_st)
        H_EMPTY:
          if (h_load) begin
            {h_tid, h_hit, h_o, h_d, h_tri, h_tri_base, h_flags} <= {f_tid, f_hit, f_o, f_d, f_tri, f_tri_base, f_flags};
            {h_t, h_u, h_v, h_cos} <= {f_t, f_u, f_v, f_cos};
            for (int k = 0; k < REC_MAX; k++) h_rec[k] <= f_buf[k];
            h_n <= '0;
            h_st <= f_st == F_REC ? H_W2O : H_FULL;
          end
        H_W2O:
          if (h_done) begin
            for (int k = 0; k < 3; k++)
              for (int r = 0; r < 3; r++) h_w2o[W*(3*k+r) +: W] <= h_buf[4*k+r][W-1:0];
            if (h_flags[0]) h_mat_addr <= h_mat_at;
            h_st <= h_flags[0] ? H_MAT : H_GN;
          end
        H_GN:
          if (h_done) begin
            for (int c = 0; c < 3; c++) h_n[W*c +: W] <= W'({h_buf[2], h_buf[1], h_buf[0]} >> (GN_SHIFT + W * c));
            h_mat_addr <= h_mat_at;
            h_st <= H_MAT;
          end
        H_MAT: if (h_done) h_st <= H_FULL;
        H_FULL: if (f_take) h_st <= H_EMPTY;
        default: h_st <= H_EMPTY;
      endcase
    end
  end

  // the back's bursts: a zero interpolated normal's geometric normal, a texture's entry
  always_comb begin
    b_start = 1'b0;
    b_rd_at = tri_base_q + 32'(TRI_WORDS) * tri_q + 32'(GN_WORD);
    b_rd_n = BNW'(GN_SPAN);
    if (st == S_NORM) b_start = nrm_ovalid && nrm_zero;
    else if (st == S_TLERP) begin
      b_start = lerp_ovalid && out_q == 2'd1;
      b_rd_at = tex_base_i + 32'd4 * tex_idx_q[tsel_q];
      b_rd_n = BNW'(4);
    end
  end

  // ---- the back's sequence ----
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st <= S_IDLE;
    end else begin
      if (q_valid) qin_q <= qin_q + 4'd1;
      if (q_ovalid) begin
        qres_q[qout_q < 4'd2 ? qout_q + 4'd7 : qout_q - 4'd2] <= q_r;
        qout_q <= qout_q + 4'd1;
      end
      unique case (st)
        S_IDLE:  // a miss has joined the queue as it was taken (q_push)
          if (f_take && h_hit) begin
            tid_q <= h_tid;
            o_q <= h_o;
            d_q <= h_d;
            tri_q <= h_tri;
            t_q <= h_t;
            u_q <= h_u;
            v_q <= h_v;
            cos_q <= h_cos;
            w2o_q <= h_w2o;
            tri_base_q <= h_tri_base;
            flags_q <= h_flags;
            for (int k = 0; k < REC_MAX; k++) rec_q[k] <= h_rec[k];
            for (int k = 0; k < BUF; k++) buf_q[k] <= h_buf[k];  // the material's words
            mat_q <= h_mat_addr;
            tex_idx_q[0] <= h_buf[7];
            tex_idx_q[1] <= h_buf[12];
            unlit_q <= h_buf[8][3];
            k_q <= h_buf[14][29:26];
            eta_q <= h_buf[13][W-1:0];
            kd_q <= h_buf[14][12:0];
            kr_q <= h_buf[14][25:13];
            kt_q <= h_buf[15][12:0];
            ks_q <= h_buf[15][25:13];
            n_q <= h_n;  // the geometric normal without vertex normals
            qin_q <= '0;
            qout_q <= '0;
            in_q <= '0;
            out_q <= '0;
            st <= h_flags[0] ? S_NORM : S_FRAME;
          end
        S_NORM:  // the hit's normal from rgs_normal (its chain started as the front had the record)
          if (nrm_ovalid) begin
            n_q <= nrm_n;
            // f24_is_zero: the geometric normal, read here (b_start)
            st <= nrm_zero ? S_GN : S_FRAME;
          end
        S_GN:
          if (burst_done) begin
            for (int c = 0; c < 3; c++) n_q[W*c +: W] <= W'({b_buf[2], b_buf[1], b_buf[0]} >> (GN_SHIFT + W * c));
            st <= S_FRAME;
          end
        S_FRAME:  // the geometry into the frame
          if (fr_ready_i) st <= S_Q;
        S_Q: begin
          if (qout_q == 4'd9) begin
            for (int k = 0; k < 3; k++) begin
              base_q[k] <= has_col ? vc_q[k] : qres_q[k];
              emis_q[k] <= qres_q[3+k];
            end
            tsel_q <= 1'b0;
            st <= S_TEX;
          end
        end
        S_TEX:
          if (tex_used) begin
            in_q <= '0;
            out_q <= '0;
            st <= S_TLERP;
          end else if (tsel_q) st <= S_TINT;
          else tsel_q <= 1'b1;
        S_TLERP: begin
          if (lerp_valid && lerp_ready) in_q <= in_q + 2'd1;
          if (lerp_ovalid) begin
            lr_q[out_q] <= lerp_r;
            out_q <= out_q + 2'd1;
            if (out_q == 2'd1) st <= S_TENTRY;  // the entry's 4 words (b_start)
          end
        end
        S_TENTRY: if (burst_done) st <= S_TSAMPLE;  // its coordinates asked for (tx_req_q)
        S_TSAMPLE: begin
          if (tx_ovalid) begin
            for (int k = 0; k < 3; k++)
              if (tsel_q) emis_q[k] <= qm_p[k];
              else base_q[k] <= qm_p[k];
            if (tsel_q) st <= S_TINT;
            else begin
              tsel_q <= 1'b1;
              st <= S_TEX;
            end
          end
        end
        S_TINT: st <= S_IDLE;  // the surface joins the queue (q_push)
        default: st <= S_IDLE;
      endcase
    end
  end
endmodule
