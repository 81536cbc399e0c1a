/* The RGS's bilinear texture sample: see rgs_ops.h and docs/shading.md ("Integer colour
 * arithmetic"). Outside rgs.c so that the unit capture can wrap rgs_sample_bilinear. */
#include "rgs_ops.h"

#include "trace_ops.h"

/* The texel word of texture entry tex at wrapped coordinates (one shading read). */
static uint32_t texel(const uint32_t *mem, const uint32_t *tex, uint32_t x, uint32_t y, unit_op *op, trace_counters *c)
{
    const uint32_t at = tex[2] + y * tex[0] + x;
    op_read(op, c, MEM_SHADING, at, 1);
    return mem[at];
}

/* Channel k of a texel word, as Q12. */
static uint32_t channel(uint32_t texel_word, int k) { return q_byte(texel_word >> (8 * k) & 0xFFu); }

void rgs_texel_axis(f24_t s, uint32_t n, uint32_t *i0, uint32_t *i1, uint32_t *frac)
{
    const f24w x = f24w_sub(f24w_mul(f24w_of(s), f24w_from_i32((int32_t)n)), rgs_ratio_w(1, 2));
    int32_t i = f24w_to_i32(x);
    if (f24w_lt(x, f24w_from_i32(i)) && i != INT32_MIN)
        i -= 1; /* to_i32 rounds toward zero; this is floor (a saturated coordinate stays) */
    const f24w f = f24w_sub(x, f24w_from_i32(i));
    const int32_t q = f24w_to_i32(f24w_add(f24w_mul(f, f24w_from_i32(256)), rgs_ratio_w(1, 2)));
    const int32_t m = i % (int32_t)n;
    *i0 = (uint32_t)(m < 0 ? m + (int32_t)n : m); /* repeat wrapping */
    *i1 = *i0 + 1 == n ? 0 : *i0 + 1;
    *frac = q < 0 ? 0u : q > 256 ? 256u : (uint32_t)q;
}

void rgs_bilinear_blend(const uint32_t texel[4], uint32_t fx, uint32_t fy, uint32_t out[3])
{
bilinear:
    for (int k = 0; k < 3; k++) {
        const uint32_t top = channel(texel[0], k) * (256u - fx) + channel(texel[1], k) * fx;
        const uint32_t bottom = channel(texel[2], k) * (256u - fx) + channel(texel[3], k) * fx;
        out[k] = (top * (256u - fy) + bottom * fy + 32768u) >> 16;
    }
}

void rgs_sample_bilinear(const uint32_t *mem, const uint32_t *tex, f24_t s, f24_t t, uint32_t out[3], unit_op *op,
                         trace_counters *c)
{
    uint32_t x0, x1, fx, y0, y1, fy;
    rgs_texel_axis(s, tex[0], &x0, &x1, &fx);
    rgs_texel_axis(t, tex[1], &y0, &y1, &fy);
    const uint32_t texels[4] = { texel(mem, tex, x0, y0, op, c), texel(mem, tex, x1, y0, op, c),
                                 texel(mem, tex, x0, y1, op, c), texel(mem, tex, x1, y1, op, c) };
    rgs_bilinear_blend(texels, fx, fy, out);
}
