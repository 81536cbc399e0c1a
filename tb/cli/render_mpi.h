/*
 * saarcor render --mpi: the render distributed over MPI ranks by libsaarcor_mpi.so (docs/mpi.md).
 * One frame: the work items are --mpi-tile square tiles; a sequence (--frames A:B): whole frames.
 * Every rank has loaded the scene and built the memory image itself; workers render items with
 * the single-process functions (render_region, cycle_render_region) and send back pixels and
 * counters; rank 0 assembles the image and writes the same files as one process.
 *
 * Cycle statistics of one frame split into tiles are combined as if all boards' pipes were one
 * chip whose ray generation controller hands out the tiles: each tile is simulated on its
 * worker's board of --pipes pipes from empty caches (so its cycles do not depend on which board
 * got it or what it did before), work, unit busy cycles, thread time and memory traffic are
 * summed, and the frame's cycles are those of handing the tiles out in order, each to the board
 * that becomes free first in simulated time (list scheduling over B = ranks - 1 boards). The
 * result depends on the number of boards but not on timing or which rank computed what.
 * Frames of a sequence are each simulated on one board exactly as in one process (caches flushed
 * per frame there too), so their statistics are the single-process ones.
 */
#ifndef SAARCOR_RENDER_MPI_H
#define SAARCOR_RENDER_MPI_H

#include "render.h"
#include "saarcor_mpi.h"

/* Runs the render of ro (b, s: the scene at frame ro->first) on all ranks; rank 0 writes the
 * outputs. A saarcor exit code. */
int render_mpi(render_opts *ro, saarcor_mpi_run_fn run, mi_builder *b, scene *s, const char *scene_name);

#endif
