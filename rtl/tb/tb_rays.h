// The packet on a trace port of a Verilated model (rgs_ctrl's tr_*, the DynRTP top's observation
// of trace_core's input) as the C core's ray_packet, for trace_begin.
#pragma once

#include "tb_common.h"

extern "C" {
#include "trace.h"
}

namespace cosim {

template <typename A, typename V, typename S>
ray_packet rays_of(A active, const V &o, const V &d, const S &tmin, const S &tmax)
{
    ray_packet rays{};
    rays.active = active;
    for (int i = 0; i < 4; i++) {
        rays.o[i] = { get(o, 3 * i), get(o, 3 * i + 1), get(o, 3 * i + 2) };
        rays.d[i] = { get(d, 3 * i), get(d, 3 * i + 1), get(d, 3 * i + 2) };
        rays.tmin[i] = get(tmin, i), rays.tmax[i] = get(tmax, i);
    }
    return rays;
}

} // namespace cosim
