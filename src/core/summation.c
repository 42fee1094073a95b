/* Compensated block sums (see summation.h). */
#include "core/summation.h"

#include <math.h>

double sum_doubles_range(const double *v, size_t lo, size_t hi)
{
    compensated c = {0, 0};
    for (size_t i = lo; i < hi; ++i)
        compensated_add(&c, v[i]);
    return compensated_total(&c);
}

static double range_sum(size_t lo, size_t hi, const void *context) { return sum_doubles_range(context, lo, hi); }

/* term and its context, for terms_sum. */
typedef struct terms {
    double (*term)(size_t, const void *);
    const void *context;
} terms;

/* Compensated sum of term(i) over [lo, hi). */
static double terms_sum(size_t lo, size_t hi, const void *context)
{
    const terms *t = context;
    compensated c = {0, 0};
    for (size_t i = lo; i < hi; ++i)
        compensated_add(&c, t->term(i, t->context));
    return compensated_total(&c);
}

/* The blocks' layout: the block length grows with n so that the block sums fit on the stack. */
static size_t block_length(size_t n)
{
    const size_t shortest = (n + IM_SUM_MAX_BLOCKS - 1) / IM_SUM_MAX_BLOCKS;
    return shortest > IM_SUM_BLOCK ? shortest : IM_SUM_BLOCK;
}

static double combine(const double *block, size_t blocks)
{
    compensated total = {0, 0};
    for (size_t b = 0; b < blocks; ++b)
        compensated_add(&total, block[b]);
    return compensated_total(&total);
}

/* Blocks summed in parallel, then combined in block order, so the result does not depend on the
 * thread count. */
double sum_ranges(size_t n, double (*range)(size_t lo, size_t hi, const void *context), const void *context)
{
    const size_t length = block_length(n), blocks = (n + length - 1) / length;
    double block[IM_SUM_MAX_BLOCKS];
#pragma omp parallel for schedule(static)
    for (size_t b = 0; b < blocks; ++b)
        block[b] = range(b * length, b + 1 < blocks ? (b + 1) * length : n, context);
    return combine(block, blocks);
}

double sum_doubles(const double *v, size_t n) { return sum_ranges(n, range_sum, v); }

double sum_terms(size_t n, double (*term)(size_t i, const void *context), const void *context)
{
    const terms t = {term, context};
    return sum_ranges(n, terms_sum, &t);
}
