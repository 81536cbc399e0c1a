/* Run-time loading of the MPI distributor: see mpi_load.h. */
#define _GNU_SOURCE
#include "mpi_load.h"

#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

/* Candidate paths of the library, in lookup order; returns how many. */
static int candidates(char paths[3][1200])
{
    int n = 0;
    const char *env = getenv("SAARCOR_MPI_LIB");
    if (env && *env) {
        snprintf(paths[n++], 1200, "%s", env);
        return n; /* an explicit choice: no fallback that could hide a wrong path */
    }
    char self[1024];
    const ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0)
        return 0;
    self[len] = 0;
    *strrchr(self, '/') = 0;
    snprintf(paths[n++], 1200, "%s/libsaarcor_mpi.so", self);
    snprintf(paths[n++], 1200, "%s/../../libsaarcor_mpi.so", self);
    return n;
}

saarcor_mpi_run_fn mpi_load(const char *cmd)
{
    char paths[3][1200], why[512] = "not found next to the program";
    const int n = candidates(paths);
    for (int i = 0; i < n; i++) {
        if (access(paths[i], F_OK) != 0 && i + 1 < n)
            continue;
        /* RTLD_GLOBAL: Open MPI's own plugins resolve libmpi's symbols through the global scope */
        void *lib = dlopen(paths[i], RTLD_NOW | RTLD_GLOBAL);
        if (!lib) {
            snprintf(why, sizeof why, "%s", dlerror());
            break;
        }
        saarcor_mpi_run_fn run = (saarcor_mpi_run_fn)(uintptr_t)dlsym(lib, "saarcor_mpi_run");
        if (run)
            return run;
        snprintf(why, sizeof why, "%.400s has no saarcor_mpi_run", paths[i]);
        break;
    }
    cli_error(cmd, "--mpi: cannot load libsaarcor_mpi.so (build it with 'make mpi'; needs Open MPI, "
                   "libopenmpi-dev): %s", why);
    return NULL;
}
