/* Gap and patch-size distributions at one state (measure.h). */
#include "indentmap/io.h"
#include "core/args.h"
#include "indentmap/measure.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int in_contact(const im_field *force, size_t i) { return force->data[i] > 0; }

/* Union-find with path halving; the smaller index is the root, so roots come in order of
 * appearance. */
static long root_of(long *parent, long i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

static void join(long *parent, long a, long b)
{
    a = root_of(parent, a);
    b = root_of(parent, b);
    if (a != b)
        parent[a > b ? a : b] = a < b ? a : b;
}

/* Edges of contacting cell (ix, iy) that face no contact or the border. */
static int free_edges(const im_field *f, int ix, int iy)
{
    const int nx = f->nx, ny = f->ny;
    const double *d = f->data + (size_t)iy * nx + ix;
    return (ix == 0 || !(d[-1] > 0)) + (ix == nx - 1 || !(d[1] > 0)) + (iy == 0 || !(d[-nx] > 0)) +
           (iy == ny - 1 || !(d[nx] > 0));
}

/* Labels the contact's cells: parent[] of every cell, the root's cells and edges summed into
 * cells[] and edges[] (indexed by cell). */
static void label(const im_field *force, long *parent, long *cells, long *edges)
{
    const int nx = force->nx, ny = force->ny;
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix) {
            long i = (long)iy * nx + ix;
            parent[i] = i;
            if (!in_contact(force, (size_t)i))
                continue;
            if (ix > 0 && in_contact(force, (size_t)i - 1))
                join(parent, i, i - 1);
            if (iy > 0 && in_contact(force, (size_t)(i - nx)))
                join(parent, i, i - nx);
        }
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix) {
            long i = (long)iy * nx + ix;
            if (!in_contact(force, (size_t)i))
                continue;
            long r = root_of(parent, i);
            ++cells[r];
            edges[r] += free_edges(force, ix, iy);
        }
}

int im_measure_patch_list(const im_field *force, im_patch **patches, long *count)
{
    ARG_VIEW(force, "force");
    ARG_REQUIRE(patches, "patches");
    ARG_REQUIRE(count, "count");
    if (!force || !force->data || !patches || !count)
        return im_fail(IM_EINVAL, "patch list: no force field or outputs");
    const size_t n = im_field_count(force);
    long *parent = malloc(sizeof *parent * n), *cells = calloc(n, sizeof *cells), *edges = calloc(n, sizeof *edges);
    int status = parent && cells && edges ? IM_OK
                                          : im_fail(IM_ENOMEM, "patch list of a %d x %d field", force->nx, force->ny);
    long found = 0;
    im_patch *list = NULL;
    if (status == IM_OK) {
        label(force, parent, cells, edges);
        for (size_t i = 0; i < n; ++i)
            found += cells[i] > 0;
        list = found > 0 ? malloc(sizeof *list * (size_t)found) : NULL;
        if (found > 0 && !list)
            status = im_fail(IM_ENOMEM, "patch list (%ld patches)", found);
    }
    for (size_t i = 0, k = 0; status == IM_OK && i < n; ++i)
        if (cells[i] > 0)
            list[k++] = (im_patch){cells[i], edges[i]};
    free(parent);
    free(cells);
    free(edges);
    if (status == IM_OK) {
        *patches = list;
        *count = found;
    }
    return status;
}

int im_measure_patch_histogram(const im_patch *list, long count, long *patches, long *cells, long *edges)
{
    if (count < 0)
        return im_fail(IM_EINVAL, "im_measure_patch_histogram: count = %ld: expected >= 0", count);
    if (count > 0 && !list) /* (no contact: no list, count 0) */
        return im_fail(IM_EINVAL, "im_measure_patch_histogram: list is NULL for %ld patches: expected a pointer",
                       count);
    if (count > 0 && (!patches || !cells || !edges))
        return im_fail(IM_EINVAL, "patch histogram: NULL arrays for %ld patches", count);
    if (patches && cells && edges) {
        memset(patches, 0, sizeof *patches * IM_PATCH_BINS);
        memset(cells, 0, sizeof *cells * IM_PATCH_BINS);
        memset(edges, 0, sizeof *edges * IM_PATCH_BINS);
    }
    for (long i = 0; i < count; ++i) {
        if (list[i].cells < 1)
            return im_fail(IM_EINVAL, "patch histogram: patch %ld has %ld cells: expected at least 1", i,
                           list[i].cells);
        int bin = 0;
        while (bin < IM_PATCH_BINS - 1 && list[i].cells >= 2L << bin)
            ++bin;
        ++patches[bin];
        cells[bin] += list[i].cells;
        edges[bin] += list[i].edges;
    }
    return IM_OK;
}

/* The largest finite gap outside contact (0 if none); IM_EINVAL for a NaN there. */
static int largest_free_gap(const im_field *gap, const im_field *force, double *largest)
{
    *largest = 0.0;
    for (size_t i = 0; i < im_field_count(gap); ++i) {
        if (in_contact(force, i))
            continue;
        if (isnan(gap->data[i]))
            return im_fail(IM_EINVAL, "gap distribution: NaN gap at cell %zu outside contact", i);
        if (isfinite(gap->data[i]) && gap->data[i] > *largest)
            *largest = gap->data[i];
    }
    return IM_OK;
}

int im_measure_gap_distribution(const im_field *gap, const im_field *force, double scale, int bins, long *counts,
                                double *bin_width, long *infinite)
{
    ARG_VIEW(gap, "gap");
    ARG_VIEW(force, "force");
    ARG_REQUIRE(counts, "counts");
    ARG_REQUIRE(bin_width, "bin_width");
    ARG_REQUIRE(infinite, "infinite");
    if (!gap || !force || !gap->data || !force->data || !counts || !bin_width || !infinite)
        return im_fail(IM_EINVAL, "gap distribution: no gap or force field, or no outputs");
    if (gap->nx != force->nx || gap->ny != force->ny)
        return im_fail(IM_EINVAL, "gap distribution: gap %d x %d and force %d x %d: expected one grid", gap->nx,
                       gap->ny, force->nx, force->ny);
    if (!(scale > 0.0 && isfinite(scale)) || bins < 1)
        return im_fail(IM_EINVAL, "gap distribution: scale = %g, bins = %d: expected scale > 0 and bins >= 1", scale,
                       bins);
    double largest;
    int status = largest_free_gap(gap, force, &largest);
    if (status != IM_OK)
        return status;
    memset(counts, 0, sizeof *counts * (size_t)bins);
    *infinite = 0;
    *bin_width = largest / scale / bins;
    for (size_t i = 0; i < im_field_count(gap); ++i) {
        double g = gap->data[i];
        if (in_contact(force, i))
            continue;
        if (isinf(g)) {
            ++*infinite;
            continue;
        }
        int bin = largest > 0.0 && g > 0.0 ? (int)(g / largest * bins) : 0;
        ++counts[bin < bins ? bin : bins - 1];
    }
    return IM_OK;
}

static int write_gaps(const im_field *force, const im_field *gap, double height_rms, int bins, const char *path)
{
    long *counts = malloc(sizeof *counts * (size_t)bins), infinite = 0;
    double width = 0.0;
    int status = counts ? im_measure_gap_distribution(gap, force, height_rms, bins, counts, &width, &infinite)
                        : im_fail(IM_ENOMEM, "gap distribution of %d bins", bins);
    im_atomic_file file;
    if (status == IM_OK)
        status = im_atomic_open(&file, path);
    if (status == IM_OK) {
        double cells = (double)im_field_count(gap);
        fprintf(file.stream, "gap_low,gap_high,cells,density\n");
        for (int b = 0; b < bins; ++b)
            fprintf(file.stream, "%.10g,%.10g,%ld,%.10g\n", b * width, (b + 1) * width, counts[b],
                    width > 0.0 ? counts[b] / (cells * width) : 0.0);
        fprintf(file.stream, "inf,inf,%ld,0\n", infinite);
        status = im_atomic_commit(&file);
    }
    free(counts);
    return status;
}

static int write_patch_histogram(const im_patch *list, long count, double delta, const char *path)
{
    long patches[IM_PATCH_BINS], cells[IM_PATCH_BINS], edges[IM_PATCH_BINS];
    int status = im_measure_patch_histogram(list, count, patches, cells, edges);
    im_atomic_file file;
    if (status == IM_OK)
        status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    fprintf(file.stream, "cells_low,cells_high,patches,cells,area,perimeter\n");
    for (int b = 0; b < IM_PATCH_BINS; ++b)
        if (patches[b] > 0)
            fprintf(file.stream, "%ld,%ld,%ld,%ld,%.10g,%.10g\n", 1L << b, (2L << b) - 1, patches[b], cells[b],
                    cells[b] * delta * delta, edges[b] * delta);
    return im_atomic_commit(&file);
}

static int write_patch_list(const im_patch *list, long count, double delta, const char *path)
{
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    fprintf(file.stream, "patch,cells,area,perimeter\n");
    for (long i = 0; i < count; ++i)
        fprintf(file.stream, "%ld,%ld,%.10g,%.10g\n", i + 1, list[i].cells, list[i].cells * delta * delta,
                list[i].edges * delta);
    return im_atomic_commit(&file);
}

/* PREFIX + suffix into out; IM_EINVAL if it does not fit. */
static int prefixed(const char *prefix, const char *suffix, char *out, size_t size)
{
    int length = snprintf(out, size, "%s%s", prefix, suffix);
    if (length < 0 || (size_t)length >= size)
        return im_fail(IM_EINVAL, "distributions: path %s%s is too long", prefix, suffix);
    return IM_OK;
}

int im_measure_write_distributions(const im_field *force, const im_field *gap, double height_rms, int bins,
                                   const char *prefix)
{
    ARG_VIEW(force, "force");
    ARG_VIEW(gap, "gap");
    ARG_REQUIRE(prefix, "prefix");
    if (!force || !force->data || !prefix)
        return im_fail(IM_EINVAL, "distributions: no force field or prefix");
    char path[4096];
    int status = prefixed(prefix, "_gaps.csv", path, sizeof path);
    if (status == IM_OK)
        status = write_gaps(force, gap, height_rms, bins, path);
    im_patch *list = NULL;
    long count = 0;
    if (status == IM_OK)
        status = im_measure_patch_list(force, &list, &count);
    if (status == IM_OK)
        status = prefixed(prefix, "_patches.csv", path, sizeof path);
    if (status == IM_OK)
        status = write_patch_histogram(list, count, force->delta, path);
    if (status == IM_OK)
        status = prefixed(prefix, "_patch_list.csv", path, sizeof path);
    if (status == IM_OK)
        status = write_patch_list(list, count, force->delta, path);
    free(list);
    return status;
}
