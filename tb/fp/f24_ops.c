/* Operation table: adapters from the typed fp24 API to uniform 32-bit in/out functions. */
#include "f24_ops.h"

#include <string.h>

#include "f24.h"
#include "f24_fast.h"

#define BIN(fn) static uint32_t fn##_w(uint32_t a, uint32_t b) { return (uint32_t)fn(a, b); }
#define UN(fn) static uint32_t fn##_w(uint32_t a, uint32_t b) { (void)b; return (uint32_t)fn(a); }

BIN(f24_add) BIN(f24_sub) BIN(f24_mul) BIN(f24_div) UN(f24_sqrt)
BIN(f24_lt) BIN(f24_le) BIN(f24_eq) BIN(f24_unordered) BIN(f24_min) BIN(f24_max)
UN(f24_neg) UN(f24_abs) UN(f24_from_f32) UN(f24_to_f32)
BIN(f24_fast_add) BIN(f24_fast_sub) BIN(f24_fast_mul) BIN(f24_fast_div) UN(f24_fast_sqrt)
UN(f24_fast_from_f32)

static uint32_t f24_from_i32_w(uint32_t a, uint32_t b) { (void)b; return f24_from_i32((int32_t)a); }
static uint32_t f24_fast_from_i32_w(uint32_t a, uint32_t b) { (void)b; return f24_fast_from_i32((int32_t)a); }
static uint32_t f24_to_i32_w(uint32_t a, uint32_t b) { (void)b; return (uint32_t)f24_to_i32(a); }

/* The fast path reuses the integer comparisons, min/max, sign operations and to_f32. */
#define OP(name, arity, arg, res, hw, fast) { name, arity, arg, res, hw##_w, fast##_w }
const f24_op_info f24_ops[F24_OP_COUNT] = {
    [F24_OP_ADD] = OP("add", 2, F24_KIND_F24, F24_KIND_F24, f24_add, f24_fast_add),
    [F24_OP_SUB] = OP("sub", 2, F24_KIND_F24, F24_KIND_F24, f24_sub, f24_fast_sub),
    [F24_OP_MUL] = OP("mul", 2, F24_KIND_F24, F24_KIND_F24, f24_mul, f24_fast_mul),
    [F24_OP_DIV] = OP("div", 2, F24_KIND_F24, F24_KIND_F24, f24_div, f24_fast_div),
    [F24_OP_SQRT] = OP("sqrt", 1, F24_KIND_F24, F24_KIND_F24, f24_sqrt, f24_fast_sqrt),
    [F24_OP_LT] = OP("lt", 2, F24_KIND_F24, F24_KIND_BOOL, f24_lt, f24_lt),
    [F24_OP_LE] = OP("le", 2, F24_KIND_F24, F24_KIND_BOOL, f24_le, f24_le),
    [F24_OP_EQ] = OP("eq", 2, F24_KIND_F24, F24_KIND_BOOL, f24_eq, f24_eq),
    [F24_OP_UNORDERED] = OP("unordered", 2, F24_KIND_F24, F24_KIND_BOOL, f24_unordered, f24_unordered),
    [F24_OP_MIN] = OP("min", 2, F24_KIND_F24, F24_KIND_F24, f24_min, f24_min),
    [F24_OP_MAX] = OP("max", 2, F24_KIND_F24, F24_KIND_F24, f24_max, f24_max),
    [F24_OP_NEG] = OP("neg", 1, F24_KIND_F24, F24_KIND_F24, f24_neg, f24_neg),
    [F24_OP_ABS] = OP("abs", 1, F24_KIND_F24, F24_KIND_F24, f24_abs, f24_abs),
    [F24_OP_FROM_F32] = OP("from_f32", 1, F24_KIND_F32, F24_KIND_F24, f24_from_f32, f24_fast_from_f32),
    [F24_OP_TO_F32] = OP("to_f32", 1, F24_KIND_F24, F24_KIND_F32, f24_to_f32, f24_to_f32),
    [F24_OP_FROM_I32] = OP("from_i32", 1, F24_KIND_I32, F24_KIND_F24, f24_from_i32, f24_fast_from_i32),
    [F24_OP_TO_I32] = OP("to_i32", 1, F24_KIND_F24, F24_KIND_I32, f24_to_i32, f24_to_i32),
};

int f24_op_find(const char *name)
{
    for (int i = 0; i < F24_OP_COUNT; i++)
        if (strcmp(f24_ops[i].name, name) == 0)
            return i;
    return -1;
}

int f24_kind_hex_digits(f24_kind kind)
{
    switch (kind) {
    case F24_KIND_F24: return (F24_WIDTH + 3) / 4;
    case F24_KIND_BOOL: return 1;
    default: return 8;
    }
}
