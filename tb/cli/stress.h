/*
 * The numerical stability stress suite (saarcor stress, make stress; docs/stress.md).
 *
 * Each case builds an adversarial scene on the host (closed jittered meshes, geometry far from
 * the origin, slivers, extreme instance transformations, NaN/Inf inputs, ...), writes its memory
 * image, and shoots a set of rays through the hardware units (trace_packet, the fp24 format of
 * this build) and through the binary64 reference (tb/ref: own BVH, watertight triangle test) on
 * the very same rays (the fp24-rounded origins and directions). What a case measures and the
 * criterion it must meet are stated per case; the counts are comparable across widths because
 * every build generates the same rays.
 */
#ifndef SAARCOR_STRESS_H
#define SAARCOR_STRESS_H

#include <stdint.h>

/* How a case's rays are judged. */
enum {
    STRESS_MUST_HIT = 1,   /* rays aimed at a surface: the reference's crossing (by t = target) missed by the units is a leak */
    STRESS_MUST_MISS = 2,  /* no ray may hit (rays leaving a convex surface): a hit is acne */
    STRESS_MULTI = 4,      /* count rays that more than one triangle of the object accepts */
    STRESS_BRUTE = 8,      /* compare the closest hit with brute force over all triangles with the units' arithmetic */
};

typedef struct {
    const char *name;
    const char *what;      /* one line: what the case does */
    const char *criterion; /* one line: when it passes */
    uint32_t flags;
    uint64_t rays;
    uint64_t unit_hits, ref_hits, agree; /* hit/miss agreement of units and reference */
    uint64_t leaks;        /* STRESS_MUST_HIT rays the units let through */
    uint64_t acne;         /* STRESS_MUST_MISS rays the units report a hit for */
    uint64_t multi;        /* STRESS_MULTI rays accepted by two or more triangles */
    uint64_t traversal;    /* STRESS_BRUTE rays where the traversal misses or hits (t +0.1%) behind brute force */
    uint64_t bad;          /* hits with a non-finite t, u or v, or t outside [tmin, tmax) */
    uint64_t nondeterministic; /* rays whose second trace differs from the first */
    uint32_t dropped;      /* triangles the host dropped as degenerate */
    double t_err_p99, t_err_max; /* relative t error over rays both hit */
    int build_failed;      /* the host refused the scene (a clear error, counted as handled) */
    int pass;
} stress_result;

/* Runs every case whose name contains one of the comma-separated parts of `filter` (NULL: all) with about `rays` rays each;
 * results[] gets at most max entries; returns the number run, or -1 (out of memory). `shared`
 * is the folder of the shared scenes (cases that need one are skipped if it is missing). A caught
 * Ctrl-C (interrupt.h) stops it before the next case. */
int stress_run(const char *filter, uint32_t rays, const char *shared, stress_result *results, int max);

/* The names, descriptions and criteria of every case, without running any; returns the count. */
int stress_describe(stress_result *results, int max);

#endif
