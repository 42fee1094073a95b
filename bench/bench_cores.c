/* What T threads can gain over one on this machine at best (not a test): the ceiling against which
 * issue 15's "two threads >= 1.8x one thread" is read.
 *
 *   bench_cores [--threads T] [--repeats R] [--mib M]
 *
 * Two kernels with no serial part, each timed at 1 thread and at T threads on the same total work,
 * alternated R times (default 5):
 *   registers: 32 independent multiply-add chains per thread (enough to keep the floating-point units
 *              busy rather than wait on each chain), no memory traffic, one parallel region; the gain
 *              of arithmetic alone. Two virtual CPUs that the host runs on the two hardware
 *              threads of one physical core share its floating-point units and gain about 1x here;
 *              on two cores, about 2x.
 *   stream:    a[i] = b[i] + s * c[i] over three arrays of M MiB each (default 3.5: one array of the
 *              padded window of a 512^2 solve), static schedule, as the solver's loops; the gain of
 *              memory traffic.
 * Prints one line per repeat (the two wall times in ms, the gain, the CPU ratio and their product, see
 * record()) and the medians: what the machine gives a program with nothing serial in it, beside which
 * bench/run_threads.sh's ratios are read.
 */
#include "bench_common.h"

#include <omp.h>
#include <stdio.h>
#include <string.h>

#define CHAINS 32
#define MAX_REPEATS 101
#define REGISTER_STEPS 120000000L /* about 0.5 s at one thread on the project's 2-core VM */

static volatile double sink; /* keeps the kernels' results alive */

typedef struct {
    double wall, cpu; /* seconds; CPU time of the whole process, all threads */
} run_time;

static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* steps iterations of CHAINS independent x = x * m + c chains; returns their sum. */
static double register_chains(long steps)
{
    double x[CHAINS];
    for (int k = 0; k < CHAINS; k++)
        x[k] = 1.0 + k;
    for (long i = 0; i < steps; i++)
        for (int k = 0; k < CHAINS; k++)
            x[k] = x[k] * 0.999999 + 1e-7;
    double sum = 0.0;
    for (int k = 0; k < CHAINS; k++)
        sum += x[k];
    return sum;
}

static run_time time_registers(int threads)
{
    double sum = 0.0, wall = bench_now(), cpu = cpu_now();
#pragma omp parallel num_threads(threads) reduction(+ : sum)
    sum += register_chains(REGISTER_STEPS / omp_get_num_threads());
    run_time t = {bench_now() - wall, cpu_now() - cpu};
    sink = sum;
    return t;
}

typedef struct {
    double *a, *b, *c;
    long n;
} stream_arrays;

static run_time time_stream(const stream_arrays *s, int threads, int sweeps)
{
    double wall = bench_now(), cpu = cpu_now();
    for (int sweep = 0; sweep < sweeps; sweep++) {
#pragma omp parallel for num_threads(threads) schedule(static)
        for (long i = 0; i < s->n; i++)
            s->a[i] = s->b[i] + 0.5 * s->c[i];
    }
    run_time t = {bench_now() - wall, cpu_now() - cpu};
    sink = s->a[s->n / 2];
    return t;
}

typedef struct {
    const char *name;
    double one[MAX_REPEATS], many[MAX_REPEATS], gain[MAX_REPEATS], cpu_ratio[MAX_REPEATS], estimate[MAX_REPEATS];
} kernel_times;

/* One repeat: the gain (wall time at 1 thread / at T), the CPU ratio (CPU time at T / at 1: the same
 * work, so above 1 only by what slows each thread when T run) and their product, which stays near T
 * for these kernels whatever the machine does, as bench/run_threads.sh's quiet estimate assumes. */
static void record(kernel_times *k, int repeat, run_time one, run_time many)
{
    k->one[repeat] = one.wall;
    k->many[repeat] = many.wall;
    k->gain[repeat] = one.wall / many.wall;
    k->cpu_ratio[repeat] = many.cpu / one.cpu;
    k->estimate[repeat] = k->gain[repeat] * k->cpu_ratio[repeat];
    printf("%s,%d,%.2f,%.2f,%.3f,%.3f,%.3f\n", k->name, repeat + 1, 1e3 * one.wall, 1e3 * many.wall, k->gain[repeat],
           k->cpu_ratio[repeat], k->estimate[repeat]);
}

static void print_medians(kernel_times *k, int repeats)
{
    printf("%s,median,%.2f,%.2f,%.3f,%.3f,%.3f\n", k->name, 1e3 * bench_median(k->one, repeats),
           1e3 * bench_median(k->many, repeats), bench_median(k->gain, repeats), bench_median(k->cpu_ratio, repeats),
           bench_median(k->estimate, repeats));
}

static int parse_args(int argc, char **argv, int *threads, int *repeats, double *mib)
{
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--threads"))
            *threads = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--repeats"))
            *repeats = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--mib"))
            *mib = atof(argv[i + 1]);
        else
            return 0;
    }
    return argc % 2 == 1 && *threads >= 1 && *repeats >= 1 && *repeats <= MAX_REPEATS && *mib > 0.0;
}

int main(int argc, char **argv)
{
    int threads = 2, repeats = 5;
    double mib = 3.5;
    if (!parse_args(argc, argv, &threads, &repeats, &mib)) {
        fprintf(stderr, "usage: bench_cores [--threads T >= 1] [--repeats 1..%d] [--mib M > 0]\n", MAX_REPEATS);
        return 2;
    }
    stream_arrays s = {.n = (long)(mib * 1048576.0 / sizeof(double))};
    s.a = malloc((size_t)s.n * sizeof(double));
    s.b = malloc((size_t)s.n * sizeof(double));
    s.c = malloc((size_t)s.n * sizeof(double));
    if (!s.a || !s.b || !s.c || s.n < 1) {
        fprintf(stderr, "bench_cores: cannot allocate three arrays of %.1f MiB\n", mib);
        return 1;
    }
    for (long i = 0; i < s.n; i++)
        s.a[i] = 0.0, s.b[i] = 1.0, s.c[i] = (double)(i % 7);
    time_stream(&s, 1, 1); /* the first sweep pays the arrays' page faults */
    double per_sweep = time_stream(&s, 1, 1).wall;
    int sweeps = per_sweep > 0.0 && per_sweep < 0.5 ? (int)(0.5 / per_sweep) + 1 : 1;

    printf("# bench_cores: %d threads against 1, %d repeats; stream: 3 x %.1f MiB, %d sweeps\n", threads, repeats,
           mib, sweeps);
    printf("kernel,repeat,one_thread_ms,threads_ms,gain,cpu_ratio,gain_x_cpu_ratio\n");
    kernel_times registers = {.name = "registers"}, stream = {.name = "stream"};
    for (int r = 0; r < repeats; r++) {
        run_time one = time_registers(1);
        record(&registers, r, one, time_registers(threads));
        one = time_stream(&s, 1, sweeps);
        record(&stream, r, one, time_stream(&s, threads, sweeps));
    }
    print_medians(&registers, repeats);
    print_medians(&stream, repeats);
    free(s.a);
    free(s.b);
    free(s.c);
    return 0;
}
