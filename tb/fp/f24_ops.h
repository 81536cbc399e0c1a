/*
 * Host-side table of the fp24 operations: name, operand and result kinds, and the three
 * implementations every check compares: the integer hardware path (hls/fp24), the fast
 * simulation path (f24_fast.h) and the correctly rounded MPFR reference (f24_mpfr.c).
 * Used by `saarcor f24gen`, `saarcor f24verify`, `saarcor f24` and tests/test_f24.c.
 */
#ifndef SAARCOR_F24_OPS_H
#define SAARCOR_F24_OPS_H

#include <stdint.h>

typedef enum {
    F24_OP_ADD, F24_OP_SUB, F24_OP_MUL, F24_OP_DIV, F24_OP_SQRT,
    F24_OP_LT, F24_OP_LE, F24_OP_EQ, F24_OP_UNORDERED, F24_OP_MIN, F24_OP_MAX,
    F24_OP_NEG, F24_OP_ABS, F24_OP_FROM_F32, F24_OP_TO_F32, F24_OP_FROM_I32, F24_OP_TO_I32,
    F24_OP_COUNT
} f24_op;

/* What a 32-bit operand or result word holds. */
typedef enum { F24_KIND_F24, F24_KIND_F32, F24_KIND_I32, F24_KIND_BOOL } f24_kind;

typedef uint32_t (*f24_impl)(uint32_t a, uint32_t b);

typedef struct {
    const char *name;
    int arity;         /* 1 or 2; unary operations ignore b */
    f24_kind arg;      /* kind of a (and b) */
    f24_kind result;
    f24_impl hw;       /* integer hardware reference, hls/fp24 */
    f24_impl fast;     /* host fast path, tb/fp/f24_fast.h */
} f24_op_info;

extern const f24_op_info f24_ops[F24_OP_COUNT];

/* Operation by name ("add", "from_f32", ...), or -1. */
int f24_op_find(const char *name);

/* Correctly rounded reference (GNU MPFR with the format's precision and exponent range). */
uint32_t f24_mpfr(f24_op op, uint32_t a, uint32_t b);

/* Decimal text ("1.5", "-2e-3", "inf", "nan") rounded correctly to fp24; 0 if not a number. */
int f24_mpfr_parse(const char *text, uint32_t *out);

/* Hex digits needed to print a word of the given kind (TestFloat-style vectors). */
int f24_kind_hex_digits(f24_kind kind);

#endif
