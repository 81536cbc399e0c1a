/*
 * Brute force with the hardware units' own arithmetic: the closest hit over every instance and
 * triangle of a memory image (world-to-object and triangle transformations, unit-triangle test,
 * no traversal). What a complete traversal must find, bit for bit, up to the walk order where a
 * triangle's rounded distance lies outside its cell. Used by tests/test_trace.c and the stress
 * suite (tb/cli/stress.c) to judge the traversal; not a renderer.
 */
#ifndef SAARCOR_REF_UNITS_H
#define SAARCOR_REF_UNITS_H

#include <stdint.h>

#include "vec3.h"

/* The smallest t in [tmin, tmax) of any triangle the units accept, or tmax if none. */
f24_t ref_units_closest(const uint32_t *mem, f24_vec3 o, f24_vec3 d, f24_t tmin, f24_t tmax);

#endif
