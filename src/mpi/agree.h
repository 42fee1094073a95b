/* Internal: what the ranks of an MPI run agree on before they work together (collective.c,
 * inputs.c), also used by the command line under mpirun and by scenes over ranks (scene/ranks.c). */
#ifndef INDENTMAP_MPI_AGREE_H
#define INDENTMAP_MPI_AGREE_H

#include <mpi.h>

/* The same status on every rank: the lowest failing rank's, with its message carried to the
 * others as "rank K: ...". */
int mpi_collective_status(MPI_Comm comm, int status);

/* The exit code of a command under mpirun: on rank 0 the worst (largest) of every rank's code, on the
 * others 0. Rank 0 speaks for all ranks; a non-zero exit of another rank made mpirun stop rank 0 with a
 * signal while it was still reporting, whose notice then joined the message. Collective. */
int mpi_exit_code(MPI_Comm comm, int code);

/* Whether every rank of comm was started alike: the same working folder, the same count arguments
 * args (a command's, after the program's name) and, when file is not NULL, the same bytes in that
 * file (a scene). IM_OK, or IM_EINVAL on every rank with rank 0's message naming the ranks that
 * differ and the first difference (the folder, the argument, or the file); a file that some rank
 * cannot read fails every rank with that rank's message, as mpi_collective_status. Collective. */
int mpi_same_inputs(MPI_Comm comm, int count, char **args, const char *file);

/* Whether every rank of comm reads the same bytes (SHA-256) from each of the count files paths: the
 * same path may name other files on other nodes. keys[i] names what gave paths[i] in messages (a
 * scene key, a command's option; NULL: nothing). IM_OK, or IM_EINVAL on every rank naming the first
 * file that differs, its key and the ranks that read other bytes from it (or, source being what names
 * the files, "the scene", the ranks whose source names another number of files); a file that some
 * rank cannot read fails every rank with that rank's message. Collective. */
int mpi_same_files(MPI_Comm comm, const char *source, int count, const char *const *paths, const char *const *keys);

#endif
