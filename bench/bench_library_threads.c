/* A library user's solves at a thread count (issue 33, "threads that hold for library users"): not a test.
 *
 *   bench_library_threads [--n N] [--threads T]
 *
 * What a C program linking libindentmap does, through the public API only: a rough surface n x n (H 0.8,
 * lambda_s 4, lambda_r n, h'rms 0.08, seed 1), then (1) a cold 80 deg cone solve to the approach whose
 * smooth contact radius is n/5 (bench_cold's configuration) and (2) a periodic flat contact of the same
 * surface at mean pressure 0.004 E* (about 10% contact), both at tol 1e-8. --threads calls
 * omp_set_num_threads, as a program would (default: OpenMP's own count). Prints one CSV line per solve:
 *
 *   solve,n,threads,wall_s,cpu_s,iterations,result,contact_patches
 *
 * wall and CPU (the process's, all threads) time of the solve alone, planning apart; the result (the
 * cone's load, the periodic cell's approach) with 17 significant digits so that runs at different thread
 * counts can be compared bit for bit.
 * bench/run_library_threads.sh runs it beside a busy process and quiet, and compares.
 */
#include "bench_common.h"
#include "bench_recipe.h"
#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>

static void die(int status, const char *what)
{
    fprintf(stderr, "bench_library_threads: %s: %s (%s)\n", what, im_last_error(), im_strstatus(status));
    exit(1);
}

static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct timing {
    double wall, cpu;
} timing;

static timing timing_start(void) { return (timing){bench_now(), cpu_now()}; }

static void print_solve(const char *solve, int n, timing start, long iterations, double result, long contact)
{
    printf("%s,%d,%d,%.4f,%.4f,%ld,%.17g,%ld\n", solve, n, omp_get_max_threads(), bench_now() - start.wall,
           cpu_now() - start.cpu, iterations, result, contact);
}

static void cone_solve(const im_field *surface, const im_solver_options *o)
{
    const int n = surface->nx;
    /* Love's cone: a = 2 w tan(alpha) / pi, so a = n / 5 at w = pi n cot(alpha) / 10 */
    const double approach = M_PI * n / (10 * tan(80 * M_PI / 180));
    im_indenter cone = im_indenter_cone(80);
    im_indentation *run = NULL;
    int status = im_indentation_create(surface, &cone, IM_CONTROL_DISPLACEMENT, approach, o, &run);
    if (status != IM_OK)
        die(status, "im_indentation_create");
    im_step_result r;
    timing start = timing_start();
    if ((status = im_indentation_step(run, approach, &r)) != IM_OK)
        die(status, "im_indentation_step");
    print_solve("cone", n, start, r.iterations, r.load, r.contact_patches);
    im_indentation_free(run);
}

static void periodic_solve(const im_field *surface, const im_solver_options *o)
{
    im_flat_contact *run = NULL;
    int status = im_flat_contact_create(surface, o, &run);
    if (status != IM_OK)
        die(status, "im_flat_contact_create");
    im_flat_result r;
    timing start = timing_start();
    if ((status = im_flat_contact_solve(run, 0.004, &r)) != IM_OK)
        die(status, "im_flat_contact_solve");
    print_solve("periodic", surface->nx, start, r.iterations, r.approach, r.contact_patches);
    im_flat_contact_free(run);
}

int main(int argc, char **argv)
{
    int n = 512, threads = 0;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--n") == 0 && i + 1 < argc)
            n = atoi(argv[++i]);
        else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc)
            threads = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_library_threads [--n N] [--threads T]\n");
            return 2;
        }
    }
    if (n < 64 || threads < 0) {
        fprintf(stderr, "bench_library_threads: expected --n >= 64 and --threads >= 1\n");
        return 2;
    }
    if (threads)
        omp_set_num_threads(threads);
    im_field *surface;
    int status = bench_paper_surface(n, &surface);
    if (status != IM_OK)
        die(status, "im_surface_generate");
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8;
    cone_solve(surface, &o);
    periodic_solve(surface, &o);
    im_field_free(surface);
    return 0;
}
