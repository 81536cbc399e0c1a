/*
 * Host fast path of rgs_surfaces (hls/units/rgs_surface.c), bit-identical to it: a simulation
 * build whose packet values are vectors (F24_SIM_LANES, tb/fp/f24_fast.h) takes this definition,
 * and the per-ray loop there keeps the name rgs_surfaces_per_ray (hls/units/rgs_ops.h).
 *
 * Each ray's vertex normals are decoded (rgs_vertex_normals) and its reads, material and colours
 * taken (rgs_surface_material) per ray, the functions the per-ray datapath calls; the normals'
 * interpolation and its zero-length test before, and the frames of the packet's hits after
 * (rgs_surface_frame: the unit direction, the shading normal through the instance's transposed
 * matrix, turned towards the ray and normalized, t_hat and the hit point through T_R) as lanes,
 * every operation once for the four rays, in the same order and roundings per lane (neither reads
 * anything, so the reads keep their order). tests/test_rgs.c surface_frames_lanes compares the
 * frames with rgs_surface_frame on random words, surfaces_lanes the packets with the per-ray loop
 * on traced hits.
 */
#include "rgs_lanes.h"

#ifdef F24_SIM_LANES

/* Each lane's words, by component. */
F24V_INLINE void vec_bits(const f24v v[3], f24_t out[3][TRACE_PACKET])
{
    for (int r = 0; r < 3; r++)
        f24v_bits(v[r], out[r]);
}

F24V_FN void rgs_surface_frames(const ray_packet *rp, const hit_record h[], const f24_vec3 n[], const f24_affine w2o[],
                                uint32_t valid, surface sf[])
{
    f24v o[3], d[3], nv[3], tr[3][3];
    f24_t t[TRACE_PACKET], w[3][3][TRACE_PACKET];
    for (int i = 0; i < TRACE_PACKET; i++) {
        t[i] = h[i].t;
        for (int r = 0; r < 3; r++)
            for (int k = 0; k < 3; k++)
                w[r][k][i] = w2o[i].m[k][r]; /* the transposed 3x3 */
    }
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 3; k++)
            tr[r][k] = f24v_of(w[r][k]);
    vec_lanes(rp->o, o);
    vec_lanes(rp->d, d);
    vec_lanes(n, nv);
    const f24v one = f24v_splat(F24_ONE), zero = f24v_splat(0u);
    const f24v dlen = f24v_sqrt(dot3_lanes(d, d)), inv = f24v_div(one, dlen);
    f24v dw[3], nw[3], nu[3], p[3];
    for (int r = 0; r < 3; r++) {
        dw[r] = f24v_mul(d[r], inv);
        nw[r] = f24v_add(f24v_add(f24v_mul(tr[r][0], nv[0]), f24v_mul(tr[r][1], nv[1])), f24v_mul(tr[r][2], nv[2]));
    }
    const uint32_t towards = f24v_sign(dot3_lanes(nw, dw)); /* else turned towards the ray */
    for (int r = 0; r < 3; r++)
        nw[r] = f24v_pick(towards, nw[r], -nw[r]);
    const f24v ninv = f24v_div(one, f24v_sqrt(dot3_lanes(nw, nw))), t_hat = f24v_mul(f24v_of(t), dlen);
    for (int r = 0; r < 3; r++) {
        nu[r] = f24v_mul(nw[r], ninv);
        /* P = T_R (0, 0, t_hat), T_R's rows (D^, N^, D^, O) */
        p[r] = f24v_add(f24v_add(f24v_add(f24v_mul(dw[r], zero), f24v_mul(nu[r], zero)), f24v_mul(dw[r], t_hat)), o[r]);
    }
    f24_t dwb[3][TRACE_PACKET], nub[3][TRACE_PACKET], pb[3][TRACE_PACKET], tb[TRACE_PACKET];
    vec_bits(dw, dwb);
    vec_bits(nu, nub);
    vec_bits(p, pb);
    f24v_bits(t_hat, tb);
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!(valid >> i & 1u))
            continue;
        sf[i].d = lane_vec(dwb, i);
        sf[i].n = lane_vec(nub, i);
        sf[i].entering = f24_sign(h[i].cos_n) != 0;
        sf[i].t_hat = tb[i];
        sf[i].tr = t_r(rp->o[i], sf[i].d, sf[i].n);
        sf[i].p = lane_vec(pb, i);
    }
}

/* The hits' interpolated vertex normals (rgs_lerp_normal's products and sums per lane; zero for
 * the rays not in has) into vn, and the rays whose vn has squared length zero (f24_is_zero of
 * rgs_dot3). */
static F24V_FN uint32_t vertex_normals_lanes(const f24_t nw[TRACE_PACKET][3][F24Q_LANES], const hit_record h[],
                                             uint32_t has, f24_vec3 vn[TRACE_PACKET])
{
    f24_t u[TRACE_PACKET], v[TRACE_PACKET], w[3][3][TRACE_PACKET];
    for (int i = 0; i < TRACE_PACKET; i++) {
        u[i] = h[i].u, v[i] = h[i].v;
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 3; k++)
                w[c][k][i] = nw[i][c][k];
    }
    const f24v zero = f24v_splat(0u), uq = f24v_of(u), vq = f24v_of(v);
    const f24v wq = f24v_sub(f24v_sub(f24v_splat(F24_ONE), uq), vq);
    f24v r[3];
    f24_t out[3][TRACE_PACKET];
    for (int c = 0; c < 3; c++) {
        const f24v p0 = f24v_mul(f24v_of(w[c][0]), uq), p1 = f24v_mul(f24v_of(w[c][1]), vq);
        r[c] = f24v_pick(has, f24v_add(f24v_add(p0, p1), f24v_mul(f24v_of(w[c][2]), wq)), zero);
        f24v_bits(r[c], out[c]);
    }
    for (int i = 0; i < TRACE_PACKET; i++)
        vn[i] = lane_vec(out, i);
    const f24v len2 = dot3_lanes(r, r);
    return f24v_le(len2, zero) & f24v_le(zero, len2); /* == 0, either sign */
}

void rgs_surfaces(const uint32_t *mem, const ray_packet *rp, const hit_record h[], surface sf[], unit_op *op,
                  trace_counters *c)
{
    f24_t nw[TRACE_PACKET][3][F24Q_LANES] = { 0 };
    f24_vec3 vn[TRACE_PACKET], n[TRACE_PACKET] = { 0 };
    f24_affine w2o[TRACE_PACKET] = { 0 };
    uint32_t has = 0, valid = 0;
    for (int i = 0; i < TRACE_PACKET; i++)
        has |= (uint32_t)rgs_vertex_normals(mem, rp, i, &h[i], nw[i]) << i;
    const uint32_t flat = vertex_normals_lanes(nw, h, has, vn);
    for (int i = 0; i < TRACE_PACKET; i++) {
        sf[i] = rgs_surface_material(mem, rp, i, &h[i], vn[i], (int)(flat >> i & 1u), &n[i], &w2o[i], op, c);
        valid |= (uint32_t)(sf[i].valid != 0) << i;
    }
    if (valid)
        rgs_surface_frames(rp, h, n, w2o, valid, sf);
}
#endif
