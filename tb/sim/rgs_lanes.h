/*
 * The vector helpers of the RGS's host fast paths (tb/sim/rgs_*_lanes.c): a packet's 3-vectors
 * as three lanes (component r of ray i in lane i of vector r) and back, and the dot product of
 * f24w_dot3 (vec3.h) per lane, in its order and roundings. Only in a simulation build whose packet
 * values are vectors (F24_SIM_LANES, tb/fp/f24_fast.h).
 */
#ifndef SAARCOR_RGS_LANES_H
#define SAARCOR_RGS_LANES_H

#include "rgs_ops.h" /* (its f24.h reads the build's F24_SIM_HEADER, which defines F24_SIM_LANES) */

#ifdef F24_SIM_LANES

/* ((a.x b.x + a.y b.y) + a.z b.z) per lane: f24w_dot3 (vec3.h) of each ray */
F24V_INLINE f24v dot3_lanes(const f24v a[3], const f24v b[3])
{
    return f24v_add(f24v_add(f24v_mul(a[0], b[0]), f24v_mul(a[1], b[1])), f24v_mul(a[2], b[2]));
}

/* Component r of each ray's vector as a lane. */
F24V_INLINE void vec_lanes(const f24_vec3 v[TRACE_PACKET], f24v out[3])
{
    f24_t w[3][TRACE_PACKET];
    for (int i = 0; i < TRACE_PACKET; i++)
        w[0][i] = v[i].x, w[1][i] = v[i].y, w[2][i] = v[i].z;
    for (int r = 0; r < 3; r++)
        out[r] = f24v_of(w[r]);
}

/* Ray i's vector from the lanes' words by component. */
F24V_INLINE f24_vec3 lane_vec(const f24_t w[3][TRACE_PACKET], int i) { return (f24_vec3){ w[0][i], w[1][i], w[2][i] }; }

#endif
#endif
