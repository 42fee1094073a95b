/* indentmap/scene_ranks.h: a scene's ensembles shared out over MPI ranks (docs/mpi.md, "Ensembles
 * over ranks"). The scene module's entry points that need MPI; their single-process twins are
 * im_scene_run and im_scene_check (scene.h).
 *
 * Installed always; im_scene_run_ranks and im_scene_check_ranks exist only in a library built with MPI (indentmap/mpi_config.h:
 * IM_HAVE_MPI, as for indentmap/mpi.h). */
#ifndef INDENTMAP_SCENE_RANKS_H
#define INDENTMAP_SCENE_RANKS_H

#include "indentmap/mpi_config.h"

#if IM_HAVE_MPI

#include "indentmap/scene.h"

#include <mpi.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Runs a scene as im_scene_run (scene.h) does, with the members of its ensembles (the table's and
 * the histories' surfaces) shared out over the ranks of comm: rank r solves the members r, r + K,
 * r + 2K, ... (K ranks, each with its OpenMP threads) and writes each under the output folder as
 * soon as it is solved, as a single process does; then rank 0 alone runs the stages, reading those
 * members back exactly (their stage lines count them as solved), and writes every table and figure:
 * byte for byte those of a single process. Rank 0 takes the output folder's lock, removes the stale
 * temporaries and writes run.json before any rank starts. First every rank reads the files the scene
 * names (surfaces, profile): IM_EINVAL on every rank, naming the file, its key and the ranks, when
 * one reads other bytes from it than rank 0 (a path naming other files on other nodes) or cannot
 * read it (that rank's message). options as for im_scene_run on every
 * rank (rank 0's progress lines only; the other ranks are quiet). With one rank, im_scene_run.
 * Collective; MPI initialised with at least MPI_THREAD_FUNNELED. Every rank returns a failure
 * when any rank fails: a rank's error (the lowest failing rank's) before an interruption; rank 0
 * and the failing rank carry its message, the others "rank K: <message>". Rank 0's status is the
 * run's (its outputs, its message). */
int im_scene_run_ranks(MPI_Comm comm, const im_scene *scene, const im_scene_run_options *options);

/* im_scene_check (scene.h) of a run by im_scene_run_ranks over comm: first the checks every rank of that
 * run makes before any work (the files the scene names read alike on every rank, each rank's preparation
 * of the scene), then rank 0's im_scene_check for that many ranks; *report (rank 0's; NULL on the
 * others and on an error) as there. Collective; every rank returns the same status, its message as
 * im_scene_run_ranks gives it. With one rank, im_scene_check. */
int im_scene_check_ranks(MPI_Comm comm, const im_scene *scene, const im_scene_run_options *options, char **report);

#ifdef __cplusplus
}
#endif

#endif /* IM_HAVE_MPI */
#endif
