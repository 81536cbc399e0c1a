/*
 * libsaarcor_mpi.so: the MPI work distributor described in saarcor_mpi.h. Messages: rank 0 sends
 * an item number (uint32, tag ITEM; SAARCOR_MPI_STOP ends the worker); a worker answers with the
 * item number followed by the result bytes (tag RESULT). The controller probes for any result,
 * so faster workers get more items (dynamic distribution). At the end every worker sends its
 * times, gathered on rank 0. SAARCOR_MPI_FAULT=R:N makes worker rank R die (SIGKILL) after N
 * items: the fault injection of tests/test_mpi.sh.
 */
#define _GNU_SOURCE
#include "saarcor_mpi.h"

#include <mpi.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { TAG_ITEM = 1, TAG_RESULT = 2 };
#define SAARCOR_MPI_STOP UINT32_MAX

/* Worker rank that dies, and after how many items; -1 if no fault is asked for. */
static int fault_rank(long *after)
{
    const char *f = getenv("SAARCOR_MPI_FAULT");
    int r;
    if (!f || sscanf(f, "%d:%ld", &r, after) != 2)
        return -1;
    return r;
}

static void send_item(uint32_t item, int to, saarcor_mpi_report *rep)
{
    MPI_Send(&item, 1, MPI_UINT32_T, to, TAG_ITEM, MPI_COMM_WORLD);
    rep->bytes_to_workers += sizeof item;
    rep->messages++;
}

/* Waits for any worker's result. Polls with short sleeps instead of MPI_Probe, which spins a
 * core: the controller shares its node with workers (one core each), and a controller that spins
 * takes their time. 100 us is far below an item's time and costs nothing measurable. */
static void wait_result(MPI_Status *st)
{
    int flag = 0;
    for (;;) {
        MPI_Iprobe(MPI_ANY_SOURCE, TAG_RESULT, MPI_COMM_WORLD, &flag, st);
        if (flag)
            return;
        nanosleep(&(struct timespec){ 0, 100000 }, NULL);
    }
}

/* Rank 0: hands out items, takes results. */
static int controller(const saarcor_mpi_work *w, saarcor_mpi_report *rep, char *err, size_t n)
{
    const int workers = rep->ranks - 1;
    unsigned char *buf = malloc(sizeof(uint32_t) + w->result_max);
    if (!buf) {
        snprintf(err, n, "out of memory for a result buffer of %zu bytes", w->result_max);
        return -1;
    }
    const double t0 = MPI_Wtime();
    uint32_t next = 0, done = 0;
    for (int d = 0; d < SAARCOR_MPI_DEPTH; d++)
        for (int r = 1; r <= workers && next < w->n_items; r++)
            send_item(next++, r, rep);
    while (done < w->n_items) {
        MPI_Status st;
        int count;
        wait_result(&st);
        MPI_Get_count(&st, MPI_BYTE, &count);
        MPI_Recv(buf, count, MPI_BYTE, st.MPI_SOURCE, TAG_RESULT, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        rep->bytes_from_workers += (uint64_t)count;
        rep->messages++;
        uint32_t item;
        memcpy(&item, buf, sizeof item);
        if (w->take(w->ctx, item, buf + sizeof item, (size_t)count - sizeof item, st.MPI_SOURCE) != 0)
            MPI_Abort(MPI_COMM_WORLD, 4); /* take() printed why */
        done++;
        if (next < w->n_items)
            send_item(next++, st.MPI_SOURCE, rep);
    }
    rep->wall_seconds = MPI_Wtime() - t0;
    for (int r = 1; r <= workers; r++)
        send_item(SAARCOR_MPI_STOP, r, rep);
    free(buf);
    return 0;
}

/* Ranks 1..: items until told to stop; times[0] work, times[1] communication. */
static void worker(const saarcor_mpi_work *w, int rank, double times[2])
{
    unsigned char *buf = malloc(sizeof(uint32_t) + w->result_max);
    if (!buf) {
        fprintf(stderr, "saarcor mpi: rank %d: error: out of memory for a result of %zu bytes\n", rank, w->result_max);
        MPI_Abort(MPI_COMM_WORLD, 4);
    }
    long after = 0, items = 0;
    const int dies = fault_rank(&after) == rank;
    for (;;) {
        uint32_t item;
        double t = MPI_Wtime();
        MPI_Recv(&item, 1, MPI_UINT32_T, 0, TAG_ITEM, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        times[1] += MPI_Wtime() - t;
        if (item == SAARCOR_MPI_STOP)
            break;
        if (dies && items >= after)
            raise(SIGKILL); /* fault injection: a worker dies without a word */
        t = MPI_Wtime();
        const long size = w->work(w->ctx, item, buf + sizeof item);
        times[0] += MPI_Wtime() - t;
        if (size < 0)
            MPI_Abort(MPI_COMM_WORLD, 4); /* work() printed why */
        memcpy(buf, &item, sizeof item);
        t = MPI_Wtime();
        MPI_Send(buf, (int)(sizeof item + (size_t)size), MPI_BYTE, 0, TAG_RESULT, MPI_COMM_WORLD);
        times[1] += MPI_Wtime() - t;
        items++;
    }
    free(buf);
}

int saarcor_mpi_run(int abi, const saarcor_mpi_work *w, saarcor_mpi_report *rep, char *err, size_t n)
{
    memset(rep, 0, sizeof *rep);
    if (abi != SAARCOR_MPI_ABI) {
        snprintf(err, n, "libsaarcor_mpi.so has interface %d, the program %d: rebuild with make mpi", SAARCOR_MPI_ABI, abi);
        return -1;
    }
    int provided;
    MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided); /* host threads render, main thread talks */
    MPI_Comm_rank(MPI_COMM_WORLD, &rep->rank);
    MPI_Comm_size(MPI_COMM_WORLD, &rep->ranks);
    if (rep->ranks < 2) {
        snprintf(err, n, "needs at least 2 ranks (rank 0 hands out work, the others do it): run it under "
                         "mpirun -np N with N >= 2");
        MPI_Finalize();
        return -1;
    }
    double times[2] = { 0, 0 };
    int rc = 0;
    if (rep->rank == 0)
        rc = controller(w, rep, err, n);
    else
        worker(w, rep->rank, times);
    double *all = rep->rank == 0 ? calloc(2 * (size_t)rep->ranks, sizeof *all) : NULL;
    MPI_Gather(times, 2, MPI_DOUBLE, all, 2, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    for (int r = 1; all && r < rep->ranks; r++) {
        rep->work_seconds += all[2 * r];
        rep->comm_seconds += all[2 * r + 1];
        rep->comm_seconds_max = all[2 * r + 1] > rep->comm_seconds_max ? all[2 * r + 1] : rep->comm_seconds_max;
    }
    rep->bytes_from_workers += rep->rank == 0 ? (uint64_t)(rep->ranks - 1) * sizeof times : 0;
    free(all);
    MPI_Finalize();
    return rc;
}
