/* How well an animated GIF keeps its annotated PNG frames' look, and what its palette costs.
 *
 *   bench_gif DIR PREFIX COUNT [OUT]
 *
 * reads DIR/PREFIX_0000.png ... (a scene's frames/contact_NNNN.png or view3d_NNNN.png), writes them as
 * GIFs in several ways (OUT_1.gif, OUT_2.gif, ...; OUT defaults to bench_gif), reads each back and prints the CIELAB colour error (ΔE*ab) against the PNG
 * frames: the mean, 99th percentile and largest pixel by pixel, and the mean between 3 x 3 box means
 * (the look from a little further away, where a dither's pattern blends), with the palette's size,
 * the file's size and the median of 3 writes' time. "cube 216 ordered" is what the scenes' 3-D GIF did
 * before: a 6 x 6 x 6 colour cube with a 4 x 4 ordered dither. */
#include "bench_common.h"
#include "../tests/gif_compare.h"

#include "indentmap/figure.h"
#include "indentmap/io.h"
#include "indentmap/status.h"

#include <stdio.h>
#include <sys/stat.h>

static int read_frames(const char *dir, const char *prefix, int count, im_image *frames)
{
    for (int i = 0; i < count; ++i) {
        char path[4096];
        uint8_t *pixels = NULL;
        int channels = 0;
        if (im_frame_path(path, sizeof path, dir, prefix, i) != IM_OK ||
            im_png_read(path, &pixels, &frames[i].width, &frames[i].height, &channels) != IM_OK)
            return -1;
        size_t n = (size_t)frames[i].width * frames[i].height;
        frames[i].rgba = malloc(n * 4);
        for (size_t p = 0; p < n; ++p) {
            memcpy(frames[i].rgba + 4 * p, pixels + channels * p, 3);
            frames[i].rgba[4 * p + 3] = 255;
        }
        free(pixels);
    }
    return 0;
}

/* The scenes' 3-D GIF before: every channel to 6 levels with a 4 x 4 ordered dither. */
static void dither_to_cube(im_image *image)
{
    static const int bayer[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
    for (int y = 0; y < image->height; ++y)
        for (int x = 0; x < image->width; ++x) {
            uint8_t *p = image->rgba + ((size_t)y * image->width + x) * 4;
            double threshold = (bayer[y % 4][x % 4] + 0.5) / 16.0;
            for (int k = 0; k < 3; ++k) {
                int q = (int)floor(p[k] * 5 / 255.0 + threshold);
                p[k] = (uint8_t)lround((q > 5 ? 5 : q) * 255.0 / 5);
            }
        }
}

static void measure(const char *name, const im_image *frames, const im_image *reference, int count,
                    const im_gif_options *options, const char *path)
{
    double times[3];
    for (int r = 0; r < 3; ++r) {
        double start = bench_now();
        if (im_animation_gif_with(frames, count, options, path) != IM_OK) {
            fprintf(stderr, "%s: %s\n", name, im_last_error());
            return;
        }
        times[r] = bench_now() - start;
    }
    gif_readback g;
    struct stat st;
    if (gif_read(path, &g) != 0 || stat(path, &st) != 0)
        return;
    colour_error worst = {0, 0, 0}, sum = {0, 0, 0};
    double blurred = 0.0;
    size_t pixels = (size_t)g.width * g.height;
    for (int k = 0; k < count; ++k) {
        colour_error e = image_delta_e(g.rgba + k * pixels * 4, reference[k].rgba, g.width, g.height, 0);
        sum.mean += e.mean / count, sum.p99 += e.p99 / count;
        worst.max = fmax(worst.max, e.max);
        blurred += image_delta_e(g.rgba + k * pixels * 4, reference[k].rgba, g.width, g.height, 1).mean / count;
    }
    printf("| %-22s | %3d | %6.3f | %5.2f | %5.1f | %6.3f | %7.0f | %7.1f |\n", name, g.palette_size, sum.mean,
           sum.p99, worst.max, blurred, st.st_size / 1024.0, 1e3 * bench_median(times, 3));
    free(g.rgba);
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: bench_gif DIR PREFIX COUNT [OUT]\n");
        return 2;
    }
    int count = atoi(argv[3]);
    const char *out = argc > 4 ? argv[4] : "bench_gif";
    char path[4096];
    im_image *frames = calloc((size_t)count, sizeof *frames), *cube = calloc((size_t)count, sizeof *cube);
    if (count < 1 || read_frames(argv[1], argv[2], count, frames) != 0) {
        fprintf(stderr, "bench_gif: cannot read %s/%s_NNNN.png: %s\n", argv[1], argv[2], im_last_error());
        return 1;
    }
    printf("%d frames of %d x %d from %s/%s_NNNN.png\n\n", count, frames[0].width, frames[0].height, argv[1],
           argv[2]);
    printf("| GIF                    | pal | mean ΔE | p99 | max | mean ΔE 3x3 | KiB | write ms |\n");
    im_gif_options o = im_gif_options_default();
    for (int i = 0; i < count; ++i) {
        size_t bytes = (size_t)frames[i].width * frames[i].height * 4;
        cube[i] = frames[i];
        cube[i].rgba = malloc(bytes);
        memcpy(cube[i].rgba, frames[i].rgba, bytes);
        dither_to_cube(&cube[i]);
    }
    snprintf(path, sizeof path, "%s_0.gif", out);
    measure("cube 216 ordered", cube, frames, count, &o, path);
    const struct {
        const char *name;
        int colours, dither;
    } ways[] = {{"64 nearest", 64, 0},
                {"64 Floyd-Steinberg", 64, 1},
                {"256 nearest", 256, 0},
                {"256 Floyd-Steinberg", 256, 1}};
    for (size_t w = 0; w < sizeof ways / sizeof *ways; ++w) {
        o.colours = ways[w].colours;
        o.dither = ways[w].dither;
        snprintf(path, sizeof path, "%s_%zu.gif", out, w + 1);
        measure(ways[w].name, frames, frames, count, &o, path);
    }
    for (int i = 0; i < count; ++i) {
        im_image_release(&frames[i]);
        im_image_release(&cube[i]);
    }
    free(frames);
    free(cube);
    return 0;
}
