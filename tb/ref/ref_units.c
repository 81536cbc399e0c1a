/* Brute force with the units' arithmetic: see ref_units.h. */
#include "ref_units.h"

#include "isect_unit.h"
#include "memimage.h"
#include "rebase_unit.h"
#include "xform_unit.h"

void ref_units_to_object(const uint32_t *mem, uint32_t ia, f24_vec3 o, f24_vec3 d, f24_vec3x2 *oo, f24_vec3x2 *dd)
{
    const f24_affine w2o = f24_affine_load(mem, ia);
    const f24_vec3 t_lo = { mem[ia + MI_I_T_LO], mem[ia + MI_I_T_LO + 1], mem[ia + MI_I_T_LO + 2] };
    const f24_vec3x2 ow = { o, { 0, 0, 0 } };
    *oo = xform_point_wide(&w2o, t_lo, ow);
    *dd = xform_vector_wide(&w2o, d);
}

/* Triangle tri against the object-space ray (o, d): first from the origin, for where the ray meets
 * its plane, then with the origin moved there, as a leaf around the triangle would move it. */
static isect_result test_near(const f24_triangle *tri, f24_vec3x2 o, f24_vec3x2 d, f24_t tmin, f24_t tmax)
{
    const isect_result far = isect_unit_rebased(tri, o, 0, d.hi, F24_SIGN_BIT | F24_POS_INF, F24_POS_INF);
    const f24_t te = rebase_distance(far.t);
    return isect_unit_rebased(tri, rebase_origin(o, d, te), te, d.hi, tmin, tmax);
}

f24_t ref_units_closest(const uint32_t *mem, f24_vec3 o, f24_vec3 d, f24_t tmin, f24_t tmax, isect_result *hit)
{
    const uint32_t ia = mem[MI_H_REGION_TABLE + 2 * MI_R_INSTANCES], oa = mem[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    f24_t best = tmax;
    for (uint32_t i = 0; i < mem[MI_H_INSTANCES]; i++) {
        const uint32_t *od = mem + oa + MI_OBJECT_WORDS * mem[ia + MI_INSTANCE_WORDS * i + MI_I_OBJECT];
        f24_vec3x2 oo, dd;
        ref_units_to_object(mem, ia + MI_INSTANCE_WORDS * i, o, d, &oo, &dd);
        for (uint32_t t = 0; t < od[MI_O_N_TRIANGLES]; t++) {
            const f24_triangle tx = f24_triangle_load(mem, od[MI_O_TRIANGLES] + MI_TRIANGLE_WORDS * t);
            const isect_result r = test_near(&tx, oo, dd, tmin, best);
            if (!r.hit)
                continue;
            best = r.t;
            if (hit)
                *hit = r;
        }
    }
    return best;
}
