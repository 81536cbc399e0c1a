/* Transformation unit: see xform_unit.h. */
#include "xform_unit.h"

/* The translation goes through a mux, not an add of zero, so a -0 sum keeps its sign. */
f24_t xform_row(const f24_t row[4], f24_vec3 p, int with_translation)
{
    const f24_t s = f24_add(f24_add(f24_mul(row[0], p.x), f24_mul(row[1], p.y)), f24_mul(row[2], p.z));
    return with_translation ? f24_add(s, row[3]) : s;
}

static f24_vec3 xform_step(const f24_affine *m, f24_vec3 p, int with_translation)
{
    const f24_vec3 r = { xform_row(m->m[0], p, with_translation), xform_row(m->m[1], p, with_translation),
                         xform_row(m->m[2], p, with_translation) };
    return r;
}

f24_vec3 xform_point(const f24_affine *m, f24_vec3 p) { return xform_step(m, p, 1); }

f24_vec3 xform_vector(const f24_affine *m, f24_vec3 v) { return xform_step(m, v, 0); }
