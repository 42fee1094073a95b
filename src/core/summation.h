/* Internal: accurate sums over whole grids (loads, forces, areas of up to 2^32 patches).
 *
 * A plain running sum of n values loses up to n ulp: over the 16.8 million patches of a 4096^2
 * grid that is 2e-9 relative in double and everything in single precision (a float accumulator
 * stops growing at 2^24 times the addend). Single-precision data (float32 .npy files) are
 * widened to double by the readers and summed here like any other. These sums use Neumaier's
 * compensated summation inside at most IM_SUM_MAX_BLOCKS blocks of at least IM_SUM_BLOCK values,
 * summed in parallel, and then combine the block sums with compensation in block order: the error
 * is a few ulp of the result whatever n, and the result is the same bit for bit for any thread
 * count (the blocks depend on n only). Nothing is allocated: the solver sums every iteration. */
#ifndef INDENTMAP_CORE_SUMMATION_H
#define INDENTMAP_CORE_SUMMATION_H

#include <math.h>
#include <stddef.h>

/* Neumaier's running sum: sum + compensation carries the low-order bits that sum drops. */
typedef struct compensated {
    double sum, compensation;
} compensated;

static inline void compensated_add(compensated *c, double x)
{
    double t = c->sum + x;
    c->compensation += fabs(c->sum) >= fabs(x) ? (c->sum - t) + x : (x - t) + c->sum;
    c->sum = t;
}

static inline double compensated_total(const compensated *c) { return c->sum + c->compensation; }

/* The sample standard deviation (n - 1 in the denominator) of n values from their sum and sum of
 * squares; NaN below two values: one surface has no spread to estimate, and 0 would claim an exact
 * ensemble (the tables and fig. 7 print nan, and draw no error bar). */
static inline double sample_sd(double sum, double sum_squares, int n)
{
    if (n < 2)
        return NAN;
    double mean = sum / n;
    return sqrt(fmax(0.0, (sum_squares - n * mean * mean) / (n - 1)));
}

#define IM_SUM_BLOCK 4096
#define IM_SUM_MAX_BLOCKS 1024

/* Sum of v[0..n) in double precision, compensated. */
double sum_doubles(const double *v, size_t n);

/* Sum of term(i, context) over i in [0, n), the same way (for values no array holds). */
double sum_terms(size_t n, double (*term)(size_t i, const void *context), const void *context);

/* The same sum of values made range by range: range(lo, hi, context) returns the compensated sum
 * (sum_doubles_range) of the values of [lo, hi), for blocks [lo, hi) that depend on n only, called in
 * parallel. A pass that makes values (and stores them) can so sum them while they are in cache, to
 * sum_doubles' bits on the values stored. */
double sum_ranges(size_t n, double (*range)(size_t lo, size_t hi, const void *context), const void *context);

/* The compensated sum of v[lo..hi) in index order (compensated_add from zero, then compensated_total):
 * one block of sum_doubles. */
double sum_doubles_range(const double *v, size_t lo, size_t hi);

#endif
