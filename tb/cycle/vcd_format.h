/* vcd_format.h: the two pieces of IEEE 1364 VCD text that cycle mode's waveforms
 * (tb/cycle/cycle_trace.c) and the RTL harness's (rtl/tb/tb_vcd.h) must write alike, so that a
 * viewer and tests/vcd_reader.py read both files the same way: a signal's identifier and a value
 * change. Header-only (static inline) for the C simulator and the C++ harness. */
#ifndef SAARCOR_VCD_FORMAT_H
#define SAARCOR_VCD_FORMAT_H

#include <stdint.h>
#include <stdio.h>

#define VCD_X UINT64_MAX /* an undefined value (a unit's thread_id while it is idle) */
#define VCD_ID_CHARS 12  /* room for the identifier of any 64-bit signal number and its end */

/* Identifier of signal number n (0 is the clock, "!"): printable characters but '#' and '$',
 * which some readers take for a timestamp or a keyword at the start of a token. */
static inline void vcd_id(uint64_t n, char id[VCD_ID_CHARS])
{
    static const char digits[] = "!\"%&'()*+,-./0123456789:;<=>?@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_`"
                                 "abcdefghijklmnopqrstuvwxyz{|}~";
    const uint64_t base = sizeof digits - 1;
    int k = 0;
    do {
        id[k++] = digits[n % base];
        n /= base;
    } while (n);
    id[k] = 0;
}

/* The change of a signal of `width` bits to v (VCD_X: undefined), in the shortest binary form. */
static inline void vcd_value(FILE *f, uint32_t width, uint64_t v, const char *id)
{
    if (width == 1) {
        fprintf(f, "%c%s\n", v == VCD_X ? 'x' : v ? '1' : '0', id);
        return;
    }
    if (v == VCD_X) {
        fprintf(f, "bx %s\n", id);
        return;
    }
    char b[65];
    int n = 0, i = 63;
    while (i > 0 && !(v >> i & 1))
        i--;
    for (; i >= 0; i--)
        b[n++] = (char)('0' + (v >> i & 1));
    b[n] = 0;
    fprintf(f, "b%s %s\n", b, id);
}

#endif
