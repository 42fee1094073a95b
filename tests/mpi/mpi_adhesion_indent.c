/* Adhesive indentation of the half-space over ranks (im_mpi_indentation_*) against the serial indentation
 * (im_indentation_* on the whole surface, crop = 0), run under mpirun with 1, 2, 3 and 4 ranks
 * (tests/mpi/mpi_solver.sh; of 2 ranks the first holds every surface row, 3 and 4 cut them): rank 0 runs the serial history and shares its steps; every rank checks the
 * distributed steps against them: net loads and tensile forces to 1e-9 relative, the same patches in
 * repulsive contact and under tension, the same iteration counts (the adhesive passes and the solves make
 * the same decisions on every rank: their sums are row-ordered), the same pull-off, jump-in and jump-out
 * (im_measure_adhesion). Cases: a smooth adhesive sphere (Maugis-Dugdale, lambda = 1) and a rough cone
 * (Maugis-Dugdale, and the exponential law), each an approach and a retraction through the pull-off. Prints
 * one line per step with the load and tensile force in hexadecimal, so that the script can check that they
 * are the same bits for every rank count. A failed check aborts all ranks. */
#include "mpi_check.h"

#include "indentmap/measure.h"
#include "indentmap/mpi.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

enum { STEPS_MAX = 16 };

typedef struct history_case {
    const char *name;
    int nx, ny;
    unsigned seed; /* 0: a flat surface */
    im_indenter punch;
    double work, range;
    int law;
    int steps;
    double approaches[STEPS_MAX]; /* an approach, then a retraction through the pull-off */
} history_case;

static im_field *surface_of(const history_case *c)
{
    im_field *surface;
    if (c->seed == 0) {
        check_status(im_field_create(c->nx, c->ny, 1.0, &surface), "flat surface");
        return surface;
    }
    im_surface_params params = im_surface_params_default();
    params.nx = c->nx;
    params.ny = c->ny;
    params.lambda_r = c->nx < c->ny ? c->nx : c->ny;
    params.seed = c->seed;
    check_status(im_surface_generate(&params, &surface), "rough surface");
    return surface;
}

/* The repulsive solver's options (no adhesion: a plan's, as a serial indentation makes it) at tol 1e-8, and
 * the case's adhesion beside them. */
static im_solver_options solver_options(void)
{
    im_solver_options o = im_solver_options_default();
    o.crop = 0;
    o.tol = 1e-8;
    return o;
}

static im_solver_options adhesive_options(const history_case *c)
{
    im_solver_options o = solver_options();
    o.adhesion_work = c->work;
    o.adhesion_range = c->range;
    o.adhesion_law = c->law;
    return o;
}

/* Rank 0's serial history, shared with every rank. */
/* The history's largest |approach|: the runs' largest target. */
static double largest_approach(const history_case *c)
{
    double largest = 0;
    for (int k = 0; k < c->steps; ++k)
        largest = fmax(largest, fabs(c->approaches[k]));
    return largest;
}

static void serial_history(const history_case *c, const im_field *surface, im_step_result *steps)
{
    if (rank == 0) {
        const im_solver_options o = adhesive_options(c);
        im_indentation *run;
        check_status(im_indentation_create(surface, &c->punch, IM_CONTROL_DISPLACEMENT, largest_approach(c), &o,
                                           &run),
                     "serial indentation");
        for (int k = 0; k < c->steps; ++k)
            check_status(im_indentation_step(run, c->approaches[k], &steps[k]), "serial step");
        im_indentation_free(run);
    }
    MPI_Bcast(steps, (int)sizeof *steps * c->steps, MPI_BYTE, 0, MPI_COMM_WORLD);
}

/* value within 1e-9 of the serial one, relative to the serial step's largest force (its load or tension). */
static void check_close(const char *what, double value, double serial, double scale, const char *detail)
{
    char line[1024];
    snprintf(line, sizeof line, "%s: %s %.17g (serial %.17g)", detail, what, value, serial);
    check(fabs(value - serial) <= 1e-9 * scale, what, line);
}

static void check_step(const history_case *c, int k, const im_step_result *mpi, const im_step_result *serial)
{
    char detail[512];
    snprintf(detail, sizeof detail,
             "%s step %d (approach %g): %d iterations (serial %d), %ld in contact (%ld), %ld pulled (%ld), %ld "
             "pushed (%ld)",
             c->name, k + 1, c->approaches[k], mpi->iterations, serial->iterations, mpi->contact_patches,
             serial->contact_patches, mpi->adhesive_patches, serial->adhesive_patches, mpi->repulsive_patches,
             serial->repulsive_patches);
    const double scale = fmax(fabs(serial->load), serial->tensile_force);
    check_close("net load", mpi->load, serial->load, scale, detail);
    check_close("tensile force", mpi->tensile_force, serial->tensile_force, scale, detail);
    check(mpi->iterations == serial->iterations && mpi->contact_patches == serial->contact_patches &&
              mpi->adhesive_patches == serial->adhesive_patches &&
              mpi->repulsive_patches == serial->repulsive_patches,
          "the serial step's iterations and patches", detail);
}

static int same_approach(double a, double b) { return a == b || (isnan(a) && isnan(b)); }

/* The pull-off, jump-in and jump-out of the history, as im_measure_adhesion finds them in each. */
static void check_summary(const history_case *c, const im_step_result *mpi, const im_step_result *serial)
{
    double approach[STEPS_MAX], load[2][STEPS_MAX];
    long contact[2][STEPS_MAX];
    for (int k = 0; k < c->steps; ++k) {
        approach[k] = c->approaches[k];
        load[0][k] = mpi[k].load;
        load[1][k] = serial[k].load;
        contact[0][k] = mpi[k].contact_patches;
        contact[1][k] = serial[k].contact_patches;
    }
    im_adhesion_summary summary[2];
    for (int h = 0; h < 2; ++h)
        check_status(im_measure_adhesion(approach, load[h], contact[h], c->steps, 0, &summary[h]),
                     "adhesion summary");
    char detail[512];
    snprintf(detail, sizeof detail, "%s: pull-off %.17g at %g (serial %.17g at %g), jump-in %g (%g), out %g (%g)",
             c->name, summary[0].pull_off_force, summary[0].pull_off_approach, summary[1].pull_off_force,
             summary[1].pull_off_approach, summary[0].jump_in_approach, summary[1].jump_in_approach,
             summary[0].jump_out_approach, summary[1].jump_out_approach);
    check(isfinite(summary[1].jump_out_approach) && summary[1].pull_off_force > 0,
          "a retraction through the pull-off", detail);
    check_close("pull-off force", summary[0].pull_off_force, summary[1].pull_off_force, summary[1].pull_off_force,
                detail);
    check(same_approach(summary[0].pull_off_approach, summary[1].pull_off_approach) &&
              same_approach(summary[0].jump_in_approach, summary[1].jump_in_approach) &&
              same_approach(summary[0].jump_out_approach, summary[1].jump_out_approach),
          "the serial history's pull-off and jumps", detail);
    if (rank == 0)
        printf("%s pull-off %a at %g\n", c->name, summary[0].pull_off_force, summary[0].pull_off_approach);
}

static void run_case(const history_case *c)
{
    im_field *surface = surface_of(c);
    im_step_result serial[STEPS_MAX], mpi[STEPS_MAX];
    serial_history(c, surface, serial);
    const im_solver_options o = solver_options(), adhesion = adhesive_options(c);
    im_mpi_solver *solver;
    int y0, rows;
    check_status(im_mpi_solver_create(MPI_COMM_WORLD, c->nx, c->ny, 1.0, &o, &solver), "distributed plan");
    im_mpi_solver_rows(solver, &y0, &rows);
    im_mpi_indentation *run;
    check_status(im_mpi_indentation_create(solver, surface->data + (size_t)y0 * c->nx, &c->punch,
                                           IM_CONTROL_DISPLACEMENT, largest_approach(c), &adhesion, &run),
                 "distributed indentation");
    for (int k = 0; k < c->steps; ++k) {
        check_status(im_mpi_indentation_step(run, c->approaches[k], &mpi[k]), "distributed step");
        check_step(c, k, &mpi[k], &serial[k]);
        if (rank == 0)
            printf("%s step %d load %a tensile %a iterations %d pulled %ld\n", c->name, k + 1, mpi[k].load,
                   mpi[k].tensile_force, mpi[k].iterations, mpi[k].adhesive_patches);
    }
    check_summary(c, mpi, serial);
    im_mpi_indentation_free(run);
    im_mpi_solver_free(solver);
    im_field_free(surface);
}

int main(int argc, char **argv)
{
    mpi_test_start(&argc, &argv);
    /* The sphere: reduced radius L = 3 patches (R = 8 L, w = K L^3 / (pi R^2)), lambda = 1 (sigma0 = lambda / 2
     * (pi w K^2 / R)^(1/3)); approaches in units of L^2 / R = 0.375 to D = 1.5, back to D = -1.6. */
    const double radius = 24, work = 4.0 / 3.0 * 27 / (M_PI * radius * radius);
    const double stress = 0.5 * cbrt(M_PI * work * 16.0 / 9.0 / radius);
    const history_case cases[] = {
        {"sphere-maugis-dugdale-48x48",
         48,
         48,
         0,
         im_indenter_sphere(radius),
         work,
         work / stress,
         IM_ADHESION_MAUGIS_DUGDALE,
         10,
         {0.1, 0.3, 0.56, 0.3, 0, -0.15, -0.3, -0.45, -0.6, -0.75}},
        {"rough-cone-maugis-dugdale-64x48",
         64,
         48,
         3,
         im_indenter_cone(80),
         0.02,
         0.2,
         IM_ADHESION_MAUGIS_DUGDALE,
         9,
         {0.5, 1.5, 2.5, 1.5, 0.5, 0, -0.1, -0.2, -0.3}},
        {"rough-cone-exponential-47x53",
         47,
         53,
         5,
         im_indenter_cone(80),
         0.01,
         0.04,
         IM_ADHESION_EXPONENTIAL,
         7,
         {0.5, 1.5, 0.8, 0, -0.1, -0.2, -0.3}},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k)
        run_case(&cases[k]);
    im_mpi_cleanup();
    MPI_Finalize();
    return 0;
}
