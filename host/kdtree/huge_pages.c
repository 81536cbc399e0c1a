/* Transparent huge pages for large buffers (huge_pages.h). */
#define _DEFAULT_SOURCE /* madvise, MADV_HUGEPAGE */
#include "huge_pages.h"

#include <malloc.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
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

/* A block of at least one huge page starts on a huge-page boundary and ends on one: malloc's
 * blocks start anywhere, and the 4 KB pages of their unaligned head and tail (up to 4 MB of a
 * block) took half of the gallery's page faults. The rounding adds less than one huge page of
 * address space, which is touched only as far as the buffer is used. */
static size_t huge_size(size_t bytes)
{
    return bytes >= HUGE_PAGE && bytes <= SIZE_MAX - HUGE_PAGE ? (bytes + HUGE_PAGE - 1) & ~(size_t)(HUGE_PAGE - 1) : 0;
}

void *huge_pages_malloc(size_t bytes)
{
    const size_t size = huge_size(bytes);
    void *p = NULL;
    if (!size)
        p = malloc(bytes);
    else if (posix_memalign(&p, HUGE_PAGE, size) != 0)
        p = NULL;
    huge_pages_advise(p, size ? size : bytes);
    return p;
}

void *huge_pages_realloc(void *p, size_t bytes)
{
    if (!huge_size(bytes)) { /* small: as malloc has it */
        void *q = realloc(p, bytes);
        huge_pages_advise(q, bytes);
        return q;
    }
    const size_t have = p ? malloc_usable_size(p) : 0;
    if (have >= bytes)
        return p;
    void *q = huge_pages_malloc(bytes); /* a fresh aligned block, advised before the copy writes it */
    if (!q)
        return NULL;
    if (p)
        memcpy(q, p, have);
    free(p);
    return q;
}
