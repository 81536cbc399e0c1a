/* Material mapping of the fixed-function shader: see shading_model.h and docs/shading.md. */
#include "shading_model.h"

#include <math.h>

static double clamp01(double x) { return x > 0 ? (x < 1 ? x : 1) : 0; } /* NaN -> 0 */

void shading_params_of(const scene_material *m, shading_params *out)
{
    const double metal = clamp01(m->metallic), rough = clamp01(m->roughness);
    const double gloss = (1 - rough) * (1 - rough);
    double transmission = clamp01(m->transmission), eta = m->ior;
    if (!(eta >= 1 && eta <= 4))
        eta = 1.5; /* the glTF default; KHR_materials_ior allows 1 or more, we cap at diamond-like 4 */
    if (transmission == 0 && m->alpha == ALPHA_BLEND) {
        transmission = clamp01(1.0 - m->base_color[3]); /* alpha blending: straight transparency */
        eta = 1;
    }
    /* unlit (KHR_materials_unlit): no reflection or highlight, and kd weighs the base colour
     * without light; transparency (alpha blend, transmission) still lets the rest through */
    const int unlit = m->unlit != 0;
    out->unlit = unlit;
    out->metallic = unlit ? 0 : metal;
    out->kr = unlit ? 0 : (0.04 + 0.96 * metal) * gloss;
    out->kt = (1 - out->kr) * (1 - out->metallic) * transmission;
    out->kd = 1 - out->kr - out->kt;
    out->ks = unlit ? 0 : 0.5 * gloss;
    out->exp_shift = (uint32_t)lround(1 + 7 * gloss);
    out->eta = eta;
}
