/*
 * The MPI work distributor of saarcor (build/libsaarcor_mpi.so, `make mpi`), and the small
 * interface through which the program drives it. Why a separate library: build/saarcor must run
 * without Open MPI installed; `render --mpi` and `jobs --mpi` dlopen() this library (mpi_load.h),
 * which alone links libmpi. Why callbacks: the library knows nothing about rendering. The program
 * describes the job as N independent work items with a worker function (item -> result bytes) and
 * a controller function (result bytes -> into the image, the statistics, the files), so no render
 * logic exists twice and the same distributor runs tiles, frames and shell jobs.
 *
 * Roles: rank 0 is the controller (the paper's ray generation controller, one level up): it hands
 * out item numbers dynamically, at most SAARCOR_MPI_DEPTH outstanding per worker, in item order to
 * whichever worker returns a result, and takes the results as they come. Ranks 1..N-1 are workers.
 * Every rank runs the same program on the same input and sets up the same state itself (scene,
 * memory image), so only item numbers and results cross the network. A worker that dies ends the
 * whole job (Open MPI's errors-are-fatal; mpirun aborts the job when a process exits early).
 */
#ifndef SAARCOR_MPI_H
#define SAARCOR_MPI_H

#include <stddef.h>
#include <stdint.h>

#define SAARCOR_MPI_ABI 1   /* bumped whenever the structs below change */
#define SAARCOR_MPI_DEPTH 2 /* items outstanding per worker: the next one waits while it works */

typedef struct {
    uint32_t n_items;
    size_t result_max; /* bytes of the largest result */
    void *ctx;
    /* worker: does item `item`, writes its result to `result` (<= result_max bytes); returns the
     * result's size, or -1 after printing a one-line error (the job is aborted) */
    long (*work)(void *ctx, uint32_t item, void *result);
    /* controller: takes the result of `item` computed by worker rank `rank`; 0, or -1 after
     * printing a one-line error (the job is aborted) */
    int (*take)(void *ctx, uint32_t item, const void *result, size_t size, int rank);
} saarcor_mpi_work;

typedef struct {
    int rank, ranks;           /* this process; all processes (workers = ranks - 1) */
    double wall_seconds;       /* from the first item handed out to the last result taken (rank 0) */
    double work_seconds;       /* summed over workers: inside work() */
    double comm_seconds;       /* summed over workers: in MPI calls (sending results, waiting for items) */
    double comm_seconds_max;   /* the worker with the most */
    uint64_t bytes_to_workers; /* item messages */
    uint64_t bytes_from_workers; /* result messages */
    uint64_t messages;
} saarcor_mpi_report;

/* Initializes MPI, runs the job (controller on rank 0, worker elsewhere), gathers the report on
 * rank 0 and finalizes MPI. 0 on success (on every rank); otherwise non-zero with a one-line
 * message in err. Needs at least 2 ranks. Only rank 0 calls take(); only workers call work(). */
typedef int (*saarcor_mpi_run_fn)(int abi, const saarcor_mpi_work *w, saarcor_mpi_report *rep, char *err, size_t n);
int saarcor_mpi_run(int abi, const saarcor_mpi_work *w, saarcor_mpi_report *rep, char *err, size_t n);

#endif
