/* Read time and peak memory of a surface in each format (issue 13): .npy (the floor: a header and the
 * raw doubles), NetCDF, .x3p, .sdf, .gsf. Usage: bench_formats N REPEATS DIR FORMAT
 *   FORMAT "write" writes DIR/s.{npy,nc,x3p,sdf,gsf} of an N x N surface (deterministic heights);
 *   FORMAT npy|nc|x3p|sdf|gsf reads DIR/s.FORMAT REPEATS times and prints
 *   format,n,repeats,median_s,min_s,peak_rss_mib,field_mib
 * Run each format in its own process (bench/run_formats.sh does) so that the peak RSS is its own. */
#include "bench_common.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *const FORMATS[] = {"npy", "nc", "x3p", "sdf", "gsf"};

static int write_all(int n, const char *dir)
{
    im_field *f = NULL;
    if (im_field_create(n, n, 1e-8, &f) != IM_OK)
        return 1;
    strcpy(f->unit, "m");
    for (int iy = 0; iy < n; ++iy)
        for (int ix = 0; ix < n; ++ix)
            f->data[(size_t)iy * n + ix] = 1e-8 *
                                           (sin(0.013 * ix) * cos(0.007 * iy) + 1e-3 * ((ix * 7919 + iy) % 101));
    int status = IM_OK;
    for (int i = 0; i < 5 && status == IM_OK; ++i) {
        char path[4096];
        snprintf(path, sizeof path, "%s/s.%s", dir, FORMATS[i]);
        status = im_surface_write(path, f);
    }
    im_field_free(f);
    if (status != IM_OK)
        fprintf(stderr, "bench_formats: %s\n", im_last_error());
    return status != IM_OK;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: bench_formats N REPEATS DIR write|npy|nc|x3p|sdf|gsf\n");
        return 2;
    }
    int n = atoi(argv[1]), repeats = atoi(argv[2]);
    if (strcmp(argv[4], "write") == 0)
        return write_all(n, argv[3]);
    char path[4096];
    snprintf(path, sizeof path, "%s/s.%s", argv[3], argv[4]);
    double times[64];
    repeats = repeats < 1 ? 1 : repeats > 64 ? 64 : repeats;
    for (int r = 0; r < repeats; ++r) {
        im_field *f = NULL;
        double start = bench_now();
        if (im_surface_read(path, &f) != IM_OK) {
            fprintf(stderr, "bench_formats: %s\n", im_last_error());
            return 1;
        }
        times[r] = bench_now() - start;
        im_field_free(f);
    }
    double min = times[0];
    for (int r = 1; r < repeats; ++r)
        min = fmin(min, times[r]);
    printf("%s,%d,%d,%.4f,%.4f,%.1f,%.1f\n", argv[4], n, repeats, bench_median(times, repeats), min,
           bench_peak_rss_mib(), (double)n * n * 8.0 / 1048576.0);
    return 0;
}
