/* The table of scene generators (see scenes.h). */
#include "scenes.h"

#include <string.h>

const scene_generator scene_generators[] = {
    { "cornell", "the Cornell box: coloured walls, two instanced blocks, area + point light (36 triangles)",
      scene_gen_cornell },
    { "room", "a furnished room like the paper's Scene6: table, 4 instances of one chair (~2.9k triangles)",
      scene_gen_room },
    { "plants", "like the paper's SunCOR: N instances (--detail, default 5000) of one 30k-triangle sunflower",
      scene_gen_plants },
    { "terrain", "a fractal height field (--detail cells per side, default 256) with 300 instanced trees",
      scene_gen_terrain },
    { "animated", "LINEAR/STEP/CUBICSPLINE node animations (4 s) and a mesh with two animated morph targets",
      scene_gen_animated },
    { "emissive", "emissive textures (own KHR_texture_transform too) under emissiveFactor 1 and strength 3",
      scene_gen_emissive },
    { "vertex_colours", "COLOR_0 vertex colours on a plain sphere and multiplying a textured box", scene_gen_vertex_colours },
    { "uv_transform", "KHR_texture_transform offset, rotation, scale, and TEXCOORD_1 on four textured quads",
      scene_gen_uv_transform },
    { "unlit", "KHR_materials_unlit: unlit sphere beside its lit twin, textured poster, alpha-blended pane",
      scene_gen_unlit },
};

const unsigned scene_generator_count = sizeof scene_generators / sizeof scene_generators[0];

const scene_generator *scene_generator_find(const char *name)
{
    for (unsigned i = 0; name && i < scene_generator_count; i++)
        if (strcmp(scene_generators[i].name, name) == 0)
            return &scene_generators[i];
    return NULL;
}
