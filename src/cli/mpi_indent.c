/* indentmap mpi-indent: one indentation of one surface over MPI ranks (run under mpirun; see
 * docs/mpi.md). Built only with MPI (IM_HAVE_MPI). */
#include "indentmap/mpi.h"

#if IM_HAVE_MPI

#include "cli/cli.h"
#include "io/json_file.h"
#include "cli/figure_provenance.h"
#include "cli/mpi_indent.h"
#include "front/front.h"
#include "mpi/agree.h"
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/status.h"

#include <errno.h>
#include <getopt.h>
#include <jansson.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

enum {
    OPT_SURFACE = 256,
    OPT_N,
    OPT_M,
    OPT_SEED,
    OPT_SLOPE,
    OPT_PUNCH,
    OPT_ALPHA,
    OPT_RADIUS,
    OPT_APPROACH,
    OPT_LOAD,
    OPT_HARDNESS,
    OPT_TOL,
    OPT_MAXIT,
    OPT_OUT,
    OPT_MAP,
    OPT_HELP,
    OPT_PERIODIC,
    OPT_PRESSURE,
    OPT_MEAN_GAP,
    OPT_ADHESION_WORK,
    OPT_ADHESION_RANGE,
    OPT_ADHESION_LAW,
    OPT_PROFILE,
    OPT_FRAMES,
    OPT_ADHESION_ZONE
};

static const struct option LONG_OPTIONS[] = {{"surface", required_argument, 0, OPT_SURFACE},
                                             {"n", required_argument, 0, OPT_N},
                                             {"m", required_argument, 0, OPT_M},
                                             {"seed", required_argument, 0, OPT_SEED},
                                             {"slope", required_argument, 0, OPT_SLOPE},
                                             {"punch", required_argument, 0, OPT_PUNCH},
                                             {"alpha", required_argument, 0, OPT_ALPHA},
                                             {"radius", required_argument, 0, OPT_RADIUS},
                                             {"approach", required_argument, 0, OPT_APPROACH},
                                             {"load", required_argument, 0, OPT_LOAD},
                                             {"hardness", required_argument, 0, OPT_HARDNESS},
                                             {"tol", required_argument, 0, OPT_TOL},
                                             {"max-iter", required_argument, 0, OPT_MAXIT},
                                             {"out", required_argument, 0, OPT_OUT},
                                             {"map", required_argument, 0, OPT_MAP},
                                             {"help", no_argument, 0, OPT_HELP},
                                             {"periodic", no_argument, 0, OPT_PERIODIC},
                                             {"pressure", required_argument, 0, OPT_PRESSURE},
                                             {"mean-gap", required_argument, 0, OPT_MEAN_GAP},
                                             {"adhesion-work", required_argument, 0, OPT_ADHESION_WORK},
                                             {"adhesion-range", required_argument, 0, OPT_ADHESION_RANGE},
                                             {"adhesion-law", required_argument, 0, OPT_ADHESION_LAW},
                                             {"profile", required_argument, 0, OPT_PROFILE},
                                             {"frames", no_argument, 0, OPT_FRAMES},
                                             {"adhesion-zone", required_argument, 0, OPT_ADHESION_ZONE},
                                             {0, 0, 0, 0}};

static void usage(FILE *stream)
{
    fprintf(stream,
            "usage: mpirun -n K indentmap mpi-indent (--approach W|LIST | --load N|LIST) [options]\n"
            "       mpirun -n K indentmap mpi-indent --periodic (--pressure LIST | --mean-gap LIST) [options]\n\n"
            "One indentation of one surface over K MPI ranks (each with its OpenMP threads): the whole\n"
            "grid is solved (no crop window), the result is the same to the bit for any K.\n"
            "Prints on rank 0: approach,load,contact_patches,iterations,residual,seconds (CSV with header).\n\n"
            "  --surface FILE  heights (float64 .npy, units of delta = 1, rows along y: a sidecar\n"
            "                  FILE.json stating another delta or the order xy is refused), read\n"
            "                  with MPI-IO; otherwise\n"
            "                  a surface is synthesised over the ranks:\n"
            "  --n NX --m NY   its grid (default 512 x 512, NY = NX; lambda_r = the shorter side)\n"
            "  --seed S --slope H'rms   (default 1 and 0.08; H = 0.8, lambda_s = 4)\n"
            "  --punch cone|sphere|flat|profile   (default cone) --alpha DEG (default 80) --radius R\n"
            "                  (sphere, flat punch)\n"
            "  --profile FILE  the punch's shape for --punch profile, indent's: an 'r z' table\n"
            "                  (axisymmetric) or a .npy height field on the surface's grid (2-D), in\n"
            "                  units of delta; every rank reads it (the same bytes on every rank)\n"
            "  --approach W | --load N   displacement or load control: one step, or with a LIST\n"
            "                  ('v1,v2,...' or 'first:last:count') indent --full's history, each step\n"
            "                  warm-started from the last, printed and written as --periodic's\n"
            "  --hardness H    perfect plasticity: no patch carries more than H (units of E*'s stress);\n"
            "                  in a history with plastic memory from step to step (unloading is elastic\n"
            "                  from the flattened surface); a load under the cap is found by\n"
            "                  displacement-controlled solves on the approach, as indent's\n"
            "  --tol T --max-iter M      stopping rule (defaults 1e-6 as for indent and scenes, 10000;\n"
            "                            tol 1e-15 to 0.5, as --tol of indent)\n"
            "  --out DIR       write DIR/force.npy (force per patch) and DIR/gap.npy with MPI-IO\n"
            "  --map F         also DIR/force_map.npy, the forces summed over F x F blocks (patch side F;\n"
            "                  .npy keeps no patch side), gathered on rank 0 (to draw with\n"
            "                  'indentmap render contact' grids too large to draw whole)\n\n"
            "  --periodic      the surface is one period of a periodic surface, pressed by a rigid flat\n"
            "                  on the whole cell (indent --periodic): a history of the steps of\n"
            "  --pressure LIST mean pressures p_m (units of E*; N = p_m nx ny), or\n"
            "  --mean-gap LIST mean gaps over the cell (delta), each > 0; LIST as indent's:\n"
            "                  'v1,v2,...' or 'first:last:count'. With --hardness: plastic memory from\n"
            "                  step to step; a yielding cell's mean gap is found by indent's search of\n"
            "                  the approach, over the ranks. Prints on rank 0 the history, indent's\n"
            "                  history.csv columns; with --out DIR also DIR/history.csv (appended step by\n"
            "                  step), DIR/run.json and the last step's fields. Rank 0 gathers the heights\n"
            "                  once (h'rms, k of eq. (2)) and each step's forces (contact patches)\n"
            "  --adhesion-work W --adhesion-range D [--adhesion-law L]   adhesion as indent's (the\n"
            "                  Maugis-Dugdale law, or L = exponential), its passes over the ranks, with\n"
            "                  --periodic --mean-gap LIST (not with --hardness), or on the half-space with\n"
            "                  --approach or --load LIST, with or without --hardness (indent --full's history:\n"
            "                  approaches then retractions, negative ones pulling the punch away, through the\n"
            "                  pull-off; negative loads a tension; run.json with the pull-off, the jumps and\n"
            "                  DIR/force_distance.png): the history's tensile force and adhesive and repulsive\n"
            "                  patches, and the net forces in force.npy\n"
            "  --adhesion-zone P  the Maugis-Dugdale zone widened to P patches at the same work, as\n"
            "                  indent's (run.json states the law solved and the law asked)\n"
            "  With a LIST and --out DIR, DIR/history.png and .pdf (indent's history figure), drawn on rank 0\n"
            "  --frames        also DIR/force_NNNN.npy and DIR/frames/contact_NNNN.png for every step of a\n"
            "                  history (indent --frames' contact maps; needs OpenGL on rank 0 and --out):\n"
            "                  rank 0 gathers each step's forces (8 nx ny bytes, held one step at a time)\n");
}

/* --pressure or --mean-gap, or the half-space's --approach or --load LIST: a step list (front.h: steps_parse, as
 * indent's and a scene's; with adhesion approaches and loads may be negative: the punch pulled away, the contact
 * under tension). */
static int steps_parse_list(mpi_indent_options *o, const char *text)
{
    char error[512];
    if (!o->targets && !(o->targets = malloc(sizeof(double) * STEPS_MAX))) {
        fprintf(stderr, "indentmap: mpi-indent: %s: out of memory\n", o->targets_option);
        return -1;
    }
    const int negative = o->adhesion_work > 0 && o->control != IM_CONTROL_MEAN_GAP;
    if (steps_parse_signed(o->targets_option, text, negative, o->targets, &o->target_count, error, sizeof error) ==
            0 &&
        (o->control != IM_CONTROL_MEAN_GAP || /* refused now, not at its step after the steps before it */
         steps_check_mean_gaps(o->targets_option, text, o->targets, o->target_count, error, sizeof error) == 0))
        return 0;
    fprintf(stderr, "indentmap: %s\n", error);
    return -1;
}

/* The controls exclude one another, as in indent: a second of --approach, --load, --pressure and --mean-gap is
 * refused (the same one twice is cli_parse_options' refusal). */
static int control_given_before(const mpi_indent_options *o)
{
    if (!o->targets_option && !o->target_text)
        return 0;
    fprintf(stderr, "indentmap: mpi-indent: give one of --approach, --load, --pressure and --mean-gap, once\n");
    return 1;
}

static int apply_option(int code, const char *arg, void *state)
{
    mpi_indent_options *o = state;
    switch (code) {
    case OPT_SURFACE: o->surface_file = arg; return 0;
    case OPT_N: return cli_parse_int("--n", arg, 2, IM_FIELD_MAX_SIDE, &o->surface.nx);
    case OPT_M: o->m_given = 1; return cli_parse_int("--m", arg, 2, IM_FIELD_MAX_SIDE, &o->surface.ny);
    case OPT_SEED: return cli_parse_u64("--seed", arg, &o->surface.seed);
    case OPT_SLOPE: return cli_parse_double("--slope", arg, 0, 1e6, &o->surface.slope_rms);
    case OPT_PERIODIC: o->periodic = 1; return 0;
    case OPT_PRESSURE:
    case OPT_MEAN_GAP:
        if (control_given_before(o))
            return -1;
        o->targets_option = code == OPT_PRESSURE ? "--pressure" : "--mean-gap";
        o->control = code == OPT_PRESSURE ? IM_CONTROL_LOAD : IM_CONTROL_MEAN_GAP;
        return steps_parse_list(o, arg);
    case OPT_PUNCH: /* the names of `indent --punch` (indenter.h); a profile's shape is --profile's */
        o->punch_given = 1;
        if (im_punch_parse(arg, &o->punch.kind) == IM_OK)
            return 0;
        fprintf(stderr, "indentmap: --punch %s\n", im_last_error());
        return -1;
    case OPT_PROFILE: o->punch_given = 1; return cli_parse_path("--profile", arg, &o->profile_path);
    case OPT_FRAMES: o->frames = 1; return 0;
    case OPT_ALPHA: o->punch_given = 1; return cli_parse_double("--alpha", arg, 0, 90, &o->punch.alpha_degrees);
    case OPT_RADIUS: o->punch_given = 1; return cli_parse_double("--radius", arg, 0, 1e300, &o->punch.radius);
    case OPT_APPROACH: /* W or N, or a LIST: read once the options are known (half_space_targets) */
    case OPT_LOAD:
        if (control_given_before(o))
            return -1;
        o->control = code == OPT_LOAD ? IM_CONTROL_LOAD : IM_CONTROL_DISPLACEMENT;
        o->target_text = arg;
        return 0;
    case OPT_HARDNESS: return cli_parse_double("--hardness", arg, 1e-300, 1e300, &o->solver.hardness);
    case OPT_TOL:
        o->tol_given = 1;
        return cli_parse_double("--tol", arg, IM_SOLVER_TOL_MIN, IM_SOLVER_TOL_MAX, &o->solver.tol);
    case OPT_MAXIT: return cli_parse_int("--max-iter", arg, 1, 1000000000, &o->solver.max_iterations);
    case OPT_OUT: return cli_parse_path("--out", arg, &o->out);
    case OPT_MAP: return cli_parse_int("--map", arg, 1, IM_FIELD_MAX_SIDE, &o->map_factor);
    case OPT_ADHESION_WORK: return cli_parse_double("--adhesion-work", arg, 1e-300, 1e300, &o->adhesion_work);
    case OPT_ADHESION_RANGE: return cli_parse_double("--adhesion-range", arg, 1e-300, 1e300, &o->adhesion_range);
    case OPT_ADHESION_LAW: o->adhesion_law_given = 1; return cli_parse_adhesion_law(arg, &o->adhesion_law);
    case OPT_ADHESION_ZONE: return cli_parse_double("--adhesion-zone", arg, 1e-300, 1e300, &o->adhesion_zone);
    default: return -1;
    }
}

/* This rank's rows of the heights: read from the file or synthesised. */
static int load_heights(const mpi_indent_options *o, int y0, int rows, double *heights)
{
    if (o->surface_file)
        return im_mpi_npy_read_rows(MPI_COMM_WORLD, o->surface_file, y0, rows, heights);
    return im_mpi_surface_generate(MPI_COMM_WORLD, &o->surface, y0, rows, heights);
}

/* DIR/force_map.npy on rank 0: forces (p delta^2, delta = 1) summed over the map's blocks. */
static int write_map(const mpi_indent_options *o, const im_mpi_solver *solver, const double *pressure)
{
    im_field *map;
    int status = im_mpi_gather_map(solver, pressure, o->map_factor, &map);
    if (status != IM_OK)
        return status;
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) {
        char path[4096];
        status = im_path_join(path, sizeof path, o->out, "force_map.npy");
        if (status == IM_OK)
            status = im_npy_write(path, map, IM_NPY_FLOAT64);
        im_field_free(map);
    }
    int shared = status;
    MPI_Bcast(&shared, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return shared == IM_OK || rank == 0 ? shared : im_fail(shared, "rank 0 could not write the map");
}

int mpi_indent_write_fields(const mpi_indent_options *o, const im_mpi_solver *solver, const double *pressure,
                            const double *gap)
{
    int y0, rows, nx = o->surface.nx, ny = o->surface.ny, rank, made = 1;
    im_mpi_solver_rows(solver, &y0, &rows);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0)
        made = mkdir(o->out, 0777) == 0 || errno == EEXIST;
    MPI_Bcast(&made, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (!made)
        return im_fail(IM_EIO, "--out %s: cannot create the folder", o->out);
    char path[4096];
    int status = im_path_join(path, sizeof path, o->out, "force.npy"); /* the same on every rank */
    if (status == IM_OK)
        status = im_mpi_npy_write_rows(MPI_COMM_WORLD, path, nx, ny, y0, rows, pressure);
    if (status == IM_OK)
        status = im_path_join(path, sizeof path, o->out, "gap.npy");
    if (status == IM_OK)
        status = im_mpi_npy_write_rows(MPI_COMM_WORLD, path, nx, ny, y0, rows, gap);
    return status == IM_OK && o->map_factor > 0 ? write_map(o, solver, pressure) : status;
}

/* Rank 0: an earlier run's DIR/force.npy, gap.npy, force_map.npy and run.json removed before this one solves, so
 * that a failed or interrupted run (which writes no fields: only a completed one does) leaves no other run's
 * fields beside its own record, and a run that fails before its record (or a single step, which writes none)
 * leaves no earlier record naming fields that are gone or not its. Kept: an input named there, and a symbolic
 * link (written through, as every output: run.json's "fields" still says that none is this run's). */
static int clear_earlier_fields(const mpi_indent_options *o)
{
    static const char *const NAMES[] = {"force.npy", "gap.npy", "force_map.npy", "run.json"};
    int rank, status = IM_OK;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    for (size_t i = 0; rank == 0 && status == IM_OK && i < sizeof NAMES / sizeof *NAMES; ++i) {
        char path[4096];
        struct stat info;
        status = im_path_join(path, sizeof path, o->out, NAMES[i]);
        if (status != IM_OK || lstat(path, &info) != 0 || S_ISLNK(info.st_mode) || im_output_check(path) != IM_OK)
            continue;
        if (unlink(path) != 0 && errno != ENOENT)
            status = im_fail(IM_EIO, "%s: cannot remove the earlier run's file: %s", path, strerror(errno));
    }
    return mpi_collective_status(MPI_COMM_WORLD, status);
}

/* Every rank must read the same bytes from the surface and profile files (agree.h: a path may name other files on
 * other nodes). */
static int same_files(const mpi_indent_options *o)
{
    const char *paths[2], *keys[2];
    int count = 0;
    if (o->surface_file) {
        paths[count] = o->surface_file;
        keys[count++] = "--surface";
    }
    if (o->profile_path) {
        paths[count] = o->profile_path;
        keys[count++] = "--profile";
    }
    return count ? mpi_same_files(MPI_COMM_WORLD, "the command", count, paths, keys) : IM_OK;
}

/* The heights are read in units of delta = 1, rows along y: a sidecar stating another spacing (`surface
 * --delta 2.5 --unit nm --out`) or the order [x, y] was not read, and the surface solved another problem
 * without a word. This rank's verdict on FILE.json (the same bytes on every rank: same_files). */
static int sidecar_readable_as_is(const char *surface_file)
{
    char path[PATH_MAX];
    struct stat info;
    if (im_path_suffix(path, sizeof path, surface_file, ".json") != IM_OK || stat(path, &info) != 0)
        return IM_OK; /* no sidecar: nothing stated */
    json_t *root = json_file_load(path, 0, NULL);
    json_t *delta = json_object_get(root, "delta"), *unit = json_object_get(root, "unit");
    const char *order = json_string_value(json_object_get(root, "order"));
    int status = IM_OK;
    if (json_is_number(delta) && json_number_value(delta) != 1.0)
        status = im_fail(IM_EINVAL,
                         "--surface %s: its sidecar %s states delta = %g %s, but mpi-indent reads heights in "
                         "units of delta = 1: expected the heights divided by delta (a surface of delta 1)",
                         surface_file, path, json_number_value(delta),
                         json_is_string(unit) ? json_string_value(unit) : "");
    else if (order && strcmp(order, "xy") == 0)
        status = im_fail(IM_EINVAL,
                         "--surface %s: its sidecar %s states the order xy (indexed [x, y]), but mpi-indent reads "
                         "rows along y: expected the array transposed (order yx)",
                         surface_file, path);
    json_decref(root);
    return status;
}

/* The grid: the file's shape, or the synthesis's. */
static int grid_of(mpi_indent_options *o)
{
    int status = same_files(o);
    if (status != IM_OK || !o->surface_file)
        return status;
    status = mpi_collective_status(MPI_COMM_WORLD, sidecar_readable_as_is(o->surface_file));
    if (status != IM_OK)
        return status;
    return im_mpi_npy_shape(MPI_COMM_WORLD, o->surface_file, &o->surface.nx, &o->surface.ny);
}

/* --profile read on every rank (each evaluates the punch on its rows), in units of delta = 1 as the heights:
 * the punch borrows it, centred as indent's. Collective. */
static int load_profile(mpi_indent_options *o)
{
    if (!o->profile_path)
        return IM_OK;
    int status = im_profile_read(o->profile_path, 1.0, &o->profile);
    if (status == IM_OK) {
        o->punch = im_indenter_from_profile(o->profile);
        status = im_indenter_check(&o->punch);
    }
    return mpi_collective_status(MPI_COMM_WORLD, status == IM_OK ? IM_OK : im_fail_context(status, "--profile"));
}

/* Fails every rank (IM_ENOMEM naming the fields) when some rank's allocation failed (have 0). */
static int all_allocated(int have, const char *fields, int rows)
{
    int all;
    MPI_Allreduce(&have, &all, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
    return all ? IM_OK : im_fail(IM_ENOMEM, "mpi-indent: the %s of some rank's %d rows", fields, rows);
}

/* One step on the half-space from this rank's heights: fills the gap, solves and writes; *result on
 * success. */
static int solve_half_space(const mpi_indent_options *o, im_mpi_solver *solver, const double *heights,
                            im_solve_result *result)
{
    int y0, rows;
    im_mpi_solver_rows(solver, &y0, &rows);
    size_t n = (size_t)rows * o->surface.nx + 1;
    double *gap0 = malloc(sizeof(double) * n), *pressure = calloc(n, sizeof(double));
    double *displacement = malloc(sizeof(double) * n);
    int status = all_allocated(gap0 && pressure && displacement, "fields", rows);
    if (status == IM_OK)
        status = im_mpi_undeformed_gap(solver, heights, &o->punch, gap0);
    if (status == IM_OK)
        status = im_mpi_solver_solve(solver, gap0, o->control, o->target, pressure, displacement, result);
    if (status == IM_OK)
        status = im_mpi_check_edge(solver, pressure);
    if (status == IM_OK && o->out) {
        for (size_t i = 0; i + 1 < n; ++i) /* the gap g = g0 - w + u */
            gap0[i] += displacement[i] - result->approach;
        status = mpi_indent_write_fields(o, solver, pressure, gap0);
    }
    free(gap0);
    free(pressure);
    free(displacement);
    return status;
}

/* Plans, reads or synthesises the heights, and solves the step (*result) or, --periodic, the history. */
static int solve(mpi_indent_options *o, im_solve_result *result)
{
    int status = grid_of(o);
    if (status == IM_OK)
        status = load_profile(o);
    if (status != IM_OK)
        return status;
    if (!o->surface_file)
        o->surface.lambda_r = o->surface.nx < o->surface.ny ? o->surface.nx : o->surface.ny;
    im_mpi_solver *solver;
    if ((status = im_mpi_solver_create(MPI_COMM_WORLD, o->surface.nx, o->surface.ny, 1.0, &o->solver, &solver)) !=
        IM_OK)
        return status;
    int y0, rows;
    im_mpi_solver_rows(solver, &y0, &rows);
    double *heights = malloc(sizeof(double) * ((size_t)rows * o->surface.nx + 1));
    status = all_allocated(heights != NULL, "heights", rows);
    if (status == IM_OK)
        status = load_heights(o, y0, rows, heights);
    if (status == IM_OK && o->out)
        status = clear_earlier_fields(o);
    if (status == IM_OK)
        status = o->targets ? mpi_indent_history(o, solver, heights) : solve_half_space(o, solver, heights, result);
    im_mpi_solver_free(solver);
    free(heights);
    return status;
}

/* What --periodic takes and what it does not: 0, or -1 with the message said. */
static int check_periodic_options(mpi_indent_options *o)
{
    if (o->targets_option && !o->periodic)
        fprintf(stderr,
                "indentmap: mpi-indent: %s (over a periodic cell) needs --periodic; the half-space takes "
                "--approach W or --load N\n",
                o->targets_option);
    else if (o->periodic && o->target_text)
        fprintf(stderr, "indentmap: mpi-indent --periodic takes mean pressures (--pressure LIST) or mean gaps "
                        "(--mean-gap LIST), not --approach or --load\n");
    else if (o->periodic && !o->targets_option)
        fprintf(stderr, "indentmap: mpi-indent --periodic: give --pressure LIST or --mean-gap LIST\n");
    else if (o->periodic && o->punch_given)
        fprintf(stderr, "indentmap: mpi-indent --periodic presses a rigid flat on the whole cell: --punch, --alpha, "
                        "--radius and --profile are the half-space's\n");
    else
        return 0;
    return -1;
}

/* Adhesion (indent's options): a periodic cell under mean gaps, the half-space under approaches or loads (with
 * a hardness too). 0, or -1 with the message said. */
static int check_adhesion_options(const mpi_indent_options *o)
{
    const int adhesion = o->adhesion_work > 0;
    const int mean_gaps = o->periodic && o->targets_option && o->control == IM_CONTROL_MEAN_GAP;
    const int half_space = !o->periodic && o->target_text;
    if (adhesion != (o->adhesion_range > 0))
        fprintf(stderr, "indentmap: mpi-indent: --adhesion-work and --adhesion-range go together\n");
    else if (o->adhesion_law_given && !adhesion)
        fprintf(stderr, "indentmap: mpi-indent: --adhesion-law goes with --adhesion-work and --adhesion-range\n");
    else if (o->adhesion_zone > 0 && !adhesion)
        fprintf(stderr, "indentmap: mpi-indent: --adhesion-zone widens the zone of --adhesion-work and "
                        "--adhesion-range: expected both\n");
    else if (o->adhesion_zone > 0 && o->adhesion_law != IM_ADHESION_MAUGIS_DUGDALE)
        fprintf(stderr, "indentmap: mpi-indent: --adhesion-zone widens the Maugis-Dugdale law's zone: expected "
                        "--adhesion-law maugis-dugdale\n");
    else if (adhesion && !mean_gaps && !half_space)
        fprintf(stderr, "indentmap: mpi-indent: --adhesion-work takes --periodic --mean-gap LIST or the "
                        "half-space's --approach or --load LIST (a periodic cell's adhesion under mean pressures, "
                        "--pressure, is indent's, serial)\n");
    else if (adhesion && o->periodic && o->solver.hardness > 0)
        fprintf(stderr, "indentmap: mpi-indent: --periodic --adhesion-work with --hardness: a cell's adhesion with "
                        "plasticity is not available over ranks (it is indent --periodic's, serial; the "
                        "half-space's is)\n");
    else
        return 0;
    return -1;
}

/* The punch's options and --frames' (indent's rules). 0, or -1 with the message said. */
static int check_punch_and_frames(const mpi_indent_options *o)
{
    if ((o->punch.kind == IM_PUNCH_PROFILE) != (o->profile_path != NULL))
        fprintf(stderr, "indentmap: mpi-indent: --punch profile and --profile FILE go together\n");
    else if (o->frames && !o->out)
        fprintf(stderr, "indentmap: mpi-indent: --frames needs --out DIR\n");
    else if (o->frames && !o->targets)
        fprintf(stderr, "indentmap: mpi-indent: --frames draws a history's steps: expected a LIST ('v1,v2,...' or "
                        "'first:last:count') after --approach or --load\n");
    else
        return 0;
    return -1;
}

/* The half-space's --approach or --load: one value W or N (one step), or a LIST, indent's history (with
 * adhesion always a history). */
static int half_space_targets(mpi_indent_options *o)
{
    if (!o->target_text || o->periodic)
        return 0;
    const char *option = o->control == IM_CONTROL_LOAD ? "--load" : "--approach";
    if (!(o->adhesion_work > 0) && !strpbrk(o->target_text, ",:"))
        return cli_parse_double(option, o->target_text, 0, 1e300, &o->target);
    o->targets_option = option;
    return steps_parse_list(o, o->target_text);
}

static int parse(int argc, char **argv, mpi_indent_options *o)
{
    *o = (mpi_indent_options){.surface = im_surface_params_default(),
                              .punch = im_indenter_cone(80),
                              .target = NAN,
                              .solver = im_solver_options_default()};
    o->solver.crop = 0;
    int parsed = cli_parse_options(argc, argv, LONG_OPTIONS, OPT_HELP, usage, apply_option, o);
    if (parsed != 0)
        return parsed;
    if (!o->m_given)
        o->surface.ny = o->surface.nx;
    if (o->map_factor > 0 && !o->out) {
        fprintf(stderr, "indentmap: mpi-indent: --map needs --out DIR\n");
        return -1;
    }
    if (check_periodic_options(o) != 0 || check_adhesion_options(o) != 0 || half_space_targets(o) != 0 ||
        check_punch_and_frames(o) != 0)
        return -1;
    if (isnan(o->target) && !o->periodic && !o->targets) {
        fprintf(stderr, "indentmap: mpi-indent: give --approach W or --load N\n");
        return -1;
    }
    o->solver.periodic = o->periodic;
    const char *const inputs[] = {o->surface_file, o->profile_path}; /* no output replaces or clears them */
    if (cli_protect_inputs(inputs, 2) != 0)
        return -1;
    if (optind < argc) {
        fprintf(stderr, "indentmap: mpi-indent: unexpected argument '%s'\n", argv[optind]);
        return -1;
    }
    int shorter = o->surface.nx < o->surface.ny ? o->surface.nx : o->surface.ny;
    if (!o->surface_file && !(shorter > o->surface.lambda_s)) { /* solve() makes lambda_r the shorter side */
        fprintf(stderr,
                "indentmap: mpi-indent: --n %d --m %d: the shorter side is the surface's lambda_r, which "
                "must exceed lambda_s = %g: expected --n and --m > %g\n",
                o->surface.nx, o->surface.ny, o->surface.lambda_s, o->surface.lambda_s);
        return -1;
    }
    return 0;
}

/* SIGINT, SIGTERM and SIGHUP (mpirun passes them on to every rank, then kills the ranks a second later) stop
 * every rank at the same iteration of a solve or before the same step of a history (mpi_periodic.c), so that
 * the steps done keep their record and figure, as indent's; without SA_RESTART, so that rank 0 blocked writing
 * a row to the stdout mpirun no longer reads gets EINTR and reaches its check (mpi_periodic.c: print_line).
 * Collective. */
static int arm_signals(mpi_indent_options *o)
{
    int status = cli_interrupt_install_unrestarted() == 0
                     ? IM_OK
                     : im_fail(IM_EUNSUPPORTED, "cannot install the signal handlers");
    o->solver.stop = &cli_stop_signal;
    return mpi_collective_status(MPI_COMM_WORLD, status);
}

int cli_mpi_indent(int argc, char **argv)
{
    int provided, rank;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    im_mpi_init();
    mpi_indent_options o = {.targets = NULL};
    int code = CLI_EXIT_OK;
    if (rank != 0) /* every rank parses the same arguments (checked first): rank 0 speaks for them */
        (void)freopen("/dev/null", "w", stderr);
    int status = mpi_same_inputs(MPI_COMM_WORLD, argc, argv, NULL);
    cli_provenance provenance = {0}; /* the command as given (before getopt reorders argv), for the figures */
    if (status == IM_OK) /* (only then: ranks started unalike may run another command, without this collective) */
        status = mpi_collective_status(
            MPI_COMM_WORLD, rank == 0 ? cli_provenance_start("indentmap", argc, argv, &provenance) : IM_OK);
    int parsed = status == IM_OK ? parse(argc, argv, &o) : 0;
    o.command = provenance.command;
    if (parsed != 0)
        code = parsed > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    im_solve_result result;
    if (status == IM_OK && parsed == 0)
        status = arm_signals(&o);
    if (status == IM_OK && parsed == 0)
        status = solve(&o, &result);
    /* The steps done are kept: said once, by rank 0. Each rank's code is 128 + the signal it received (128 on a
     * rank that received none); mpi_exit_code gives rank 0 the largest and the others 0, and mpirun exits with
     * rank 0's, 128 + the signal, when the ranks were signalled (cli_mpi_signal); 1 when mpirun was (measured). */
    if (status == IM_EINTERRUPTED)
        code = cli_interrupt_report(rank == 0);
    else if (status != IM_OK)
        code = cli_report(status);
    else if (parsed == 0 && rank == 0 && !o.targets)
        printf("approach,load,contact_patches,iterations,residual,seconds\n%.17g,%.17g,%ld,%d,%.3g,%.3f\n",
               result.approach, result.load, result.contact_patches, result.iterations, result.residual,
               result.seconds);
    free(o.targets);
    im_profile_free(o.profile); /* after the solves that borrowed it */
    cli_provenance_free(&provenance);
    code = mpi_exit_code(MPI_COMM_WORLD, code);
    im_mpi_cleanup();
    MPI_Finalize();
    return code;
}

#endif
