/* indentmap run: runs a scene file. */
#include "cli/cli.h"

#include "indentmap/mpi.h"
#include "indentmap/render.h"
#include "indentmap/scene.h"
#include "indentmap/scene_ranks.h"
#include "indentmap/status.h"
#if IM_HAVE_MPI
#include "mpi/agree.h"
#endif

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *stream)
{
    fprintf(stream, "usage: indentmap run SCENE.ini [--check] [--resume] [--quiet] [--backend auto|egl|osmesa]\n"
                    "                     [--wisdom FILE | --no-wisdom] [--out DIR]\n"
                    "       indentmap run --from-record DIR/run.json [--out NEWDIR] [options as above]\n\n"
                    "Runs a scene: solves what its outputs need and writes them under its output folder\n"
                    "(default output/NAME). Bundled scenes are in scenes/; fig4 is the paper's Fig. 4.\n\n"
                    "  --from-record R the scene a run recorded in its run.json R (its keys as parsed), run\n"
                    "                  again: refused when an input file's SHA-256 is no longer the recorded\n"
                    "                  one or R was made by another version; its FFTW plans as recorded\n"
                    "                  (estimated ones unless --wisdom is given) (docs/scenes.md, \"Provenance\")\n"
                    "  --check         solve and write nothing: check the scene as the run would (its keys,\n"
                    "                  input files, outputs, memory and disk estimates against this\n"
                    "                  machine's) and print what it would read, solve and write, with\n"
                    "                  whether --resume would reuse each kept result; exit 0 when it would\n"
                    "                  run, else the run's error (docs/scenes.md, \"Checking a scene\")\n"
                    "  --out DIR       write under DIR instead of the scene's output folder\n"
                    "  --resume        reuse results already on disk instead of solving them again\n"
                    "                  (after an interruption: SIGINT or SIGTERM stops at the next solver\n"
                    "                  step, keeps finished results and exits 130 or 143); a result made\n"
                    "                  from other inputs (the scene was edited) is solved again, with a notice\n"
                    "  --quiet         no stage lines on stderr (errors and notices remain); the progress\n"
                    "                  bar is drawn only when stderr is a terminal\n"
                    "  --backend B     OpenGL backend (default auto, or $IM_RENDER_BACKEND)\n"
                    "  --wisdom FILE   FFTW wisdom for the scene's histories, read before planning and\n"
                    "                  updated after it (their plans are measured). Default:\n"
                    "                  $IM_FFTW_WISDOM, else the user's cache ($XDG_CACHE_HOME or\n"
                    "                  ~/.cache)/indentmap/fftw-wisdom (docs/solver.md)\n"
                    "  --no-wisdom     no wisdom file (also IM_FFTW_WISDOM=\"\"): FFTW_ESTIMATE plans\n"
                    "\nIM_NO_SPACE_CHECK=1 skips the check of the free disk against the outputs' estimated\n"
                    "size (an upper bound); a disk that fills still stops the run, keeping what it finished.\n"
#if IM_HAVE_MPI
                    "\nUnder mpirun (mpirun -n K indentmap run SCENE.ini) the ensembles' surfaces are shared\n"
                    "out over the K ranks and rank 0 writes the outputs (docs/mpi.md)\n"
#endif
    );
}

#if IM_HAVE_MPI
/* Started by mpirun (Open MPI's environment, or a PMI launcher's such as Slurm's srun). */
static int launched_by_mpirun(void)
{
    return getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMIX_RANK") || getenv("PMI_SIZE");
}
#endif

/* The exit status of a run, or of --check (scene NULL: its report is the success's output); only the
 * reporting rank (rank 0, or a single process) prints. */
static int finish(int status, const im_scene *scene, int reporting)
{
    if (status == IM_EINTERRUPTED)
        return cli_interrupt_report(reporting);
    if (status != IM_OK)
        return reporting                                                            ? cli_report(status)
               : status == IM_EINVAL || status == IM_EFORMAT || status == IM_ENOMEM ? CLI_EXIT_USAGE
                                                                                    : CLI_EXIT_FAILURE;
    if (reporting && scene)
        printf("indentmap: scene %s written to %s/\n", im_scene_name(scene), im_scene_output_dir(scene));
    return CLI_EXIT_OK;
}

/* The FFTW wisdom file of the run (cli.h: cli_wisdom_resolve), the scene's (im_scene_set_wisdom_path). */
typedef struct run_wisdom {
    const char *given;
    int off;
    int use_cache; /* cli_wisdom_resolve's: the cache, or (--check) the cache looked at only */
    char cache[4096];
} run_wisdom;

/* Where the scene comes from and where it writes: a scene file or a run's record (--from-record),
 * and --out. */
typedef struct run_source {
    const char *path;
    int from_record;
    const char *out;
} run_source;

/* The scene of a file or a record into *scene (NULL on an error); --out replaces its output folder. */
static int load_scene(const run_source *source, im_scene **scene)
{
    int status = source->from_record ? im_scene_load_record(source->path, scene) : im_scene_load(source->path, scene);
    if (status != IM_OK || !source->out)
        return status;
    status = im_scene_set_output_dir(*scene, source->out);
    return status == IM_OK ? IM_OK : im_fail_context(status, "--out");
}

/* The scene, its wisdom file, and the SIGINT/SIGTERM handlers that let a run stop cleanly. A scene
 * rebuilt from a record whose plans were estimated is estimated again unless --wisdom is given. */
static int load_and_arm(const run_source *source, im_scene **scene, run_wisdom *wisdom)
{
    int status = load_scene(source, scene);
    im_solver_options solver = im_solver_options_default();
    if (status == IM_OK) {
        int off = wisdom->off || (im_scene_recorded_plans(*scene) == 0 && !wisdom->given);
        status = cli_wisdom_resolve(wisdom->given, off, wisdom->use_cache, &solver, wisdom->cache,
                                    sizeof wisdom->cache);
    }
    if (status == IM_OK)
        im_scene_set_wisdom_path(*scene, solver.wisdom_path);
    if (status == IM_OK && cli_interrupt_install() != 0)
        status = im_fail(IM_EUNSUPPORTED, "cannot install the SIGINT/SIGTERM handlers");
    return status;
}

/* A scene that asks for no output would solve and draw nothing and still succeed: refused here, not by
 * the parser (nor by im_scene_run, which Python's run_scene calls on such a scene). A periodic scene
 * writes each surface's history and k without one; frames3d alone is an output (im_scene_run then
 * says it needs frames). */
static int check_asks_for_output(const im_scene *scene)
{
    if (im_scene_asks_for_output(scene))
        return IM_OK;
    return im_fail(IM_EINVAL,
                   "%s: no output asked for: expected an [output] section with table, contact_panels, "
                   "frames or distributions = yes, or plots = a figure (nothing would be solved or drawn)",
                   im_scene_path(scene));
}

/* The backend of a scene that renders: --backend, else IM_RENDER_BACKEND, else auto. */
static int backend_of_scene(const im_scene *scene, im_scene_run_options *run)
{
    im_render_backend backend = (im_render_backend)run->backend;
    int status = im_scene_renders(scene) ? cli_render_backend(&backend) : IM_OK;
    run->backend = (int)backend;
    return status;
}

/* --check: the report of what the run would do on stdout (report: im_scene_check's or, under mpirun,
 * im_scene_check_ranks'), or the run's error. */
static int print_check(int status, char **report)
{
    if (status == IM_OK && *report)
        fputs(*report, stdout);
    free(*report);
    return status;
}

#if IM_HAVE_MPI
/* Under mpirun: MPI starts before the signal handlers (ours, installed after, are the ones in
 * force); every rank checks that it was given the same command and scene as the others, loads it,
 * and runs it over the ranks once all have loaded it (an error on one rank, such as a wisdom file
 * or backend of its own environment, stops all); rank 0 reports. */
static int run_under_mpirun(int argc, char **argv, const run_source *source, const im_scene_run_options *run,
                            run_wisdom *wisdom, int check)
{
    int provided, rank, ranks;
    MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    im_scene *scene = NULL;
    im_scene_run_options options = *run;
    int status = mpi_same_inputs(MPI_COMM_WORLD, argc, argv, source->path);
    if (status == IM_OK) {
        status = load_and_arm(source, &scene, wisdom);
        if (status == IM_OK)
            status = check_asks_for_output(scene);
        if (status == IM_OK)
            status = backend_of_scene(scene, &options);
        status = mpi_collective_status(MPI_COMM_WORLD, status);
    }
    char *report = NULL;
    if (status == IM_OK && check) /* every rank's checks of the run, then rank 0's report for all */
        status = print_check(im_scene_check_ranks(MPI_COMM_WORLD, scene, &options, &report), &report);
    else if (status == IM_OK)
        status = im_scene_run_ranks(MPI_COMM_WORLD, scene, &options);
    int code = mpi_exit_code(MPI_COMM_WORLD, finish(status, check ? NULL : scene, rank == 0));
    im_scene_free(scene);
    if (rank != 0) /* rank 0 has spoken for all: nothing more (mpirun may signal a rank still finishing) */
        (void)freopen("/dev/null", "w", stderr);
    MPI_Finalize();
    return code;
}
#endif

/* What `run`'s options set. */
typedef struct run_arguments {
    im_scene_run_options *run;
    run_source *source;
    im_render_backend *backend;
    run_wisdom *wisdom;
    int *check;
} run_arguments;

static int apply_option(int code, const char *arg, void *state)
{
    run_arguments *a = state;
    switch (code) {
    case 'r': a->run->resume = 1; return 0;
    case 'q': a->run->quiet = 1; return 0;
    case 'c':
        *a->check = 1;
        a->wisdom->use_cache = CLI_WISDOM_CACHE_LOOK;
        return 0;
    case 'w': a->wisdom->given = arg; return 0;
    case 'W': a->wisdom->off = 1; return 0;
    case 'R': *a->source = (run_source){.path = arg, .from_record = 1, .out = a->source->out}; return 0;
    case 'o': a->source->out = arg; return 0;
    case 'b':
        if (im_render_backend_from_name(arg, a->backend) == IM_OK)
            return 0;
        cli_report(IM_EINVAL);
        return -1;
    default: return -1;
    }
}

int cli_run(int argc, char **argv)
{
    static const struct option options[] = {
        {"resume", no_argument, 0, 'r'},    {"quiet", no_argument, 0, 'q'},
        {"check", no_argument, 0, 'c'},     {"backend", required_argument, 0, 'b'},
        {"help", no_argument, 0, 'h'},      {"wisdom", required_argument, 0, 'w'},
        {"no-wisdom", no_argument, 0, 'W'}, {"from-record", required_argument, 0, 'R'},
        {"out", required_argument, 0, 'o'}, {0, 0, 0, 0}};
    im_scene_run_options run = {0};
    run_source source = {0};
    im_render_backend backend = IM_RENDER_AUTO;
    run_wisdom wisdom = {.use_cache = CLI_WISDOM_CACHE};
    int check = 0;
    run_arguments arguments = {&run, &source, &backend, &wisdom, &check};
    int code = cli_parse_options(argc, argv, options, 'h', usage, apply_option, &arguments);
    if (code != 0)
        return code > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (optind != argc - !source.from_record) { /* a scene file, or a record */
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (!source.from_record)
        source.path = argv[optind];
    run.backend = (int)backend;
    run.no_space_check = cli_space_check_off();
    run.stop = &cli_stop_signal;
    run.log = cli_log;
    run.progress = run.quiet ? NULL : cli_progress; /* --quiet: no bar either */
#if IM_HAVE_MPI
    if (launched_by_mpirun())
        return run_under_mpirun(argc, argv, &source, &run, &wisdom, check);
#endif
    im_scene *scene = NULL;
    int status = load_and_arm(&source, &scene, &wisdom);
    if (status == IM_OK)
        status = check_asks_for_output(scene);
    if (status == IM_OK)
        status = backend_of_scene(scene, &run);
    char *report = NULL;
    if (status == IM_OK && check)
        status = print_check(im_scene_check(scene, &run, 1, &report), &report);
    else if (status == IM_OK)
        status = im_scene_run(scene, &run);
    code = finish(status, check ? NULL : scene, 1);
    im_scene_free(scene);
    return code;
}
