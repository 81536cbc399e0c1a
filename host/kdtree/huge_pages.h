/*
 * Transparent huge pages for the host build's large buffers. The first touch of a fresh 4 KB page
 * costs a page fault; on this project's 2-CPU virtual machine (paravirtualized faults) the
 * gallery_ccby_503k.glb build took about 52,000 of them, 8% of its CPU samples (triangle
 * transformations, the kd builder's event lists, the memory image). Where the kernel gives huge
 * pages on request (transparent_hugepage = madvise), a 2 MB page takes one fault instead of 512.
 * Only the kernel's page mapping changes: the buffers' contents and every result are the same.
 */
#ifndef SAARCOR_HUGE_PAGES_H
#define SAARCOR_HUGE_PAGES_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Asks for huge pages over the 2 MB-aligned part of [p, p + bytes) if that is at least 2 MB
 * (a hint: ignored where unsupported). Call it before the buffer is first written. */
void huge_pages_advise(void *p, size_t bytes);

/* malloc(bytes) with huge_pages_advise; NULL if memory ran out. From 2 MB on, the block is
 * aligned to 2 MB and rounded up to a multiple of it (posix_memalign), so that all of it gets
 * huge pages; free() releases it. */
void *huge_pages_malloc(size_t bytes);

/* realloc(p, bytes) for p from malloc or huge_pages_malloc; NULL if memory ran out (p is then
 * unchanged). Below 2 MB realloc with huge_pages_advise; from 2 MB on p itself if it has room
 * (it is not shrunk), else a new huge_pages_malloc block that p is copied into. */
void *huge_pages_realloc(void *p, size_t bytes);

#ifdef __cplusplus
}
#endif

#endif
