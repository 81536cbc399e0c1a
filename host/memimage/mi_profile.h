/*
 * The scene profile (issue: skip what a scene does not need): what a memory image needs of the
 * pipeline, derived from the image words alone (so the validator can re-derive and check it),
 * and the PROFILE_* skip bits (hls/units/trace.h) the host writes into camera word 3 for the
 * device. `saarcor profile SCENE [-o hls/config_NAME.h]` prints it and writes the synthesis
 * configuration that removes what the scene does not use (hls/config.h, docs/hls.md).
 */
#ifndef SAARCOR_MI_PROFILE_H
#define SAARCOR_MI_PROFILE_H

#include <stdint.h>

typedef struct {
    uint32_t objects, instances, triangles;
    int single_object;        /* one instance, alone in a one-leaf top-level tree */
    int identity;             /* ... whose world-to-object map is the identity */
    uint32_t textures;        /* textures some material uses on an object with texture coordinates */
    uint32_t lights, point_lights, spot_lights, directional_lights;
    uint32_t reflective, transmissive, refractive, emissive; /* materials with kr, kt, eta != 1, emission */
    int orthographic;         /* primary rays do not share their origin */
    uint32_t skip;            /* PROFILE_* bits this image allows */
} mi_profile;

/* Derives the profile of a validated image. */
void mi_profile_derive(const uint32_t *w, mi_profile *p);

#endif
