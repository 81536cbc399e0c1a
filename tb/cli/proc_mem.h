/*
 * The host program's own memory use, for long-run checks (render --stats writes it per frame,
 * make bench-longrun and tests/test_longrun.sh compare frame 10 with frame 1000): resident set
 * size now (VmRSS) and its peak so far (VmHWM) from /proc/self/status, in KiB.
 */
#ifndef SAARCOR_PROC_MEM_H
#define SAARCOR_PROC_MEM_H

typedef struct {
    long rss_kb, peak_rss_kb; /* -1 where /proc does not tell */
} proc_mem;

/* Fills m; 0 if both values were read, -1 otherwise. */
int proc_mem_read(proc_mem *m);

#endif
