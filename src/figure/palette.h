/* Internal: one palette for all the frames of a GIF (palette.c). */
#ifndef INDENTMAP_FIGURE_PALETTE_H
#define INDENTMAP_FIGURE_PALETTE_H

#include "indentmap/render.h"

#include <stdint.h>

typedef struct gif_palette {
    int count;
    uint8_t rgb[256][3];
} gif_palette;

/* The distinct colours of the frames with their pixel counts, and each colour's palette index once known. */
typedef struct colour_table colour_table;

/* The colours of frames[0..count); IM_ENOMEM. */
int colour_table_build(const im_image *frames, int count, colour_table **table);
void colour_table_free(colour_table *table);

/* At most `colours` colours: the frames' own colours when there are no more, else boxes of the colour
 * cube split greedily (the box with the largest weighted squared error, along its widest channel, where
 * the two halves' error is least) and each box's weighted mean. A colour weighs the square root of its
 * pixel count, so that a colour map's rarer colours keep entries beside a large lit surface's greys
 * (bench/bench_gif.c: on the 3-D frames the largest ΔE fell from 34 to 22, the mean rose from 0.14 to
 * 0.22). IM_ENOMEM. */
int palette_build(const colour_table *table, int colours, gif_palette *palette);

/* The palette index of every pixel of frame: its nearest palette colour (RGB distance) or, with dither,
 * Floyd–Steinberg error diffusion in serpentine order. IM_ENOMEM. */
int palette_index_frame(colour_table *table, const gif_palette *palette, const im_image *frame, int dither,
                        uint8_t *indices);

#endif
