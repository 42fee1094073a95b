/* The distributed solver against the serial one, run under mpirun with 1, 2, 3 and 4 ranks
 * (tests/mpi/mpi_solver.sh): rank 0 solves the same problem (the undeformed gap the ranks made,
 * gathered) on the serial CPU engine and shares its answer, which every rank compares with its rows:
 * loads to 1e-10 relative, contact sets identical, iteration counts equal (both run the one
 * iteration of solver/pk.c). Cases: a rough cone and a rough sphere (preconditioned CG) and the rough
 * cone under a hardness cap (plain PK with a second bound), each under displacement and load
 * control; nominally flat contact of a periodic rough cell (im_mpi_flat_contact against
 * im_flat_contact: approach, mean pressure and mean gap to 1e-10) under a mean pressure, a mean gap
 * and a mean pressure with a cap, on odd and even sides. Also: the
 * distributed synthesis against im_surface_generate, the maps gathered on rank 0 (whole and 5 x 5),
 * and .npy rows through MPI-IO against the serial reader and writer. Prints one line per case with
 * the load and the map's total in hexadecimal, so the script can check that they are the same
 * bits for every rank count. A failed check aborts all ranks. */
#include "mpi_check.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/mpi.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct scenario {
    const char *name;
    int nx, ny;
    im_indenter punch;
    enum im_control control;
    double approach; /* displacement control: w; load control: N = the smooth N(w) */
    unsigned seed;
    double hardness; /* the pressure cap H_p (0: none) */
    int cascade;     /* both solvers start from their coarse grids (0: from the local guess) */
    int periodic;    /* a periodic cell under a rigid flat (g0 = max h - h; approach: see run_periodic) */
} scenario;

static im_field *rough_surface(const scenario *c)
{
    im_surface_params params = im_surface_params_default();
    params.nx = c->nx;
    params.ny = c->ny;
    params.lambda_r = c->nx < c->ny ? c->nx : c->ny;
    params.seed = c->seed;
    im_field *surface;
    check_status(im_surface_generate(&params, &surface), "serial synthesis");
    return surface;
}

/* The distributed synthesis gives the serial surface's rows to rounding. */
static void check_synthesis(const scenario *c, const im_field *surface, int y0, int rows, double *heights)
{
    im_surface_params params = im_surface_params_default();
    params.nx = c->nx;
    params.ny = c->ny;
    params.lambda_r = c->nx < c->ny ? c->nx : c->ny;
    params.seed = c->seed;
    check_status(im_mpi_surface_generate(MPI_COMM_WORLD, &params, y0, rows, heights), "distributed synthesis");
    double largest = 0, worst = 0;
    for (size_t i = 0; i < im_field_count(surface); ++i)
        largest = fmax(largest, fabs(surface->data[i]));
    for (size_t i = 0; i < (size_t)rows * c->nx; ++i)
        worst = fmax(worst, fabs(heights[i] - surface->data[(size_t)y0 * c->nx + i]));
    char detail[128];
    snprintf(detail, sizeof detail, "%s: largest height difference %.3g of %.3g", c->name, worst, largest);
    check(worst <= 1e-13 * largest, "synthesis equals im_surface_generate", detail);
}

/* Both solvers run with the defaults (the preconditioner on) at tol 1e-10 on the whole grid, both
 * with or both without the cascade start: they take the same path and their iteration counts compare. */
static im_solver_options options(const scenario *c)
{
    im_solver_options o = im_solver_options_default();
    o.crop = 0;
    o.tol = 1e-10;
    o.cascade = c->cascade;
    o.periodic = c->periodic;
    o.hardness = c->hardness;
    return o;
}

/* Displacement control: w; load control: the smooth N(w), or on a periodic cell p_m nx ny. */
static double target_of(const scenario *c)
{
    if (c->control == IM_CONTROL_LOAD)
        return c->periodic ? c->approach * c->nx * c->ny : im_indenter_load(&c->punch, 1, c->approach);
    return c->approach;
}

/* The largest height of the surface. */
static double highest_of(const im_field *surface)
{
    double highest = -INFINITY;
    for (size_t i = 0; i < im_field_count(surface); ++i)
        highest = fmax(highest, surface->data[i]);
    return highest;
}

/* One distributed problem on the serial surface's rows: the solver, this rank's rows, its undeformed
 * gap, a zero pressure. */
typedef struct distributed_run {
    im_mpi_solver *solver;
    int y0, rows;
    double *gap0, *pressure, *displacement;
} distributed_run;

/* The serial CPU engine's answer to the problem the ranks solve (their undeformed gap gathered on
 * rank 0), shared with every rank: its result and its pressures. */
static void serial_solution(const scenario *c, const distributed_run *d, im_solve_result *serial, im_field **force)
{
    im_field *gap0;
    check_status(im_mpi_gather_map(d->solver, d->gap0, 1, &gap0), "gathered gap");
    check_status(im_field_create(c->nx, c->ny, 1.0, force), "force field");
    if (rank == 0) {
        im_solver_options o = options(c);
        im_solver_plan *plan;
        double *displacement = malloc(sizeof(double) * im_field_count(gap0));
        check_status(im_solver_plan_create(c->nx, c->ny, 1.0, &o, &plan), "serial plan");
        check_status(im_solver_solve(plan, gap0->data, c->control, target_of(c), (*force)->data, displacement,
                                     serial),
                     "serial solve");
        im_solver_plan_free(plan);
        free(displacement);
    }
    MPI_Bcast(serial, sizeof *serial, MPI_BYTE, 0, MPI_COMM_WORLD);
    MPI_Bcast((*force)->data, (int)im_field_count(*force), MPI_DOUBLE, 0, MPI_COMM_WORLD);
    im_field_free(gap0);
}

/* Patches at the cap in the serial answer (0 without a hardness). */
static long capped_patches(const scenario *c, const im_field *force)
{
    long capped = 0;
    for (size_t i = 0; i < im_field_count(force); ++i)
        capped += c->hardness > 0 && force->data[i] == c->hardness;
    return capped;
}

/* value within 1e-10 relative of the serial solver's */
static void check_close(const scenario *c, const char *what, double value, double serial)
{
    char detail[256];
    double relative = fabs(value - serial) / fabs(serial);
    snprintf(detail, sizeof detail, "%s: %s %.17g (serial %.17g), relative difference %.3g", c->name, what, value,
             serial, relative);
    check(relative <= 1e-10, what, detail);
}

/* The same iteration count as the serial solver (the one iteration of solver/pk.c on both), a cap
 * that binds where there is one, and the serial contact set (force: the serial answer, whole). */
static void check_solution(const scenario *c, const im_field *force, int iterations, int serial_iterations,
                           long contact, long serial_contact, const double *pressure, int y0, int rows)
{
    char detail[256];
    snprintf(detail, sizeof detail, "%s: %d iterations (serial %d)", c->name, iterations, serial_iterations);
    check(iterations == serial_iterations, "iterations as the serial solver's", detail);
    snprintf(detail, sizeof detail, "%s: %ld patches at the cap %g", c->name, capped_patches(c, force), c->hardness);
    check((c->hardness > 0) == (capped_patches(c, force) > 0), "a cap that binds", detail);
    long differ = 0;
    for (size_t i = 0; i < (size_t)rows * c->nx; ++i)
        differ += (pressure[i] > 0) != (force->data[(size_t)y0 * c->nx + i] > 0);
    MPI_Allreduce(MPI_IN_PLACE, &differ, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
    snprintf(detail, sizeof detail, "%s: %ld patches differ; %ld in contact (serial %ld)", c->name, differ, contact,
             serial_contact);
    check(differ == 0 && contact == serial_contact, "contact set as the serial solver's", detail);
    check(serial_contact > 20, "a contact of many patches", detail);
}

static void compare(const scenario *c, const im_solve_result *serial, const im_field *force,
                    const im_solve_result *mpi, const double *pressure, int y0, int rows)
{
    check_close(c, "load", mpi->load, serial->load);
    char detail[160];
    snprintf(detail, sizeof detail, "%s: %d coarse iterations (serial %d)", c->name, mpi->coarse_iterations,
             serial->coarse_iterations);
    check(mpi->coarse_iterations == serial->coarse_iterations && (mpi->coarse_iterations > 0) == (c->cascade != 0),
          "coarse iterations as the serial solver's", detail);
    check_solution(c, force, mpi->iterations, serial->iterations, mpi->contact_patches, serial->contact_patches,
                   pressure, y0, rows);
}

/* Rank 0: the whole map (factor 1) is the distributed solution, whose contact set is the serial
 * one; the 5 x 5 map holds its block sums (to rounding: summed here in another order). Returns
 * the 5 x 5 map's total, summed in order, for the bit-for-bit check across rank counts. */
static double check_maps(const scenario *c, const im_field *force, const im_field *whole, const im_field *coarse)
{
    char detail[160];
    snprintf(detail, sizeof detail, "%s: map sizes %d x %d and %d x %d", c->name, whole->nx, whole->ny, coarse->nx,
             coarse->ny);
    check(whole->nx == c->nx && whole->ny == c->ny && coarse->nx == (c->nx + 4) / 5 &&
              coarse->ny == (c->ny + 4) / 5 && coarse->delta == 5.0,
          "map sizes", detail);
    double total = 0, worst = 0;
    for (int by = 0; by < coarse->ny; ++by)
        for (int bx = 0; bx < coarse->nx; ++bx) {
            double sum = 0;
            for (int y = 5 * by; y < 5 * by + 5 && y < c->ny; ++y)
                for (int x = 5 * bx; x < 5 * bx + 5 && x < c->nx; ++x) {
                    size_t i = (size_t)y * c->nx + x;
                    check((whole->data[i] > 0) == (force->data[i] > 0), "whole map's contact set", c->name);
                    sum += whole->data[i];
                }
            double value = coarse->data[(size_t)by * coarse->nx + bx];
            worst = fmax(worst, fabs(value - sum));
            total += value;
        }
    snprintf(detail, sizeof detail, "%s: a block sum differs by %.3g", c->name, worst);
    check(worst <= 1e-13 * total, "5 x 5 map", detail);
    return total;
}

static void distributed_run_create(const scenario *c, const im_field *surface, const im_solver_options *o,
                                   distributed_run *d)
{
    check_status(im_mpi_solver_create(MPI_COMM_WORLD, c->nx, c->ny, 1.0, o, &d->solver), "distributed plan");
    im_mpi_solver_rows(d->solver, &d->y0, &d->rows);
    size_t n = (size_t)d->rows * c->nx + 1;
    d->gap0 = malloc(sizeof(double) * n);
    d->pressure = calloc(n, sizeof(double));
    d->displacement = malloc(sizeof(double) * n);
    if (c->periodic) /* a rigid flat: max h - h */
        for (size_t i = 0; i < (size_t)d->rows * c->nx; ++i)
            d->gap0[i] = highest_of(surface) - surface->data[(size_t)d->y0 * c->nx + i];
    else
        check_status(im_mpi_undeformed_gap(d->solver, surface->data + (size_t)d->y0 * c->nx, &c->punch, d->gap0),
                     "distributed gap");
}

static void distributed_run_free(distributed_run *d)
{
    im_mpi_solver_free(d->solver);
    free(d->gap0);
    free(d->pressure);
    free(d->displacement);
}

static void run_scenario(const scenario *c)
{
    im_field *surface = rough_surface(c);
    im_solver_options o = options(c);
    distributed_run d;
    distributed_run_create(c, surface, &o, &d);
    im_solve_result serial;
    im_field *force;
    serial_solution(c, &d, &serial, &force);
    double *heights = malloc(sizeof(double) * ((size_t)d.rows * c->nx + 1));
    check_synthesis(c, surface, d.y0, d.rows, heights);
    free(heights);
    im_solve_result result;
    check_status(im_mpi_solver_solve(d.solver, d.gap0, c->control, target_of(c), d.pressure, d.displacement, &result),
                 "distributed solve");
    if (!c->periodic) /* a periodic cell has no edge */
        check_status(im_mpi_check_edge(d.solver, d.pressure), "distributed edge check");
    compare(c, &serial, force, &result, d.pressure, d.y0, d.rows);
    im_field *whole, *coarse;
    check_status(im_mpi_gather_map(d.solver, d.pressure, 1, &whole), "whole map");
    check_status(im_mpi_gather_map(d.solver, d.pressure, 5, &coarse), "5 x 5 map");
    check((rank == 0) == (whole != NULL && coarse != NULL), "maps on rank 0 only", c->name);
    if (rank == 0)
        printf("%s load %a contact %ld map %a iterations %d serial-iterations %d coarse %d load-vs-serial %.2g "
               "capped %ld\n",
               c->name, result.load, result.contact_patches, check_maps(c, force, whole, coarse), result.iterations,
               serial.iterations, result.coarse_iterations, fabs(result.load - serial.load) / serial.load,
               capped_patches(c, force));
    im_field_free(whole);
    im_field_free(coarse);
    distributed_run_free(&d);
    im_field_free(force);
    im_field_free(surface);
}

/* The mean of max h - h over the surface: the undeformed cell's mean gap. */
static double undeformed_mean_gap(const im_field *surface)
{
    const double highest = highest_of(surface);
    double sum = 0;
    for (size_t i = 0; i < im_field_count(surface); ++i)
        sum += highest - surface->data[i];
    return sum / (double)im_field_count(surface);
}

/* Nominally flat contact of the periodic cell c->surface: under load control c->approach is the mean
 * pressure p_m, under displacement control the mean gap as a fraction of the undeformed cell's. */
static int flat_solve(const scenario *c, const im_field *surface, void *run, int over_ranks, im_flat_result *out)
{
    if (c->control == IM_CONTROL_LOAD)
        return over_ranks ? im_mpi_flat_contact_solve(run, c->approach, out)
                          : im_flat_contact_solve(run, c->approach, out);
    const double gap = c->approach * undeformed_mean_gap(surface);
    return over_ranks ? im_mpi_flat_contact_solve_gap(run, gap, out) : im_flat_contact_solve_gap(run, gap, out);
}

/* The serial im_flat_contact's answer on rank 0, shared with every rank: its result and pressures. */
static void serial_flat_solution(const scenario *c, const im_field *surface, im_flat_result *serial, im_field **force)
{
    check_status(im_field_create(c->nx, c->ny, 1.0, force), "force field");
    if (rank == 0) {
        im_solver_options o = options(c);
        im_flat_contact *run;
        check_status(im_flat_contact_create(surface, &o, &run), "serial flat contact");
        check_status(flat_solve(c, surface, run, 0, serial), "serial flat solve");
        memcpy((*force)->data, im_flat_contact_pressure(run), sizeof(double) * im_field_count(*force));
        im_flat_contact_free(run);
    }
    MPI_Bcast(serial, sizeof *serial, MPI_BYTE, 0, MPI_COMM_WORLD);
    MPI_Bcast((*force)->data, (int)im_field_count(*force), MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

/* The periodic cell over ranks (im_mpi_flat_contact) against the serial im_flat_contact. */
static void run_periodic(const scenario *c)
{
    im_field *surface = rough_surface(c);
    im_solver_options o = options(c);
    im_mpi_solver *solver;
    int y0, rows;
    check_status(im_mpi_solver_create(MPI_COMM_WORLD, c->nx, c->ny, 1.0, &o, &solver), "periodic distributed plan");
    im_mpi_solver_rows(solver, &y0, &rows);
    im_mpi_flat_contact *run;
    check_status(im_mpi_flat_contact_create(solver, surface->data + (size_t)y0 * c->nx, &run),
                 "distributed flat contact");
    im_flat_result serial, result;
    im_field *force;
    serial_flat_solution(c, surface, &serial, &force);
    check_status(flat_solve(c, surface, run, 1, &result), "distributed flat solve");
    check_close(c, "approach", result.approach, serial.approach);
    check_close(c, "mean pressure", result.mean_pressure, serial.mean_pressure);
    check_close(c, "mean gap", result.mean_gap, serial.mean_gap);
    const double *pressure = im_mpi_flat_contact_pressure(run);
    check_solution(c, force, result.iterations, serial.iterations, result.contact_patches, serial.contact_patches,
                   pressure, y0, rows);
    im_field *whole, *coarse;
    check_status(im_mpi_gather_map(solver, pressure, 1, &whole), "whole map");
    check_status(im_mpi_gather_map(solver, pressure, 5, &coarse), "5 x 5 map");
    if (rank == 0)
        printf("%s approach %a contact %ld map %a iterations %d serial-iterations %d p_m %.6g A/A0 %.4g capped %ld\n",
               c->name, result.approach, result.contact_patches, check_maps(c, force, whole, coarse),
               result.iterations, serial.iterations, result.mean_pressure, result.area_fraction,
               capped_patches(c, force));
    im_field_free(whole);
    im_field_free(coarse);
    im_mpi_flat_contact_free(run);
    im_mpi_solver_free(solver);
    im_field_free(force);
    im_field_free(surface);
}

/* The serial steps of an adhesive periodic cell on rank 0 (im_indentation_step, mean-gap control), shared with
 * every rank: each step's result and net force. */
static void serial_adhesive_steps(const im_field *surface, const im_solver_options *o, const double *gaps, int steps,
                                  im_step_result *serial, im_field **forces)
{
    for (int k = 0; k < steps; ++k)
        check_status(im_field_create(surface->nx, surface->ny, 1.0, &forces[k]), "force field");
    if (rank == 0) {
        const im_indenter flat = im_indenter_flat(100);
        double largest = 0;
        for (int k = 0; k < steps; ++k)
            largest = fmax(largest, gaps[k]);
        im_indentation *run;
        check_status(im_indentation_create(surface, &flat, IM_CONTROL_MEAN_GAP, largest, o, &run), "adhesive cell");
        for (int k = 0; k < steps; ++k) {
            im_field *force;
            check_status(im_indentation_step(run, gaps[k], &serial[k]), "serial adhesive step");
            check_status(im_indentation_fields(run, &force, NULL, NULL), "serial adhesive force");
            memcpy(forces[k]->data, force->data, sizeof(double) * im_field_count(force));
            im_field_free(force);
        }
        im_indentation_free(run);
    }
    MPI_Bcast(serial, (int)sizeof *serial * steps, MPI_BYTE, 0, MPI_COMM_WORLD);
    for (int k = 0; k < steps; ++k)
        MPI_Bcast(forces[k]->data, (int)im_field_count(forces[k]), MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

/* Patches whose net pressure's sign (in contact or pulled, or neither) differs from the serial force's. */
static long sign_differences(const im_field *force, const double *pressure, int y0, int rows)
{
    long differ = 0;
    for (size_t i = 0; i < (size_t)rows * force->nx; ++i) {
        const double serial = force->data[(size_t)y0 * force->nx + i];
        differ += (pressure[i] > 0) != (serial > 0) || (pressure[i] < 0) != (serial < 0);
    }
    MPI_Allreduce(MPI_IN_PLACE, &differ, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
    return differ;
}

/* An adhesive periodic cell over ranks (im_mpi_flat_contact_adhesion) against the serial indentation's steps:
 * an approach, a deeper step and a retraction, each under tension, with the same iterations, loads and tensile
 * forces within 1e-10, and the same patches in contact and in the cohesive zone. */
static void run_adhesive_cell(void)
{
    const scenario c = {"periodic-adhesion-mean-gap-64x48", 64, 48, {0}, IM_CONTROL_MEAN_GAP, 0, 5, 0, 0, 1};
    im_field *surface = rough_surface(&c);
    im_solver_options o = options(&c), adhesive = o;
    adhesive.adhesion_work = 0.004;
    adhesive.adhesion_range = 0.1;
    const double mean_gap = undeformed_mean_gap(surface);
    enum { STEPS = 3 };
    const double gaps[STEPS] = {0.6 * mean_gap, 0.3 * mean_gap, 0.8 * mean_gap};
    im_step_result serial[STEPS], step;
    im_field *forces[STEPS];
    serial_adhesive_steps(surface, &adhesive, gaps, STEPS, serial, forces);
    im_mpi_solver *solver;
    int y0, rows;
    check_status(im_mpi_solver_create(MPI_COMM_WORLD, c.nx, c.ny, 1.0, &o, &solver), "periodic distributed plan");
    im_mpi_solver_rows(solver, &y0, &rows);
    im_mpi_flat_contact *run;
    check_status(im_mpi_flat_contact_create(solver, surface->data + (size_t)y0 * c.nx, &run), "distributed cell");
    check_status(im_mpi_flat_contact_adhesion(run, &adhesive), "adhesion over ranks");
    for (int k = 0; k < STEPS; ++k) {
        check_status(im_mpi_flat_contact_step(run, IM_CONTROL_MEAN_GAP, gaps[k], &step), "adhesive step");
        check_close(&c, "load", step.load, serial[k].load);
        check_close(&c, "tensile force", step.tensile_force, serial[k].tensile_force);
        const long differ = sign_differences(forces[k], im_mpi_flat_contact_pressure(run), y0, rows);
        char detail[256];
        snprintf(detail, sizeof detail,
                 "%s step %d: %d iterations (serial %d), %ld in contact (%ld), %ld pulled (%ld), %ld patches differ",
                 c.name, k + 1, step.iterations, serial[k].iterations, step.contact_patches,
                 serial[k].contact_patches, step.adhesive_patches, serial[k].adhesive_patches, differ);
        check(step.iterations == serial[k].iterations && step.contact_patches == serial[k].contact_patches &&
                  step.adhesive_patches == serial[k].adhesive_patches && differ == 0,
              "adhesive step as the serial one", detail);
        check(step.load < 0 && step.adhesive_patches > step.contact_patches / 2, "a cell under tension", detail);
        if (rank == 0)
            printf("%s step %d load %a iterations %d pulled %ld\n", c.name, k + 1, step.load, step.iterations,
                   step.adhesive_patches);
        im_field_free(forces[k]);
    }
    im_mpi_flat_contact_free(run);
    im_mpi_solver_free(solver);
    im_field_free(surface);
}

/* The stop flag, set on the last rank only, stops every rank at the same iteration with
 * IM_EINTERRUPTED; cleared, the same solve goes on from the pressure it left to the serial answer. */
static void check_stop(const scenario *c)
{
    im_field *surface = rough_surface(c);
    int size;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    static volatile sig_atomic_t stop;
    stop = rank == size - 1 ? SIGINT : 0;
    im_solver_options o = options(c);
    o.stop = &stop;
    distributed_run d;
    distributed_run_create(c, surface, &o, &d);
    im_solve_result serial;
    im_field *force;
    serial_solution(c, &d, &serial, &force);
    im_solve_result result;
    int status = im_mpi_solver_solve(d.solver, d.gap0, c->control, target_of(c), d.pressure, d.displacement, &result);
    char detail[256];
    snprintf(detail, sizeof detail, "%s: status %d (%s), %d iterations", c->name, status, im_last_error(),
             result.iterations);
    check(status == IM_EINTERRUPTED && result.iterations == 0 && strstr(im_last_error(), "signal 2"),
          "a stop flag on one rank stops every rank", detail);
    stop = 0;
    check_status(im_mpi_solver_solve(d.solver, d.gap0, c->control, target_of(c), d.pressure, d.displacement, &result),
                 "the solve resumed after the stop");
    compare(c, &serial, force, &result, d.pressure, d.y0, d.rows);
    distributed_run_free(&d);
    im_field_free(force);
    im_field_free(surface);
}

/* What the MPI engine cannot do is refused on every rank with IM_EUNSUPPORTED naming it, never ignored. */
static void check_refusals(void)
{
    const char *names[] = {"adhesion", "device = gpu"};
    for (int k = 0; k < 2; ++k) {
        im_solver_options o = im_solver_options_default();
        if (k == 0)
            o.adhesion_work = o.adhesion_range = 0.1;
        o.device = k == 1 ? IM_DEVICE_GPU : IM_DEVICE_CPU;
        im_mpi_solver *solver = NULL;
        int status = im_mpi_solver_create(MPI_COMM_WORLD, 32, 32, 1.0, &o, &solver);
        char detail[600];
        snprintf(detail, sizeof detail, "status %d: %s", status, im_last_error());
        check(status == IM_EUNSUPPORTED && solver == NULL && strstr(im_last_error(), names[k]), names[k], detail);
    }
}

static void check_refused(int status, int expected, const char *message, const char *what)
{
    char detail[600];
    snprintf(detail, sizeof detail, "status %d: %s", status, im_last_error());
    check(status == expected && strstr(im_last_error(), message), what, detail);
}

/* A flat contact needs a periodic solver; a periodic cell pressed to a mean gap <= 0 is refused over
 * ranks as by the serial solver, on every rank. */
static void check_periodic_refusals(void)
{
    scenario c = {.name = "periodic-refusals", .nx = 32, .ny = 24, .seed = 8};
    im_field *surface = rough_surface(&c);
    im_solver_options o = options(&c);
    im_mpi_solver *solver;
    int y0, rows;
    check_status(im_mpi_solver_create(MPI_COMM_WORLD, c.nx, c.ny, 1.0, &o, &solver), "half-space plan");
    im_mpi_solver_rows(solver, &y0, &rows);
    im_mpi_flat_contact *run = NULL;
    check_refused(im_mpi_flat_contact_create(solver, surface->data + (size_t)y0 * c.nx, &run), IM_EINVAL,
                  "half-space", "flat contact on a half-space");
    check(run == NULL, "no flat contact on a half-space", c.name);
    im_mpi_solver_free(solver);
    o.periodic = 1;
    check_status(im_mpi_solver_create(MPI_COMM_WORLD, c.nx, c.ny, 1.0, &o, &solver), "periodic plan");
    im_mpi_solver_rows(solver, &y0, &rows); /* the periodic grid's slabs: other rows */
    check_status(im_mpi_flat_contact_create(solver, surface->data + (size_t)y0 * c.nx, &run), "flat contact");
    im_flat_result result;
    check_refused(im_mpi_flat_contact_solve_gap(run, 0, &result), IM_EINVAL, "expected 0 < mean gap", "mean gap 0");
    /* gap0 = 1 everywhere: an approach of 1.5 leaves a mean gap of -0.5 */
    const size_t n = (size_t)rows * c.nx + 1;
    double *gap0 = malloc(sizeof(double) * n), *p = calloc(n, sizeof(double)), *u = malloc(sizeof(double) * n);
    for (size_t i = 0; i < n; ++i)
        gap0[i] = 1;
    check_refused(im_mpi_solver_solve(solver, gap0, IM_CONTROL_DISPLACEMENT, 1.5, p, u, NULL), IM_EINVAL,
                  "its mean gap would be -0.5", "a periodic approach past full contact");
    free(gap0);
    free(p);
    free(u);
    im_mpi_flat_contact_free(run);
    im_mpi_solver_free(solver);
    im_field_free(surface);
}

/* MPI-IO .npy: rows written by the ranks read back by the serial reader, and rows of a file the
 * serial writer made read by the ranks, both to the bit. */
static void check_npy(const char *folder)
{
    scenario c = {.name = "npy", .nx = 37, .ny = 29, .seed = 7};
    im_field *surface = rough_surface(&c);
    int ranks;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    int y0 = c.ny * rank / ranks, rows = c.ny * (rank + 1) / ranks - y0;
    char written[4096], serial_path[4096];
    snprintf(written, sizeof written, "%s/mpi_written_%d.npy", folder, ranks);
    snprintf(serial_path, sizeof serial_path, "%s/serial_%d.npy", folder, ranks);
    check_status(im_mpi_npy_write_rows(MPI_COMM_WORLD, written, c.nx, c.ny, y0, rows,
                                       surface->data + (size_t)y0 * c.nx),
                 "MPI-IO write");
    if (rank == 0)
        check_status(im_npy_write(serial_path, surface, IM_NPY_FLOAT64), "serial write");
    MPI_Barrier(MPI_COMM_WORLD);
    im_field *back;
    check_status(im_npy_read(written, &back), "serial read of the MPI-IO file");
    check(back->nx == c.nx && back->ny == c.ny &&
              memcmp(back->data, surface->data, sizeof(double) * im_field_count(surface)) == 0,
          "MPI-IO write", "the file read back differs from the rows written");
    int nx, ny;
    check_status(im_mpi_npy_shape(MPI_COMM_WORLD, serial_path, &nx, &ny), "MPI-IO shape");
    check(nx == c.nx && ny == c.ny, "MPI-IO shape", "shape differs from the serial file's");
    double *rows_read = malloc(sizeof(double) * ((size_t)rows * nx + 1));
    check_status(im_mpi_npy_read_rows(MPI_COMM_WORLD, serial_path, y0, rows, rows_read), "MPI-IO read");
    check(memcmp(rows_read, surface->data + (size_t)y0 * nx, sizeof(double) * (size_t)rows * nx) == 0, "MPI-IO read",
          "rows differ from the serial file's");
    free(rows_read);
    im_field_free(back);
    im_field_free(surface);
}

int main(int argc, char **argv)
{
    mpi_test_start(&argc, &argv);
    const double w_cone = 3.0, w_sphere = 2.0;
    const scenario cases[] = {
        {"cone-displacement-64x48", 64, 48, im_indenter_cone(80), IM_CONTROL_DISPLACEMENT, w_cone, 1, 0, 0, 0},
        {"cone-load-47x53", 47, 53, im_indenter_cone(80), IM_CONTROL_LOAD, w_cone, 2, 0, 0, 0},
        {"sphere-displacement-96x80", 96, 80, im_indenter_sphere(100), IM_CONTROL_DISPLACEMENT, w_sphere, 3, 0, 0, 0},
        {"sphere-load-50x71", 50, 71, im_indenter_sphere(100), IM_CONTROL_LOAD, w_sphere, 4, 0, 0, 0},
        {"cone-hardness-displacement-64x48", 64, 48, im_indenter_cone(80), IM_CONTROL_DISPLACEMENT, w_cone, 1, 0.12,
         0, 0},
        {"cone-hardness-load-47x53", 47, 53, im_indenter_cone(80), IM_CONTROL_LOAD, w_cone, 2, 0.2, 0, 0},
        /* the cascade's coarse grids have sides of at least 32 */
        {"cone-cascade-displacement-128x96", 128, 96, im_indenter_cone(80), IM_CONTROL_DISPLACEMENT, 6, 7, 0, 1, 0},
        {"sphere-cascade-load-131x100", 131, 100, im_indenter_sphere(200), IM_CONTROL_LOAD, 4, 8, 0, 1, 0},
        {"periodic-cascade-load-128x96", 128, 96, im_indenter_cone(80), IM_CONTROL_LOAD, 0.01, 9, 0, 1, 1},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k)
        run_scenario(&cases[k]);
    const im_indenter flat = {0}; /* unused: a rigid flat */
    const scenario periodic_cases[] = {
        {"periodic-load-64x48", 64, 48, flat, IM_CONTROL_LOAD, 0.01, 5, 0, 0, 1},
        {"periodic-load-47x53", 47, 53, flat, IM_CONTROL_LOAD, 0.02, 6, 0, 0, 1},
        {"periodic-mean-gap-64x48", 64, 48, flat, IM_CONTROL_DISPLACEMENT, 0.5, 5, 0, 0, 1},
        {"periodic-hardness-load-64x48", 64, 48, flat, IM_CONTROL_LOAD, 0.02, 5, 0.1, 0, 1},
        {"periodic-cascade-load-128x128", 128, 128, flat, IM_CONTROL_LOAD, 0.005, 10, 0, 1, 1},
        {"periodic-cascade-mean-gap-128x96", 128, 96, flat, IM_CONTROL_DISPLACEMENT, 0.5, 11, 0, 1, 1},
    };
    for (size_t k = 0; k < sizeof periodic_cases / sizeof periodic_cases[0]; ++k)
        run_periodic(&periodic_cases[k]);
    run_adhesive_cell();
    check_stop(&cases[1]);
    check_refusals();
    check_periodic_refusals();
    check_npy(argc > 1 ? argv[1] : ".");
    im_mpi_cleanup();
    MPI_Finalize();
    return 0;
}
