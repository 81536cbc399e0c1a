/* Brute force with the units' arithmetic: see ref_units.h. */
#include "ref_units.h"

#include "isect_unit.h"
#include "memimage.h"
#include "xform_unit.h"

f24_t ref_units_closest(const uint32_t *mem, f24_vec3 o, f24_vec3 d, f24_t tmin, f24_t tmax)
{
    const uint32_t ia = mem[MI_H_REGION_TABLE + 2 * MI_R_INSTANCES], oa = mem[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    f24_t best = tmax;
    for (uint32_t i = 0; i < mem[MI_H_INSTANCES]; i++) {
        const f24_affine w2o = f24_affine_load(mem, ia + MI_INSTANCE_WORDS * i);
        const uint32_t *od = mem + oa + MI_OBJECT_WORDS * mem[ia + MI_INSTANCE_WORDS * i + 12];
        const f24_vec3 oo = xform_point(&w2o, o), od_dir = xform_vector(&w2o, d);
        for (uint32_t t = 0; t < od[MI_O_N_TRIANGLES]; t++) {
            const f24_affine tx = f24_affine_load_record(mem, od[MI_O_TRIANGLES] + MI_TRIANGLE_WORDS * t);
            const isect_result r = isect_unit_transformed(&tx, oo, od_dir, tmin, best);
            if (r.hit)
                best = r.t;
        }
    }
    return best;
}
