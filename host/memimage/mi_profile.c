/* The scene profile: see mi_profile.h. */
#include "mi_profile.h"

#include "f24.h"
#include "memimage.h"
#include "shade_rec.h"
#include "trace.h"
#include "xform_unit.h"

enum { M_EMISSIVE = 4, M_TEXTURE = 7, M_ETA = 13, M_SHADER0 = 14, M_SHADER1 = 15 };

static const uint32_t *region(const uint32_t *w, mi_region r) { return w + w[MI_H_REGION_TABLE + 2 * r]; }

/* One instance alone in a one-leaf top tree: then skipping the top level visits the same object
 * with the same ray bits. */
static int single_object(const uint32_t *w)
{
    if (w[MI_H_INSTANCES] != 1 || w[MI_H_TOP_NODES] != 1)
        return 0;
    const uint32_t *node = region(w, MI_R_TOP_NODES);
    return (node[0] & 3u) == MI_NODE_LEAF && node[0] >> 2 == 1 && region(w, MI_R_TOP_LISTS)[node[1]] == 0;
}

/* Its world-to-object map is the identity up to the signs of its zeros (xform_identity). */
static int identity_instance(const uint32_t *w)
{
    const f24_affine m = f24_affine_load(region(w, MI_R_INSTANCES), 0);
    return xform_is_identity(&m);
}

/* Materials whose textures (base colour, emission) some object with texture coordinates may sample. */
static uint32_t textured(const uint32_t *w)
{
    int coords = 0;
    for (uint32_t o = 0; o < w[MI_H_OBJECTS]; o++)
        coords |= (region(w, MI_R_OBJECTS)[MI_OBJECT_WORDS * o + MI_O_FLAGS] & MI_OBJECT_HAS_TEXCOORDS) != 0;
    uint32_t n = 0;
    for (uint32_t m = 0; m < w[MI_H_MATERIALS]; m++) {
        const uint32_t *mat = region(w, MI_R_MATERIALS) + MI_MATERIAL_WORDS * m;
        n += coords && (mat[M_TEXTURE] < w[MI_H_TEXTURES] || mat[SHADE_M_EMISSIVE_TEXTURE] < w[MI_H_TEXTURES]);
    }
    return n;
}

void mi_profile_derive(const uint32_t *w, mi_profile *p)
{
    *p = (mi_profile){ 0 };
    p->objects = w[MI_H_OBJECTS];
    p->instances = w[MI_H_INSTANCES];
    for (uint32_t o = 0; o < p->objects; o++)
        p->triangles += region(w, MI_R_OBJECTS)[MI_OBJECT_WORDS * o + MI_O_N_TRIANGLES];
    p->single_object = single_object(w);
    p->identity = p->single_object && identity_instance(w);
    p->textures = textured(w);
    p->lights = w[MI_H_LIGHTS];
    for (uint32_t l = 0; l < p->lights; l++) {
        const uint32_t kind = region(w, MI_R_LIGHTS)[MI_LIGHT_WORDS * l];
        p->directional_lights += kind == 0;
        p->point_lights += kind == 1;
        p->spot_lights += kind == 2;
    }
    for (uint32_t m = 0; m < w[MI_H_MATERIALS]; m++) {
        const uint32_t *mat = region(w, MI_R_MATERIALS) + MI_MATERIAL_WORDS * m;
        const uint32_t kr = mat[M_SHADER0] >> 13 & 0x1FFFu, kt = mat[M_SHADER1] & 0x1FFFu;
        p->reflective += kr != 0;
        p->transmissive += kt != 0;
        p->refractive += kt != 0 && mat[M_ETA] != F24_ONE;
        p->emissive += !f24_is_zero(mat[M_EMISSIVE]) || !f24_is_zero(mat[M_EMISSIVE + 1]) ||
                       !f24_is_zero(mat[M_EMISSIVE + 2]);
    }
    p->orthographic = region(w, MI_R_CAMERA)[0] == 1;
    p->skip = PROFILE_ANY_HIT | PROFILE_LIVE_CHILDREN;
    if (p->single_object)
        p->skip |= PROFILE_SINGLE_OBJECT;
    if (p->identity)
        p->skip |= PROFILE_IDENTITY;
    if (!p->reflective && !p->transmissive)
        p->skip |= PROFILE_NO_SECONDARY;
}
