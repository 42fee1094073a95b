/* Benchmark of the off-screen renderer (not a test).
 *
 *   bench_render [--repeats R]
 *
 * One frame = render (upload, draw, read back) + PNG encode, for 512 x 512 and 2048 x 2048 pixel
 * images (fields of 256^2 and 1024^2 patches at 2 pixels per patch): the contact map of a
 * synthetic speckled cone field and the hill-shaded height field of a generated surface. GL time
 * and encode time are reported separately (median of R repeats, default 7, after one warm-up
 * draw), with the CPU colour mapping (im_colormap_field_image, one pixel per patch) as a
 * reference point; PNG encoding at zlib levels 1, 3, 6 and 9 (time and size) chooses the default
 * compression; the annotated figure (cairo + PNG) is timed too.
 */
#include "bench_common.h"

#include "indentmap/colormap.h"
#include "indentmap/figure.h"
#include "indentmap/io.h"
#include "indentmap/render.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_REPEATS 31

static void die(int status, const char *what)
{
    fprintf(stderr, "bench_render: %s: %s (%s)\n", what, im_last_error(), im_strstatus(status));
    exit(1);
}

/* Love's cone pressure acosh(a / r) inside a = n / 4, thinned by a hashed speckle. */
static im_field *cone_forces(int n)
{
    im_field *f = NULL;
    int status = im_field_create(n, n, 1.0, &f);
    if (status != IM_OK)
        die(status, "field");
    double a = 0.25 * n;
    for (int iy = 0; iy < n; ++iy)
        for (int ix = 0; ix < n; ++ix) {
            double r = hypot(ix + 0.5 - 0.5 * n, iy + 0.5 - 0.5 * n);
            uint32_t hash = (uint32_t)(ix * 73856093u) ^ (uint32_t)(iy * 19349663u);
            hash = (hash ^ (hash >> 13)) * 0x5bd1e995u;
            if (r < a && (hash >> 24) > 90)
                f->data[(size_t)iy * n + ix] = 0.088 * acosh(a / fmax(r, 0.5));
        }
    return f;
}

static im_field *surface(int n)
{
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = n;
    p.lambda_r = n;
    im_field *h = NULL;
    int status = im_surface_generate(&p, &h);
    if (status != IM_OK)
        die(status, "surface");
    return h;
}

static double time_contact(im_render_context *c, const im_field *f, const im_contact_style *s, int repeats,
                           im_image *keep)
{
    double times[MAX_REPEATS];
    int status = im_render_contact_map(c, f, s, keep); /* warm-up: shader JIT, first allocation */
    if (status != IM_OK)
        die(status, "contact map");
    for (int r = 0; r < repeats; ++r) {
        im_image image;
        double start = bench_now();
        status = im_render_contact_map(c, f, s, &image);
        times[r] = bench_now() - start;
        if (status != IM_OK)
            die(status, "contact map");
        im_image_release(&image);
    }
    return bench_median(times, repeats);
}

static double time_height(im_render_context *c, const im_field *h, int repeats)
{
    im_height_style s = im_height_style_default(h);
    double times[MAX_REPEATS];
    for (int r = -1; r < repeats; ++r) {
        im_image image;
        double start = bench_now();
        int status = im_render_height_map(c, h, &s, &image);
        if (r >= 0)
            times[r] = bench_now() - start;
        if (status != IM_OK)
            die(status, "height map");
        im_image_release(&image);
    }
    return bench_median(times, repeats);
}

static double time_cpu_colormap(const im_field *f, const im_colormap *c, int repeats)
{
    double times[MAX_REPEATS];
    uint8_t *rgb = malloc(im_field_count(f) * 3);
    for (int r = 0; r < repeats; ++r) {
        double start = bench_now();
        im_colormap_field_image(c, f, rgb);
        times[r] = bench_now() - start;
    }
    free(rgb);
    return bench_median(times, repeats);
}

/* Median time and size of encoding an RGB image at a zlib level. */
static void time_png(const uint8_t *rgb, int width, int height, int level, int repeats, double *seconds,
                     double *bytes)
{
    char path[256];
    snprintf(path, sizeof path, "/tmp/bench_render_%ld.png", (long)getpid());
    im_png_options options = {NULL, 0, 300 / 0.0254, level};
    double times[MAX_REPEATS];
    for (int r = 0; r < repeats; ++r) {
        double start = bench_now();
        int status = im_png_write(path, rgb, width, height, 3, (size_t)width * 3, &options);
        times[r] = bench_now() - start;
        if (status != IM_OK)
            die(status, "PNG");
    }
    struct stat st;
    stat(path, &st);
    *bytes = (double)st.st_size;
    *seconds = bench_median(times, repeats);
    remove(path);
}

static uint8_t *to_rgb(const im_image *image)
{
    size_t pixels = (size_t)image->width * image->height;
    uint8_t *rgb = malloc(pixels * 3);
    for (size_t i = 0; i < pixels; ++i)
        memcpy(rgb + 3 * i, image->rgba + 4 * i, 3);
    return rgb;
}

static double time_figure(const im_image *image, const im_colormap *norm, int repeats)
{
    char path[256];
    snprintf(path, sizeof path, "/tmp/bench_render_figure_%ld.png", (long)getpid());
    im_figure_panel panel = {image, "(a)", NULL};
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.colormap = norm;
    figure.colorbar_label = "local force f / (E* δ²)";
    double times[MAX_REPEATS];
    for (int r = 0; r < repeats; ++r) {
        double start = bench_now();
        int status = im_figure_write(&figure, path);
        times[r] = bench_now() - start;
        if (status != IM_OK)
            die(status, "figure");
    }
    remove(path);
    return bench_median(times, repeats);
}

static void run_size(im_render_context *c, int side, int repeats)
{
    int n = side / 2;
    im_field *f = cone_forces(n), *h = surface(n);
    im_contact_style style = im_contact_style_default(f);
    style.boundary_px = 0;
    style.circle_radius = 0.25 * n;
    im_image image;
    double gl = time_contact(c, f, &style, repeats, &image);
    double gl_height = time_height(c, h, repeats);
    double cpu = time_cpu_colormap(f, &style.colormap, repeats);
    uint8_t *rgb = to_rgb(&image);
    printf("\n### %d x %d pixels (%d x %d patches, 2 px per patch)\n\n", side, side, n, n);
    printf("| step | median time (ms) |\n|---|---:|\n");
    printf("| GL contact map: upload + draw + read back | %.2f |\n", 1e3 * gl);
    printf("| GL height field (hill-shaded): upload + draw + read back | %.2f |\n", 1e3 * gl_height);
    printf("| CPU colour mapping, 1 px per patch (reference, %d threads) | %.2f |\n", omp_get_max_threads(),
           1e3 * cpu);
    printf("\n| PNG level | encode (ms) | size (KiB) | frame = GL + encode (ms) |\n|---:|---:|---:|---:|\n");
    const int levels[] = {1, 3, 6, 9};
    for (int i = 0; i < 4; ++i) {
        double seconds, bytes;
        time_png(rgb, image.width, image.height, levels[i], repeats, &seconds, &bytes);
        printf("| %d | %.1f | %.0f | %.1f |\n", levels[i], 1e3 * seconds, bytes / 1024.0, 1e3 * (gl + seconds));
    }
    printf("\nAnnotated figure (cairo layout + colour bar + PNG level %d): %.1f ms\n", IM_FIGURE_PNG_COMPRESSION,
           1e3 * time_figure(&image, &style.colormap, repeats));
    fflush(stdout);
    free(rgb);
    im_image_release(&image);
    im_field_free(f);
    im_field_free(h);
}

int main(int argc, char **argv)
{
    int repeats = 7;
    if (argc == 3 && strcmp(argv[1], "--repeats") == 0)
        repeats = atoi(argv[2]);
    if (repeats < 1 || repeats > MAX_REPEATS) {
        fprintf(stderr, "usage: bench_render [--repeats R], 1 <= R <= %d\n", MAX_REPEATS);
        return 2;
    }
    im_render_context *c = NULL;
    int status = im_render_open(IM_RENDER_AUTO, &c);
    if (status != IM_OK)
        die(status, "GL context");
    printf("renderer: %s, %s\nGL_RENDERER: %s\nGL_VERSION: %s\n", im_render_backend_name(c),
           im_render_display_name(c), im_render_gl_renderer(c), im_render_gl_version(c));
    printf("processors: %ld, OpenMP threads: %d, LP_NUM_THREADS=%s, repeats: %d (median)\n",
           sysconf(_SC_NPROCESSORS_ONLN), omp_get_max_threads(),
           getenv("LP_NUM_THREADS") ? getenv("LP_NUM_THREADS") : "(unset)", repeats);
    run_size(c, 512, repeats);
    run_size(c, 2048, repeats);
    im_render_close(c);
    return 0;
}
