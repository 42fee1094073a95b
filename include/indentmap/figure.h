/* indentmap/figure.h: publication figures around rendered images (render.h): panel grids with
 * panel labels and titles, one shared colour bar with ticks and the quantity's name (and a second
 * one for the tension of patches under tension, where there is any), a scale bar,
 * and output as PNG (with the run's parameters in tEXt chunks and the resolution in pHYs), PDF or
 * SVG; frames of an indentation run and animations (GIF, MP4).
 *
 * Entry points:
 *   im_figure_default, im_figure_write           a figure of panels, written as PNG, PDF or SVG
 *   im_figure_colorbar_label                     the colour bar's label of a quantity
 *   im_figure_write_frame, im_frame_path         one frame of a run, and where frames go
 *   im_animation_gif, im_animation_mp4           frames as an animation
 *
 * GL draws the data, cairo the annotations. Text uses FreeType on the DejaVu Sans files
 * (in the folder the build names, cmake -DIM_FONT_DIR=...) loaded directly, so output does not depend on fontconfig.
 * Every file is written atomically (io.h): an unwritable path gives IM_EIO and leaves nothing.
 *
 * Text (labels, titles, the colour bar's quantity) is UTF-8 and may contain _{subscript} and
 * ^{superscript} markup, e.g. "h′_{rms} = 0.08" or "f / (E* δ^{2})".
 *
 * Sizes: the layout is made in pixels at `dpi`; each data image is placed at its own pixel size
 * (one image pixel = one figure pixel, at integer offsets, so patches stay crisp). PDF and SVG use
 * the same layout scaled by 72 / dpi points per pixel, with the data images embedded as rasters
 * drawn without interpolation. Text sizes are in points.
 *
 * Misuse (status.h): IM_EINVAL for a NULL figure, frame list, path or output; im_figure_ticks
 * gives 0 ticks for a NULL colormap or array.
 * Threads: thread-safe; two threads may write figures at once (to different paths). The fonts are
 * loaded once per process, under a lock; im_animation_mp4 runs ffmpeg as a child process.
 */
#ifndef INDENTMAP_FIGURE_H
#define INDENTMAP_FIGURE_H

#include "indentmap/colormap.h"
#include "indentmap/io.h"
#include "indentmap/render.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct im_figure_panel {
    const im_image *image; /* the data, from im_render_*; required */
    const char *label;     /* "(a)", bold, above the panel's left edge; NULL: none */
    const char *title;     /* above the panel, centred (UTF-8); NULL: none */
} im_figure_panel;

typedef struct im_figure {
    int rows, columns;                   /* the panel grid, >= 1 each */
    const im_figure_panel *panels;       /* rows * columns panels, row by row from the top */
    const im_colormap *colormap;         /* norm of the one shared colour bar; NULL: no colour bar */
    const char *colorbar_label;          /* the quantity, e.g. "local force f / (E* δ²)" */
    int extend_under, extend_over;       /* 1: triangles in the under / over colour beyond the bar's
                                        ends, saying that some values lie outside the norm */
    const im_colormap *tension_colormap; /* a second bar right of the first: the norm of the tension
                                        of patches under tension (render.h: im_contact_style.tension);
                                        NULL (the default): none */
    const char *tension_label;           /* its quantity, e.g. "tensile force −f / (E* δ²)" */
    double scale_bar;                    /* length in the images' units (delta, or their unit);
                                        0: automatic (a 1-2-5 length near a fifth of a panel);
                                        < 0: none */
    double dpi;                          /* pixels per inch of the PNG, (0, 2400] */
    double font_size;                    /* points, (0, 72] */
    const im_png_text *texts;            /* run parameters: PNG tEXt chunks, PDF keywords */
    int text_count;
    int png_compression; /* zlib level 0-9 for PNG output */
    const char *note;    /* one line under the panels, ending at the grid's right edge
                                        (e.g. the punch and the load, "N* = 37000"); NULL: none */
} im_figure;

/* One panel, no colour bar, automatic scale bar, 300 dpi, 8 pt text, PNG compression
 * IM_FIGURE_PNG_COMPRESSION (chosen from bench/bench_render.c). */
im_figure im_figure_default(void);
#define IM_FIGURE_PNG_COMPRESSION 6

/* Output format from the path's extension. */
typedef enum im_figure_format { IM_FIGURE_PNG, IM_FIGURE_PDF, IM_FIGURE_SVG } im_figure_format;
/* IM_EINVAL naming the supported extensions (.png, .pdf, .svg) otherwise. */
int im_figure_format_of(const char *path, im_figure_format *format);

/* Lays out and writes the figure. IM_EINVAL for a bad spec (grid, missing image, dpi, font
 * size, unknown extension, colour norm), IM_EUNSUPPORTED if the font files cannot be loaded,
 * IM_EIO if the file cannot be written (nothing is left behind), IM_ENOMEM. */
int im_figure_write(const im_figure *figure, const char *path);

/* The nice tick values of a colour bar on [lo, hi] (linear: 1-2-5 steps, about 5 ticks; log: the
 * decades inside, or 1-2-5 multiples when fewer than three decades fit). Writes at most capacity
 * values in increasing order; returns how many. Exposed for tests. */
int im_figure_ticks(const im_colormap *colormap, double *ticks, int capacity);

/* The colour bar's label `indentmap render` gives a field, in its units: quantity "force" gives
 * "local force f / UNIT", unit the forces' (field.h's value_unit: "N", "Pa µm²"; "" gives "(E* δ²)"; a unit
 * of several factors is put in parentheses: "Pa µm²" and "E* δ²" as "(Pa µm²)", "(E* δ²)"),
 * and "tension" the tension bar's "tensile force −f / UNIT" in the same unit;
 * "height", "gap", "displacement" and "plastic" (the fields of an indentation step) give "height h /
 * UNIT", "gap g / UNIT", "displacement u / UNIT" and "plastic depth d / UNIT", unit the field's length
 * unit ("" gives "δ"). Writes the UTF-8 label into text (size bytes). IM_EINVAL for a NULL argument,
 * another quantity (naming the known ones) or a label that does not fit (text is then truncated). */
int im_figure_colorbar_label(const char *quantity, const char *unit, char *text, size_t size);

/* ---- frames and animations ---- */

/* "DIRECTORY/PREFIX_NNNN.png" (4 digits, more when index >= 10000) into buffer; IM_EINVAL when it
 * does not fit or index < 0. */
int im_frame_path(char *buffer, size_t size, const char *directory, const char *prefix, int index);

/* Writes the figure as the PNG frame path (as im_figure_write; IM_EINVAL unless path ends in .png)
 * and gives its pixels (RGBA, alpha 255; only the size and the pixels are set) in *frame, to be
 * released with im_image_release: the one annotated frame (panel, title, colour bar, scale bar) that
 * the PNG frames, the MP4 (made from those PNG files) and the GIF (made from the returned images)
 * all show. *frame is zeroed first and stays empty on failure. */
int im_figure_write_frame(const im_figure *figure, const char *path, im_image *frame);

/* How a GIF is written. A GIF holds at most 256 colours; an annotated frame has more (the colour
 * map's 256, anti-aliased text and lines, a lit 3-D surface's shades), so one palette is built from
 * all the frames' pixels: their own colours when there are at most `colours` of them (the GIF is
 * then exact), else a greedy variance split of the colour cube (the box of colours with the largest
 * weighted squared error split along its widest channel, where the halves' error is least; a colour
 * weighs the square root of its pixel count, so that a colour map's rarer colours keep entries),
 * each box's weighted mean a palette colour. Every pixel then takes its nearest palette colour, or with
 * dither an error-diffused (Floyd–Steinberg, serpentine) one; docs/rendering.md has the measured
 * colour errors of both. */
typedef struct im_gif_options {
    double seconds_per_frame; /* [0.01, 600]; stored in 1/100 s */
    int colours;              /* the palette's size limit, 2 to 256 */
    int dither;               /* 0: nearest colour (the default), 1: Floyd–Steinberg */
} im_gif_options;

/* 0.25 s per frame, 256 colours, no dithering. */
im_gif_options im_gif_options_default(void);

/* Writes frames[0..count) as a looping animated GIF (giflib) with one global palette as above.
 * Frames must share one size (at most 65535 per side). IM_EINVAL naming the option or the frame for
 * a bad one, IM_EIO (nothing left behind), IM_ENOMEM. */
int im_animation_gif_with(const im_image *frames, int count, const im_gif_options *options, const char *path);

/* im_animation_gif_with with the default options but seconds_per_frame; its errors. */
int im_animation_gif(const im_image *frames, int count, double seconds_per_frame, const char *path);

/* 1 when the ffmpeg command is on PATH (as `command -v ffmpeg`), 0 otherwise; never fails. */
int im_ffmpeg_available(void);

/* Encodes DIRECTORY/PREFIX_%04d.png, frames 0 to count - 1 (later ones in the folder, such as a
 * longer earlier run's, are not read), into an H.264 MP4 with the ffmpeg command at
 * frames_per_second, written atomically. IM_EUNSUPPORTED with "ffmpeg not found" when it is not
 * installed (the frames stay where they are); IM_EINVAL for count < 1; IM_EIO when ffmpeg fails. */
int im_animation_mp4(const char *directory, const char *prefix, int count, double frames_per_second,
                     const char *path);

#ifdef __cplusplus
}
#endif

#endif
