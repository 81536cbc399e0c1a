/*
 * fp24 held packet values: the packet values (f24q, f24.h) a unit keeps in its state from one
 * operation to the next (the traversal unit's intervals, trav_entry in hls/units/trace.h). The
 * hardware holds the fp24 words: f24h_put stores the results' bits, f24h_get reads them. A
 * simulation build with working values holds the lanes as working values instead (its
 * F24_SIM_HEADER may name the type and define F24_SIM_HELD), so that an operation reads them
 * without decoding and stores its results without encoding. Every use of a held value is an
 * operation on it, which reads a word and its decoding alike (subnormal encodings as zero, a NaN
 * as a NaN of its sign); f24h_words gives the words of the values (a copied word that was not the
 * result of an operation comes back as its value's encoding). A header of its own: f24.h is read
 * in the middle of a simulation header that defines f24q after it.
 */
#ifndef SAARCOR_F24_HELD_H
#define SAARCOR_F24_HELD_H

#include "f24.h"

#ifdef F24_SIM_WORKING
#ifndef F24_SIM_HELD
typedef f24q f24h;
#endif
F24Q_INLINE f24q f24h_get(const f24h *h) { return *h; }
F24Q_INLINE void f24h_put(f24h *h, f24q q) { *h = q; }
#else
typedef f24_t f24h[F24Q_LANES];
static inline f24q f24h_get(const f24h *h) { return f24q_of(*h); }
static inline void f24h_put(f24h *h, f24q q) { f24q_bits(q, *h); }
#endif
/* a held value copied as it is (the hardware's register move: the words, not their values) */
#ifdef F24_SIM_WORKING
static inline void f24h_copy(f24h *dst, const f24h *src) { *dst = *src; }
#else
static inline void f24h_copy(f24h *dst, const f24h *src)
{
held_copy:
    for (int i = 0; i < F24Q_LANES; i++)
        (*dst)[i] = (*src)[i];
}
#endif
/* the lanes of h from fp24 words, and back */
F24Q_INLINE void f24h_of(f24h *h, const f24_t a[F24Q_LANES]) { f24h_put(h, f24q_of(a)); }
F24Q_INLINE void f24h_words(const f24h *h, f24_t out[F24Q_LANES]) { f24q_bits(f24h_get(h), out); }
/* one lane's word, and a lane set from a word (the cursor walkers' per-ray operations) */
F24Q_INLINE f24_t f24h_lane(const f24h *h, int i) { return f24w_bits(f24q_lane(f24h_get(h), i)); }
F24Q_INLINE void f24h_set_lane(f24h *h, int i, f24_t a)
{
    f24h_put(h, f24q_select(1u << i, f24q_splat(a), f24h_get(h)));
}

#endif
