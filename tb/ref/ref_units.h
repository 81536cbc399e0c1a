/*
 * Brute force with the hardware units' own arithmetic: the closest hit over every instance and
 * triangle of a memory image (world-to-object and triangle transformations, unit-triangle test,
 * no traversal). Where the traversal moves each ray's origin to the leaf it enters (rebase_unit.h),
 * the brute force has no leaves: it tests each triangle from the ray's origin for where the ray
 * meets its plane, then again with the origin moved there, so that its answer has the precision of
 * the traversal's (equal distances up to the rounding of the two rebase distances). Used by tests/test_trace.c and the stress
 * suite (tb/cli/stress.c) to judge the traversal; not a renderer.
 */
#ifndef SAARCOR_REF_UNITS_H
#define SAARCOR_REF_UNITS_H

#include <stdint.h>

#include "isect_unit.h"

/* The object-space ray (o, d) of the instance record at word ia, as the transformation unit's
 * wide mode gives it (double words). */
void ref_units_to_object(const uint32_t *mem, uint32_t ia, f24_vec3 o, f24_vec3 d, f24_vec3x2 *oo, f24_vec3x2 *dd);

/* The smallest t in [tmin, tmax) of any triangle the units accept, or tmax if none; that
 * triangle's result in *hit if hit is not NULL and there is one. */
f24_t ref_units_closest(const uint32_t *mem, f24_vec3 o, f24_vec3 d, f24_t tmin, f24_t tmax, isect_result *hit);

#endif
