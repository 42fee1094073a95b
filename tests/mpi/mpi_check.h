/* The MPI test programs' start and checks (mpi_solver.c, mpi_parity.c, mpi_adhesion_indent.c; one include
 * each): a failed check names this process's rank (set by mpi_test_start) and aborts every rank, so that
 * mpirun ends. */
#ifndef INDENTMAP_TESTS_MPI_CHECK_H
#define INDENTMAP_TESTS_MPI_CHECK_H

#include "indentmap/mpi.h"
#include "indentmap/status.h"

#include <mpi.h>
#include <stdio.h>

static int rank;

static inline void check(int ok, const char *what, const char *detail)
{
    if (ok)
        return;
    fprintf(stderr, "rank %d: FAILED %s: %s\n", rank, what, detail);
    MPI_Abort(MPI_COMM_WORLD, 1);
}

static inline void check_status(int status, const char *what) { check(status == IM_OK, what, im_last_error()); }

/* MPI (the threads funnelled through the main one: OpenMP inside each rank), this rank, the library. */
static inline void mpi_test_start(int *argc, char ***argv)
{
    int provided;
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    im_mpi_init();
}

#endif
