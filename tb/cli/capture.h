/*
 * saarcor render --capture-unit-io DIR: the inputs and outputs of the datapath units while a
 * frame renders, as hex vectors for the RTL co-simulation (rtl/tb/tb_units.cpp): DIR/xform.hex
 * (12 matrix words, 3 vector words, point flag, 3 result words), DIR/isect.hex (O', D', the
 * rebase distance te, tmin, tmax; hit, t, u, v, cos), DIR/trav.hex (axis, split, mask, 4 x O, 4 x D, 4 x tn, 4 x tf; child
 * masks, near-left bits, 4 x left tn, tf, right tn, tf), DIR/list.hex (the list unit, for
 * rtl/tb/tb_list.cpp: thread, level, clear, lists, leaf_first, k, leaf_mask, alive, the entry
 * read; key, need, skip mask, k after; a clear has zeros beyond its flag; the thread is the
 * trace_state's number in the order first seen), DIR/mem.hex (cycle mode only, for
 * rtl/tb/tb_cache.cpp: per pipe a line "C pipe" with the cache sizes and line bytes of the four
 * kinds, the latency and the port's occupancy per byte in 1/65536 cycles, then per read of the
 * memory interface: pipe, kind, word address, words, cycle, the cycle its data is at the unit,
 * lookups, hits; "N pipe" where a frame starts, "F pipe" where the caches are emptied),
 * DIR/sched.hex (cycle mode only, for rtl/tb/tb_sched.cpp: the thread scheduler's ready and
 * issue events, capture_sched_probe), DIR/rgs.hex (the RGS's primary rays, for
 * rtl/tb/tb_rgs.cpp: per block a thread takes, in the order taken, x0, y0, the 16 camera words, the primary packet's active mask, 4 x O, 4 x D, 4 x tmin, 4 x tmax;
 * in cycle mode with one pipe that is the tile controller's order),
 * DIR/rebase.hex (rebase_origin, for rtl/tb/tb_wide.cpp: o hi, o lo, d hi, d lo, t; p hi, p lo,
 * rebase_distance(t)), DIR/wide.hex (xform_point_wide and xform_vector_wide: 12 matrix words, the
 * translation's 3 low words, p hi, p lo, point flag; r hi, r lo; a vector with zero low words),
 * DIR/trav_unit.hex (the traversal unit's operations, for rtl/tb/tb_trav.cpp: scene and object
 * clips, walk starts and steps per thread and level with their operands, the node read and the
 * walker state after; the layout at record_trav in capture.c), DIR/trace.hex (the core, for
 * rtl/tb/tb_core.cpp: every packet traced, from trace_begin to the trace_step that ends it: the
 * rays, flags, hits and the packet's trace_counters; the layout at captured_trace_step), with the
 * memory images they read in DIR/image_N.bin (the used words, little-endian), DIR/shade_rec.hex (the RGS's
 * decoding of the compact shading record's vertex normals, shade_rec_normals (a line per normal), for
 * rtl/tb/tb_shade.cpp: the record's 4 normal words, the vertex k, the unit normal's 3 words),
 * DIR/tex.hex (the RGS's bilinear texture samples, rgs_sample_bilinear, for rtl/tb/tb_shade.cpp:
 * s, t, the texture's width, height and texel address, the 4 texel words read, the axes' x0, x1,
 * fx, y0, y1, fy, the Q12 sample), DIR/frame.hex (the frame of each hit the RGS shades,
 * rgs_surface_frame, for rtl/tb/tb_shade.cpp: o, d, t, cos_n, the object-space normal, the
 * world-to-object matrix's 3x3 row by row; the unit direction, the unit normal, entering, t_hat,
 * the hit point), DIR/light.hex (each light at each surface of a packet, rgs_light_packet, for
 * rtl/tb/tb_shade.cpp, a line per ray: the light record's words 0..12, eps, the surface's valid,
 * unlit, P, N^, D^, highlight exponent; the shadow ray's o, d, tmin, tmax, active bit, the diffuse
 * and highlight weights), DIR/lerp.hex (each component of a hit's interpolated vertex normal or
 * texture coordinates, rgs_lerp and rgs_lerp_normal (a line per component), for rtl/tb/tb_shade.cpp: a, b, c, u, v; the result),
 * DIR/colour.hex (each light's colour, rgs_light_colour: the record's words 1..3; the Q12 colour),
 * DIR/accum.hex (each visible light added to a ray, rgs_add_light: the diffuse and highlight sums
 * before, diff, spec, the colour; the sums after), DIR/spawn.hex (the child rays of each surface,
 * rgs_spawn_children: the material's words 13..15, the ray's weight, e, the T_R origin, D^, N^,
 * t_hat, entering, tint, base; the reflection and the transmission ray's o, d, weight, active bit).
 * The hls/ units are not touched: the capture build of the program (CAPTURE_DIR/saarcor beside it,
 * which the program runs for --capture-unit-io; the only one that links this file) is linked with --wrap for xform_point, xform_vector,
 * isect_unit_rebased, isect_unit_packet (recorded ray by ray), trav_node_split_held, list_unit_entry,
 * list_mailboxes_clear, mem_iface_read, mem_iface_flush, mem_iface_new_frame, rgs_block_begin,
 * rebase_origin, xform_point_wide, xform_vector_wide (called from trace.c, in another object),
 * trav_scene_clip, trav_object_clip, trav_start, trav_walk, trace_begin, trace_step,
 * shade_rec_normals, rgs_sample_bilinear, rgs_lerp, rgs_lerp_normal, rgs_surface_frame, rgs_light_packet,
 * rgs_light_colour, rgs_add_light, rgs_spawn_children, rgs_surface_at, rgs_surfaces, rgs_accumulate_ray and
 * rgs_accumulate_rays (a packet's surfaces and accumulation, recorded ray by ray) (called from rgs.c; trace_packet's own
 * calls are not seen), and the wrappers record the calls
 * while capturing is on (at most `limit` transactions per unit; recorded in call order, which with several host threads
 * interleaves).
 */
#ifndef SAARCOR_CAPTURE_H
#define SAARCOR_CAPTURE_H

#include <stdint.h>

/* The capture build's folder, beside the program it stands for (build/capture/saarcor; the
 * Makefile's CAPTURE_DIR). */
#define CAPTURE_DIR "capture"

/* Weak: this file's functions are linked only into the capture build (tb/cli/capture.c with the
 * units' --wrap wrappers), which keeps the wrappers off every other render's path; in the program
 * they are NULL, and render runs the capture build instead. */
#define CAPTURE_API __attribute__((weak))

/* 0, or -1 with a message in err if DIR cannot be made or its files written. */
CAPTURE_API int capture_start(const char *dir, uint64_t limit, char *err, unsigned errlen);

/* Transactions recorded per unit (DIR/NAME.hex for each name): xform, isect, trav, list, mem, sched, rgs,
 * rebase, wide, trav_unit, trace, shade_rec, tex, frame, light, lerp, colour, accum, spawn, surface, accumulate. */
#define CAPTURE_UNITS 21
CAPTURE_API extern const char *const capture_unit_names[CAPTURE_UNITS];
CAPTURE_API void capture_counts(uint64_t out[CAPTURE_UNITS]);

/* The cycle model's scheduler probe (cycle_set_sched_probe) that writes DIR/sched.hex. */
CAPTURE_API void capture_sched_probe(void *arg, uint32_t pipe, int what, uint64_t cycle, uint32_t unit, uint32_t thread,
                         uint32_t slots);

/* Closes the files; 0, or -1 if writing failed. */
CAPTURE_API int capture_stop(void);

#endif
