/* Header-only helpers shared by tests/test_figure.c and bench/bench_gif.c: a GIF read back into RGBA
 * frames (giflib) and the CIELAB colour difference (ΔE*ab, CIE 1976; sRGB, D65) of two images. */
#ifndef INDENTMAP_TESTS_GIF_COMPARE_H
#define INDENTMAP_TESTS_GIF_COMPARE_H

#include "indentmap/render.h"

#include <gif_lib.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct gif_readback {
    int count, width, height;
    int palette_size; /* entries of the global colour table (0: none) */
    int delays[64];   /* centiseconds, the first 64 frames */
    uint8_t *rgba;    /* count frames of width * height RGBA pixels */
} gif_readback;

/* Reads every frame of path (frames that cover the screen, as im_animation_gif writes); 0 on success. */
static inline int gif_read(const char *path, gif_readback *g)
{
    int error = 0;
    *g = (gif_readback){0};
    GifFileType *gif = DGifOpenFileName(path, &error);
    if (!gif || DGifSlurp(gif) != GIF_OK) {
        if (gif)
            DGifCloseFile(gif, &error);
        return -1;
    }
    *g = (gif_readback){gif->ImageCount,
                        gif->SWidth,
                        gif->SHeight,
                        gif->SColorMap ? gif->SColorMap->ColorCount : 0,
                        {0},
                        malloc((size_t)gif->ImageCount * gif->SWidth * gif->SHeight * 4)};
    for (int k = 0; g->rgba && k < g->count; ++k) {
        const SavedImage *image = &gif->SavedImages[k];
        const ColorMapObject *map = image->ImageDesc.ColorMap ? image->ImageDesc.ColorMap : gif->SColorMap;
        GraphicsControlBlock control = {0};
        if (k < 64 && DGifSavedExtensionToGCB(gif, k, &control) == GIF_OK)
            g->delays[k] = control.DelayTime;
        size_t pixels = (size_t)g->width * g->height;
        for (size_t i = 0; map && i < pixels; ++i) {
            const GifColorType *c = &map->Colors[image->RasterBits[i]];
            uint8_t *out = g->rgba + ((size_t)k * pixels + i) * 4;
            out[0] = c->Red, out[1] = c->Green, out[2] = c->Blue, out[3] = 255;
        }
    }
    DGifCloseFile(gif, &error);
    return g->rgba ? 0 : -1;
}

static inline double srgb_linear(double c)
{
    c /= 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static inline double lab_f(double t) { return t > 216.0 / 24389.0 ? cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0; }

static inline void rgb_to_lab(const double rgb[3], double lab[3])
{
    double r = srgb_linear(rgb[0]), g = srgb_linear(rgb[1]), b = srgb_linear(rgb[2]);
    double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
    double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
    lab[0] = 116.0 * lab_f(y) - 16.0;
    lab[1] = 500.0 * (lab_f(x) - lab_f(y));
    lab[2] = 200.0 * (lab_f(y) - lab_f(z));
}

static inline double delta_e(const double a[3], const double b[3])
{
    double la[3], lb[3];
    rgb_to_lab(a, la);
    rgb_to_lab(b, lb);
    return sqrt((la[0] - lb[0]) * (la[0] - lb[0]) + (la[1] - lb[1]) * (la[1] - lb[1]) +
                (la[2] - lb[2]) * (la[2] - lb[2]));
}

/* The mean of RGBA pixel (x, y) over a (2r+1)^2 box clipped to the image (r = 0: the pixel). */
static inline void box_mean_rgb(const uint8_t *rgba, int width, int height, int x, int y, int r, double out[3])
{
    double sum[3] = {0, 0, 0};
    int n = 0;
    for (int j = y - r; j <= y + r; ++j)
        for (int i = x - r; i <= x + r; ++i)
            if (i >= 0 && j >= 0 && i < width && j < height) {
                for (int k = 0; k < 3; ++k)
                    sum[k] += rgba[((size_t)j * width + i) * 4 + k];
                ++n;
            }
    for (int k = 0; k < 3; ++k)
        out[k] = sum[k] / n;
}

typedef struct colour_error {
    double mean, max; /* ΔE*ab over the pixels */
    double p99;       /* the 99th percentile */
} colour_error;

/* ΔE*ab between two RGBA images of one size, pixel by pixel (radius 0) or between their box means of
 * radius r (the look from a little further away, where a dither's pattern blends). */
static inline colour_error image_delta_e(const uint8_t *a, const uint8_t *b, int width, int height, int r)
{
    size_t pixels = (size_t)width * height, histogram[1001] = {0};
    colour_error e = {0, 0, 0};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double ca[3], cb[3];
            box_mean_rgb(a, width, height, x, y, r, ca);
            box_mean_rgb(b, width, height, x, y, r, cb);
            double d = delta_e(ca, cb);
            e.mean += d / pixels;
            e.max = d > e.max ? d : e.max;
            ++histogram[d >= 100.0 ? 1000 : (int)(d * 10.0)];
        }
    size_t seen = 0;
    for (int i = 0; i <= 1000; ++i) {
        seen += histogram[i];
        if (seen >= 0.99 * pixels) {
            e.p99 = (i + 1) / 10.0;
            break;
        }
    }
    return e;
}

#endif
