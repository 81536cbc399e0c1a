/*
 * VmRSS and VmHWM of this process from /proc/self/status (Linux; see proc_mem.h). Parsed here
 * rather than with getrusage: ru_maxrss gives only the peak, the long-run check wants both.
 */
#include "proc_mem.h"

#include <stdio.h>
#include <string.h>

int proc_mem_read(proc_mem *m)
{
    m->rss_kb = m->peak_rss_kb = -1;
    FILE *f = fopen("/proc/self/status", "r");
    if (!f)
        return -1;
    char line[256];
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "VmRSS:", 6) == 0)
            sscanf(line + 6, "%ld", &m->rss_kb);
        else if (strncmp(line, "VmHWM:", 6) == 0)
            sscanf(line + 6, "%ld", &m->peak_rss_kb);
    }
    fclose(f);
    return m->rss_kb >= 0 && m->peak_rss_kb >= 0 ? 0 : -1;
}
