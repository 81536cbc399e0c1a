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

/* malloc(bytes) with huge_pages_advise; NULL if memory ran out. */
void *huge_pages_malloc(size_t bytes);

/* realloc(p, bytes) with huge_pages_advise over the whole new block (the part p held is already
 * mapped and keeps its pages); NULL if memory ran out (p is then unchanged). */
void *huge_pages_realloc(void *p, size_t bytes);

/* Grows the main thread's malloc heap (glibc) by about `bytes` of address space advised for huge
 * pages (no memory is used until touched), serves blocks up to 32 MB from it and never gives its
 * top back: the glTF loader's vectors (tinygltf's file and buffer copies, the accessors) and the
 * other buffers of the main thread then take one fault per 2 MB, and reuse what they freed.
 * saarcor calls it first thing with 256 MB: `saarcor info gallery_ccby_503k.glb` 36,600 ->
 * 13,300 page faults, 3.30 -> 2.95 s of CPU (perf stat, a loaded machine). The price: the
 * process keeps its peak heap until it exits. Nothing under AddressSanitizer. */
void huge_pages_heap(size_t bytes);

#ifdef __cplusplus
}
#endif

#endif
