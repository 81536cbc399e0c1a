/*
 * Finding and loading build/libsaarcor_mpi.so (tb/mpi/saarcor_mpi.h) at run time, only when a
 * command is given --mpi: the program itself never links libmpi, so it runs where Open MPI is
 * not installed. The library is looked up in $SAARCOR_MPI_LIB, else next to this program, else
 * two folders up (build/w/eEmM/saarcor -> build/).
 */
#ifndef SAARCOR_MPI_LOAD_H
#define SAARCOR_MPI_LOAD_H

#include "saarcor_mpi.h"

/* saarcor_mpi_run of the library, or NULL after a one-line error "saarcor CMD: error: ...". */
saarcor_mpi_run_fn mpi_load(const char *cmd);

#endif
