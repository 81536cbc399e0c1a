/* Embree two-level scene of the benchmarks: see embree_scene.h. */
#include "embree_scene.h"

#include <stdio.h>
#include <string.h>

#include "scenes.h"

#ifndef SAARCOR_SRC_DIR
#define SAARCOR_SRC_DIR "."
#endif

const char *const bench_scene_names[BENCH_SCENES] = { "cornell", "room", "plants", "terrain", "teapot.glb", "bunny.glb",
                                                      "CesiumMilkTruck.glb", "gallery_ccby_503k.glb" };

int bench_scene_load(const char *name, scene *s, char *err, size_t n)
{
    if (!strchr(name, '.')) {
        const scene_gen_params gp = { 1, 0 };
        return scene_generator_find(name)->build(s, &gp, err, n);
    }
    char path[512];
    snprintf(path, sizeof path, SAARCOR_SRC_DIR "/../shared/scenes/%s", name);
    return scene_load_gltf(path, s, err, n);
}

/* One RTCScene holding the mesh's triangles (uncommitted), or NULL for an empty mesh. */
RTCScene embree_mesh_scene(RTCDevice dev, const scene_mesh *m, enum RTCBuildQuality q)
{
    if (m->n_triangles == 0 || m->n_vertices == 0)
        return NULL;
    RTCScene sc = rtcNewScene(dev);
    rtcSetSceneBuildQuality(sc, q);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, q);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m->n_vertices);
    unsigned *ix = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m->n_triangles);
    if (v && ix) {
        memcpy(v, m->positions, 3 * sizeof(float) * m->n_vertices);
        memcpy(ix, m->indices, 3 * sizeof(unsigned) * m->n_triangles);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(sc, g);
    rtcReleaseGeometry(g);
    return sc;
}

/* Top-level scene with one instance per scene instance (uncommitted). */
RTCScene embree_top_scene(RTCDevice dev, const scene *s, RTCScene *meshes, enum RTCBuildQuality q)
{
    RTCScene top = rtcNewScene(dev);
    rtcSetSceneBuildQuality(top, q);
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const scene_instance *in = &s->instances[i];
        if (!meshes[in->mesh])
            continue;
        float xf[12];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++)
                xf[4 * r + c] = (float)in->world.m[r][c];
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, meshes[in->mesh]);
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xf);
        rtcCommitGeometry(g);
        rtcAttachGeometry(top, g);
        rtcReleaseGeometry(g);
    }
    return top;
}
