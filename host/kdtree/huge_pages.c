/* Transparent huge pages for large buffers (huge_pages.h). */
#define _DEFAULT_SOURCE /* madvise, MADV_HUGEPAGE */
#include "huge_pages.h"

#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>

enum { HUGE_PAGE = 2u << 20 };

void huge_pages_advise(void *p, size_t bytes)
{
#ifdef MADV_HUGEPAGE
    const uintptr_t lo = ((uintptr_t)p + HUGE_PAGE - 1) & ~(uintptr_t)(HUGE_PAGE - 1);
    const uintptr_t hi = ((uintptr_t)p + bytes) & ~(uintptr_t)(HUGE_PAGE - 1);
    if (p && hi > lo)
        (void)madvise((void *)lo, hi - lo, MADV_HUGEPAGE); /* a hint: a refusal changes nothing */
#else
    (void)p;
    (void)bytes;
#endif
}

void *huge_pages_malloc(size_t bytes)
{
    void *p = malloc(bytes);
    huge_pages_advise(p, bytes);
    return p;
}

void *huge_pages_realloc(void *p, size_t bytes)
{
    void *q = realloc(p, bytes);
    huge_pages_advise(q, bytes);
    return q;
}
