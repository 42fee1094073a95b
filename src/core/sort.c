#include "core/sort.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void sort_doubles(double *values, size_t count) { qsort(values, count, sizeof *values, compare_doubles); }

/* (sort.h) Wirth's selection: Hoare's partition, which splits ties such as a scan's row of zeros evenly,
 * with the median of three as pivot. Signed indices: j runs to left - 1. */
void select_doubles(double *values, size_t count, size_t k)
{
    ptrdiff_t left = 0, right = (ptrdiff_t)count - 1, kth = (ptrdiff_t)k;
    while (left < right) {
        const double a = values[left], b = values[left + (right - left) / 2], c = values[right];
        const double pivot = fmax(fmin(a, b), fmin(fmax(a, b), c));
        ptrdiff_t i = left, j = right;
        do {
            while (values[i] < pivot)
                ++i;
            while (pivot < values[j])
                --j;
            if (i <= j) {
                const double swap = values[i];
                values[i++] = values[j];
                values[j--] = swap;
            }
        } while (i <= j);
        if (j < kth)
            left = i;
        if (kth < i)
            right = j;
    }
}
