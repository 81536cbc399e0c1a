/* Edge and random operands for the fp24 checks (see f24_vec.h). */
#include "f24_vec.h"

#include "f24.h"

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

void f24_rng_seed(f24_rng *rng, uint64_t seed)
{
    for (int i = 0; i < 4; i++) { /* splitmix64 */
        uint64_t z = (seed += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        rng->s[i] = z ^ (z >> 31);
    }
}

uint64_t f24_rng_next(f24_rng *rng)
{
    uint64_t *s = rng->s;
    const uint64_t result = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

static uint32_t rnd_below(f24_rng *rng, uint32_t n) { return (uint32_t)(f24_rng_next(rng) % n); }

/* ---- edge set ---------------------------------------------------------------------------- */

typedef struct { f24_pair *out; size_t cap, n; } sink;

static void put(sink *s, uint32_t a, uint32_t b)
{
    if (s->n < s->cap)
        s->out[s->n] = (f24_pair){ a, b };
    s->n++;
}

static uint32_t fmk(uint32_t sign, int32_t exp, uint32_t frac)
{
    return f24_pack(sign, (uint32_t)exp, frac & F24_FRAC_MASK);
}

/* Magnitudes that every operation is tried on, each with both signs. */
static size_t special_values(uint32_t *v)
{
    const int32_t B = F24_BIAS, X = F24_EXP_MAX;
    const uint32_t ones = F24_FRAC_MASK, top = 1u << (F24_MAN_BITS - 1);
    const uint32_t mags[] = {
        0, 1, ones,                                          /* zero, subnormal encodings */
        fmk(0, 1, 0), fmk(0, 1, 1), fmk(0, 1, ones), fmk(0, 2, 0), /* around the smallest normal */
        fmk(0, B - 1, 0), fmk(0, B - 1, ones), fmk(0, B, 0), fmk(0, B, 1), fmk(0, B, top),
        fmk(0, B, ones), fmk(0, B + 1, 0), fmk(0, B + 1, top),   /* 0.5 .. 3 */
        fmk(0, B + B / 2, 0x5A5A5A5Au), fmk(0, B - B / 2, 0x2C2C2C2Cu), /* products near the limits */
        fmk(0, B > F24_MAN_BITS + 1 ? B - F24_MAN_BITS - 1 : 1, 0), /* half an ulp of one */
        fmk(0, X - 2, ones), fmk(0, X - 1, 0), fmk(0, X - 1, ones - 1), fmk(0, X - 1, ones), /* max */
        fmk(0, X, 0), fmk(0, X, top), fmk(0, X, 1), fmk(0, X, ones), /* Inf, NaNs */
    };
    size_t n = 0;
    for (size_t i = 0; i < sizeof mags / sizeof mags[0]; i++) {
        v[n++] = mags[i];
        v[n++] = mags[i] | F24_SIGN_BIT;
    }
    return n;
}

/* Exact ties, ties +- one bit, and carries into the next binade of an adder, at exponent e. */
static void add_rounding_cases(sink *s, int32_t e)
{
    const int32_t half_exp = e - F24_MAN_BITS - 1; /* half an ulp of 2^e */
    if (half_exp < 1 || e >= F24_EXP_MAX)
        return;
    const uint32_t ones = F24_FRAC_MASK;
    for (uint32_t k = 0; k < 4; k++) {
        const uint32_t a = fmk(0, e, k == 3 ? ones : k);
        put(s, a, fmk(0, half_exp, 0));            /* exact tie */
        put(s, a, fmk(0, half_exp, 1));            /* just above the tie */
        put(s, a, fmk(0, half_exp - 1, ones));     /* just below the tie */
        put(s, a | F24_SIGN_BIT, fmk(1, half_exp, 0));
        put(s, a, fmk(1, half_exp, 0));            /* tie while subtracting */
    }
}

/* Significand pairs whose product sits just below (rounding carries into the next binade) or
 * just above a power of two, with the result in binade result_exp (0: rounds up to the
 * smallest normal or flushes; EXP_MAX-1: rounds up to overflow). */
static void mul_carry_cases(sink *s, int32_t result_exp)
{
    const int32_t eb = result_exp < 1 ? 1 : result_exp, ea = F24_BIAS + result_exp - eb;
    for (uint32_t k = 0; k < 16; k++) {
        const uint32_t siga = (1u << F24_MAN_BITS) | ((k * 0x9E3779B9u) & F24_FRAC_MASK);
        const uint64_t target = 1ull << (2 * F24_MAN_BITS + 1);
        const uint32_t sigb = (uint32_t)((target + siga - 1) / siga) - (k & 1u);
        if (sigb >> (F24_MAN_BITS + 1) || !(sigb >> F24_MAN_BITS))
            continue;
        put(s, fmk(0, ea, siga), fmk(k & 2u ? 1u : 0u, eb, sigb));
    }
}

size_t f24_vec_edges(f24_op op, f24_pair *out, size_t cap)
{
    sink s = { out, cap, 0 };
    const f24_op_info *info = &f24_ops[op];

    if (info->arg == F24_KIND_F32) {
        /* binary32 specials and values at the fp24 range and rounding boundaries */
        const uint32_t drop = 23 - F24_MAN_BITS, tie = (1u << drop) >> 1;
        const int32_t lo = 127 - F24_BIAS + 1, hi = 127 + F24_BIAS;
        const uint32_t v[] = {
            0, 1, 0x7FFFFF, 0x800000, 0x3F800000, 0x3F800000 | tie, 0x3F800000 | tie | (1u << drop),
            0x3F800000 | (tie ? tie + 1 : 0), 0x3FFFFFFF, 0x7F7FFFFF, 0x7F800000, 0x7FC00000, 0x7F800001,
            (uint32_t)lo << 23, ((uint32_t)lo - 1) << 23 | 0x7FFFFF, ((uint32_t)lo - 2) << 23,
            (uint32_t)hi << 23 | 0x7FFFFF, (uint32_t)hi << 23 | (0x7FFFFF ^ tie), ((uint32_t)hi + 1) << 23,
        };
        for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
            put(&s, v[i], 0);
            put(&s, v[i] | 0x80000000u, 0);
        }
        return s.n;
    }
    if (info->arg == F24_KIND_I32) {
        for (int k = 0; k < 31; k++) {
            const uint32_t p = 1u << k;
            const uint32_t v[] = { p, p - 1, p + 1, p | (p >> (F24_MAN_BITS + 1)), p | (p >> (F24_MAN_BITS + 2)) };
            for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
                put(&s, v[i], 0);
                put(&s, 0u - v[i], 0);
            }
        }
        put(&s, 0x80000000u, 0);
        put(&s, 0x7FFFFFFFu, 0);
        return s.n;
    }

    uint32_t v[64];
    const size_t nv = special_values(v);
    if (info->arity == 1) {
        for (size_t i = 0; i < nv; i++)
            put(&s, v[i], 0);
    } else {
        for (size_t i = 0; i < nv; i++)
            for (size_t j = 0; j < nv; j++)
                put(&s, v[i], v[j]);
    }
    if (op == F24_OP_ADD || op == F24_OP_SUB) {
        const int32_t exps[] = { 1, 2, F24_BIAS, F24_EXP_MAX - 1 };
        for (size_t i = 0; i < sizeof exps / sizeof exps[0]; i++)
            add_rounding_cases(&s, exps[i]);
        for (uint32_t k = 0; k < 4; k++) /* cancellation to below the smallest normal */
            put(&s, fmk(0, 1, k + 1), fmk(op == F24_OP_ADD, 1, k));
    }
    if (op == F24_OP_MUL) {
        for (uint32_t k = 1; k <= F24_MAN_BITS; k++) /* (1+2^-k)(1+2^-(M+1-k)) = tie */
            put(&s, fmk(0, F24_BIAS, 1u << (F24_MAN_BITS - k)), fmk(0, F24_BIAS, 1u << (k - 1)));
        const int32_t exps[] = { 0, 1, F24_BIAS, F24_EXP_MAX - 2, F24_EXP_MAX - 1 };
        for (size_t i = 0; i < sizeof exps / sizeof exps[0]; i++)
            mul_carry_cases(&s, exps[i]);
    }
    if (op == F24_OP_DIV) {
        for (uint32_t k = 0; k < 8; k++) { /* quotients near the range limits and near one */
            put(&s, fmk(0, 1, k), fmk(0, F24_BIAS, F24_FRAC_MASK - k));
            put(&s, fmk(0, F24_EXP_MAX - 1, F24_FRAC_MASK - k), fmk(0, F24_BIAS - 1, F24_FRAC_MASK - k));
            put(&s, fmk(0, F24_BIAS, k), fmk(0, F24_BIAS, k + 1));
        }
    }
    if (op == F24_OP_SQRT) /* exact squares */
        for (int32_t k = 1; k < 64 && k * k < (1 << (F24_MAN_BITS + 1)); k++)
            put(&s, f24_from_i32(k * k), 0);
    return s.n;
}

/* ---- random operands --------------------------------------------------------------------- */

/* A random field of 1..32 bits with TestFloat-like patterns. */
static uint32_t rnd_frac(f24_rng *rng, int bits)
{
    const uint64_t mask = (1ull << bits) - 1u;
    const uint64_t r = f24_rng_next(rng);
    const uint32_t run = rnd_below(rng, (uint32_t)bits + 1);
    switch (rnd_below(rng, 8)) {
    case 0: return 0;
    case 1: return (uint32_t)mask;
    case 2: return (uint32_t)(1ull << rnd_below(rng, (uint32_t)bits));  /* one bit */
    case 3: return (uint32_t)((mask << run) & mask);                      /* ones at the top */
    case 4: return (uint32_t)((1ull << run) - 1u);                        /* ones at the bottom */
    case 5: return (uint32_t)(r & f24_rng_next(rng) & mask);             /* sparse */
    default: return (uint32_t)(r & mask);
    }
}

static int32_t rnd_exp(f24_rng *rng, int32_t bias, int32_t max)
{
    const int32_t picks[] = { 0, 1, 2, bias - 1, bias, bias + 1, max - 2, max - 1, max };
    if (rnd_below(rng, 2))
        return (int32_t)rnd_below(rng, (uint32_t)max + 1);
    return picks[rnd_below(rng, sizeof picks / sizeof picks[0])];
}

static uint32_t rnd_f24(f24_rng *rng)
{
    if (rnd_below(rng, 8) < 3)
        return (uint32_t)f24_rng_next(rng) & F24_MASK;
    return fmk((uint32_t)f24_rng_next(rng) & 1u, rnd_exp(rng, F24_BIAS, F24_EXP_MAX),
               rnd_frac(rng, F24_MAN_BITS));
}

/* b close to a: same or neighbouring exponent, so adders cancel and comparisons tie. */
static uint32_t rnd_near(f24_rng *rng, uint32_t a)
{
    int32_t e = f24_exp(a) + (int32_t)rnd_below(rng, 5) - 2;
    e = e < 0 ? 0 : e > F24_EXP_MAX ? F24_EXP_MAX : e;
    uint32_t frac = f24_frac(a) + rnd_below(rng, 5) - 2u;
    if (rnd_below(rng, 2))
        frac = rnd_frac(rng, F24_MAN_BITS);
    return fmk((uint32_t)f24_rng_next(rng) & 1u, e, frac);
}

f24_pair f24_vec_random(f24_op op, f24_rng *rng)
{
    const f24_op_info *info = &f24_ops[op];
    if (info->arg == F24_KIND_F32) {
        if (rnd_below(rng, 4) == 0)
            return (f24_pair){ (uint32_t)f24_rng_next(rng), 0 };
        const uint32_t e = (uint32_t)(127 + rnd_exp(rng, F24_BIAS, F24_EXP_MAX) - F24_BIAS) & 0xFFu;
        return (f24_pair){ ((uint32_t)f24_rng_next(rng) & 0x80000000u) | e << 23 | rnd_frac(rng, 23), 0 };
    }
    if (info->arg == F24_KIND_I32) {
        const uint32_t bits = rnd_below(rng, 33);
        const uint32_t mag = bits == 32 ? (uint32_t)f24_rng_next(rng) : rnd_frac(rng, (int)bits + 1) >> 1;
        return (f24_pair){ rnd_below(rng, 2) ? 0u - mag : mag, 0 };
    }
    const uint32_t a = rnd_f24(rng);
    if (info->arity == 1)
        return (f24_pair){ a, 0 };
    return (f24_pair){ a, rnd_below(rng, 4) == 0 ? rnd_near(rng, a) : rnd_f24(rng) };
}
