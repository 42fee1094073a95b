/* Shared helpers for benchmarks: wall clock, medians, peak memory, a hash of answers. */
#ifndef INDENTMAP_BENCH_COMMON_H
#define INDENTMAP_BENCH_COMMON_H

#include <stdlib.h>
#include <sys/resource.h>
#include <time.h>

static inline double bench_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int bench_compare(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of n values (sorts them in place). */
static inline double bench_median(double *values, int n)
{
    qsort(values, (size_t)n, sizeof *values, bench_compare);
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/* Peak resident set size of this process so far, in MiB. */
static inline double bench_peak_rss_mib(void)
{
    struct rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    return (double)usage.ru_maxrss / 1024.0;
}

/* FNV-1a over the bytes of n doubles: equal hashes, bit-identical answers (in practice). */
static inline unsigned long long bench_bits_hash(const double *v, size_t n)
{
    const unsigned char *bytes = (const unsigned char *)v;
    unsigned long long h = 14695981039346656037ull;
    for (size_t i = 0; i < n * sizeof(double); ++i)
        h = (h ^ bytes[i]) * 1099511628211ull;
    return h;
}

#endif
