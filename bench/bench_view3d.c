/* Benchmark of the 3-D view (not a test).
 *
 *   bench_view3d [--repeats R]
 *
 * Frame time of im_render_view3d (CPU preparation, upload, draw with 4 samples, resolve, read
 * back; no PNG) at 1920 x 1080 pixels for a cone pressed into generated rough surfaces of 512^2
 * and 2048^2 patches: median of R repeats (default 7) after one warm-up frame, wall clock and the
 * process's CPU time (llvmpipe draws on its own threads), at the default level of detail (mesh_side
 * 384), at 512, and, as the reference the level of detail saves, with the full 2048^2 mesh. Prints
 * GL_RENDERER and the load average before and after, as the machine may be shared.
 */
#include "bench_common.h"

#include "indentmap/render.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_REPEATS 31

static void die(int status, const char *what)
{
    fprintf(stderr, "bench_view3d: %s: %s (%s)\n", what, im_last_error(), im_strstatus(status));
    exit(1);
}

static double cpu_seconds(void)
{
    struct rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    return (double)usage.ru_utime.tv_sec + 1e-6 * (double)usage.ru_utime.tv_usec + (double)usage.ru_stime.tv_sec +
           1e-6 * (double)usage.ru_stime.tv_usec;
}

static void print_load(const char *when)
{
    FILE *f = fopen("/proc/loadavg", "r");
    char line[128] = "unknown";
    if (f) {
        if (!fgets(line, sizeof line, f))
            snprintf(line, sizeof line, "unknown\n");
        fclose(f);
    }
    printf("load average %s: %s", when, line);
}

/* A rough surface with a 80 degree cone pressed to a depth of n / 16 patches (heights clipped to
 * the cone's face), and forces on the clipped patches. */
static void indented(int n, im_field **height, im_field **force)
{
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = n;
    p.lambda_r = n;
    int status = im_surface_generate(&p, height);
    if (status == IM_OK)
        status = im_field_create(n, n, 1.0, force);
    if (status != IM_OK)
        die(status, "fields");
    double tip = -n / 16.0, cot = 1.0 / tan(80.0 * M_PI / 180.0);
    for (int iy = 0; iy < n; ++iy)
        for (int ix = 0; ix < n; ++ix) {
            size_t i = (size_t)iy * n + ix;
            double face = tip + cot * hypot(ix + 0.5 - 0.5 * n, iy + 0.5 - 0.5 * n);
            if ((*height)->data[i] > face) {
                (*force)->data[i] = (*height)->data[i] - face;
                (*height)->data[i] = face;
            }
        }
}

/* mesh_side 0: the default. */
static void time_view(im_render_context *c, int n, int mesh_side, int repeats)
{
    im_field *height = NULL, *force = NULL;
    indented(n, &height, &force);
    im_indenter punch = im_indenter_cone(80.0);
    im_view3d_style s = im_view3d_style_default(force);
    s.mesh_side = mesh_side > 0 ? mesh_side : s.mesh_side;
    s.exaggeration = 3.0;
    double wall[MAX_REPEATS], cpu[MAX_REPEATS];
    for (int r = -1; r < repeats; ++r) {
        im_image image;
        double start = bench_now(), start_cpu = cpu_seconds();
        int status = im_render_view3d(c, height, force, &punch, &s, &image);
        if (status != IM_OK)
            die(status, "3-D view");
        if (r >= 0) {
            wall[r] = bench_now() - start;
            cpu[r] = cpu_seconds() - start_cpu;
        }
        im_image_release(&image);
    }
    printf("%5d^2 patches  mesh_side %5d  1920x1080, 4 samples: median %.3f s wall, %.3f s CPU (%d repeats)\n", n,
           s.mesh_side, bench_median(wall, repeats), bench_median(cpu, repeats), repeats);
    fflush(stdout);
    im_field_free(height);
    im_field_free(force);
}

int main(int argc, char **argv)
{
    int repeats = 7;
    if (argc == 3 && strcmp(argv[1], "--repeats") == 0)
        repeats = atoi(argv[2]);
    if (repeats < 1 || repeats > MAX_REPEATS) {
        fprintf(stderr, "usage: bench_view3d [--repeats 1..%d]\n", MAX_REPEATS);
        return 2;
    }
    im_render_context *c = NULL;
    int status = im_render_open(IM_RENDER_AUTO, &c);
    if (status != IM_OK)
        die(status, "render context");
    printf("GL_RENDERER %s; %s, %s\n", im_render_gl_renderer(c), im_render_backend_name(c),
           im_render_display_name(c));
    print_load("before");
    time_view(c, 512, 0, repeats);
    time_view(c, 512, 512, repeats);
    time_view(c, 2048, 0, repeats);
    time_view(c, 2048, 2048, repeats < 3 ? repeats : 3);
    print_load("after");
    im_render_close(c);
    return 0;
}
