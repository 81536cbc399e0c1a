/* Transparent huge pages for large buffers (huge_pages.h). */
#define _DEFAULT_SOURCE /* madvise, MADV_HUGEPAGE */
#include "huge_pages.h"

#include <malloc.h>
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

void huge_pages_heap(size_t bytes)
{
#ifdef __SANITIZE_ADDRESS__
    (void)bytes; /* ASan's allocator ignores mallopt, and would poison the blocks for nothing */
#else
    enum { BLOCK = 16u << 20, MAX_BLOCKS = 64 };
    (void)mallopt(M_MMAP_THRESHOLD, 32 << 20); /* glibc's largest: blocks up to 32 MB from the heap */
    (void)mallopt(M_TRIM_THRESHOLD, 1 << 30);  /* above bytes: the advised top is never given back */
    /* the heap grown by blocks that follow each other, advised in one range, then freed to its top */
    void *block[MAX_BLOCKS];
    size_t n = 0;
    for (; n < MAX_BLOCKS && n * BLOCK < bytes; n++)
        if (!(block[n] = malloc(BLOCK - 64)))
            break;
    char *lo = NULL, *hi = NULL;
    for (size_t i = 0; i < n; i++) {
        char *p = block[i];
        lo = !lo || p < lo ? p : lo;
        hi = !hi || p + BLOCK - 64 > hi ? p + BLOCK - 64 : hi;
    }
    if (n)
        huge_pages_advise(lo, (size_t)(hi - lo));
    for (size_t i = n; i-- > 0;)
        free(block[i]);
#endif
}
