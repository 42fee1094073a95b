/* One palette for all the frames of a GIF: the frames' colours counted in a hash table, a greedy
 * variance split of the colour cube into at most 256 boxes, and each pixel mapped to its nearest
 * palette colour, with or without Floyd–Steinberg dithering. */
#include "figure/palette.h"

#include "indentmap/status.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- the colour table: open addressing on 0xRRGGBB + 1 (0: empty) ---- */

struct colour_table {
    size_t capacity, used; /* capacity a power of two, used <= capacity / 2 */
    uint32_t *keys;
    uint64_t *counts;
    int16_t *index; /* palette index, -1 until looked up */
};

static size_t slot_of(const colour_table *t, uint32_t key)
{
    size_t slot = (size_t)(key * 2654435761u) & (t->capacity - 1);
    while (t->keys[slot] && t->keys[slot] != key)
        slot = (slot + 1) & (t->capacity - 1);
    return slot;
}

static int table_allocate(colour_table *t, size_t capacity)
{
    t->capacity = capacity;
    t->used = 0;
    t->keys = calloc(capacity, sizeof *t->keys);
    t->counts = calloc(capacity, sizeof *t->counts);
    t->index = malloc(capacity * sizeof *t->index);
    if (!t->keys || !t->counts || !t->index)
        return im_fail(IM_ENOMEM, "GIF palette: %zu colours: out of memory", capacity / 2);
    memset(t->index, 0xff, capacity * sizeof *t->index);
    return IM_OK;
}

static void table_release(colour_table *t)
{
    free(t->keys);
    free(t->counts);
    free(t->index);
}

static int table_grow(colour_table *t)
{
    colour_table bigger;
    int status = table_allocate(&bigger, 2 * t->capacity);
    for (size_t i = 0; status == IM_OK && i < t->capacity; ++i)
        if (t->keys[i]) {
            size_t slot = slot_of(&bigger, t->keys[i]);
            bigger.keys[slot] = t->keys[i];
            bigger.counts[slot] = t->counts[i];
            bigger.index[slot] = t->index[i];
            ++bigger.used;
        }
    if (status != IM_OK) {
        table_release(&bigger);
        return status;
    }
    table_release(t);
    *t = bigger;
    return IM_OK;
}

/* The slot of a colour, adding it (count 0) when new; IM_ENOMEM. */
static int table_slot(colour_table *t, uint32_t rgb, size_t *slot)
{
    uint32_t key = rgb + 1;
    *slot = slot_of(t, key);
    if (t->keys[*slot])
        return IM_OK;
    if (2 * (t->used + 1) > t->capacity) {
        int status = table_grow(t);
        if (status != IM_OK)
            return status;
        *slot = slot_of(t, key);
    }
    t->keys[*slot] = key;
    ++t->used;
    return IM_OK;
}

static uint32_t pixel_rgb(const uint8_t *p) { return (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2]; }

int colour_table_build(const im_image *frames, int count, colour_table **table)
{
    colour_table *t = calloc(1, sizeof *t);
    int status = t ? table_allocate(t, 1024) : im_fail(IM_ENOMEM, "GIF palette: out of memory");
    for (int k = 0; status == IM_OK && k < count; ++k) {
        size_t pixels = (size_t)frames[k].width * frames[k].height, slot = 0;
        for (size_t i = 0; status == IM_OK && i < pixels; ++i) {
            status = table_slot(t, pixel_rgb(frames[k].rgba + 4 * i), &slot);
            t->counts[slot] += status == IM_OK;
        }
    }
    if (status != IM_OK) {
        colour_table_free(t);
        t = NULL;
    }
    *table = t;
    return status;
}

void colour_table_free(colour_table *table)
{
    if (table)
        table_release(table);
    free(table);
}

/* ---- the palette: greedy variance split ---- */

typedef struct weighted_colour {
    uint8_t rgb[3], key; /* key: the channel sorted on */
    double weight;
} weighted_colour;

typedef struct box {
    size_t begin, end; /* colours[begin, end) */
    double error;      /* pixel-weighted squared distance to the mean */
} box;

static int by_key(const void *a, const void *b)
{
    const weighted_colour *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return memcmp(x->rgb, y->rgb, 3); /* a total order: the same palette on every platform */
}

/* Per channel: sum of weights, of weight * value and of weight * value^2. */
typedef struct moments {
    double w, s[3], q[3];
} moments;

static void moments_add(moments *m, const weighted_colour *c)
{
    m->w += c->weight;
    for (int k = 0; k < 3; ++k) {
        m->s[k] += c->weight * c->rgb[k];
        m->q[k] += c->weight * c->rgb[k] * c->rgb[k];
    }
}

static double channel_error(const moments *m, int k) { return m->w > 0.0 ? m->q[k] - m->s[k] * m->s[k] / m->w : 0.0; }

static double moments_error(const moments *m)
{
    return channel_error(m, 0) + channel_error(m, 1) + channel_error(m, 2);
}

static moments box_moments(const weighted_colour *colours, const box *b)
{
    moments m = {0};
    for (size_t i = b->begin; i < b->end; ++i)
        moments_add(&m, &colours[i]);
    return m;
}

/* Splits b along its widest channel where the halves' error is least; *right gets the upper half. */
static void split_box(weighted_colour *colours, box *b, box *right)
{
    moments all = box_moments(colours, b), left = {0};
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        axis = channel_error(&all, k) > channel_error(&all, axis) ? k : axis;
    for (size_t i = b->begin; i < b->end; ++i)
        colours[i].key = colours[i].rgb[axis];
    qsort(colours + b->begin, b->end - b->begin, sizeof *colours, by_key);
    size_t best = b->begin + 1;
    double best_error = INFINITY;
    for (size_t i = b->begin; i + 1 < b->end; ++i) {
        moments_add(&left, &colours[i]);
        moments rest = all;
        for (int k = 0; k < 3; ++k)
            rest.s[k] -= left.s[k], rest.q[k] -= left.q[k];
        rest.w -= left.w;
        double error = moments_error(&left) + moments_error(&rest);
        if (error < best_error)
            best_error = error, best = i + 1;
    }
    *right = (box){best, b->end, 0.0};
    b->end = best;
    moments m = box_moments(colours, b);
    b->error = moments_error(&m);
    m = box_moments(colours, right);
    right->error = moments_error(&m);
}

static void box_mean(const weighted_colour *colours, const box *b, uint8_t rgb[3])
{
    moments m = box_moments(colours, b);
    for (int k = 0; k < 3; ++k) {
        long v = lround(m.s[k] / m.w);
        rgb[k] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
    }
}

/* The table's colours with a pixel, in a list. */
static weighted_colour *list_colours(const colour_table *t, size_t *n)
{
    weighted_colour *colours = malloc((t->used ? t->used : 1) * sizeof *colours);
    *n = 0;
    for (size_t i = 0; colours && i < t->capacity; ++i)
        if (t->keys[i] && t->counts[i]) {
            uint32_t rgb = t->keys[i] - 1;
            colours[(*n)++] = (weighted_colour){{(uint8_t)(rgb >> 16), (uint8_t)(rgb >> 8), (uint8_t)rgb},
                                                0,
                                                sqrt((double)t->counts[i])};
        }
    return colours;
}

int palette_build(const colour_table *table, int colours, gif_palette *palette)
{
    size_t n = 0;
    weighted_colour *list = list_colours(table, &n);
    if (!list)
        return im_fail(IM_ENOMEM, "GIF palette: out of memory");
    box boxes[256] = {{0, n, 0.0}};
    moments all = box_moments(list, &boxes[0]);
    boxes[0].error = moments_error(&all);
    int count = n > 0;
    for (; count < colours; ++count) {
        int worst = 0;
        for (int i = 1; i < count; ++i)
            worst = boxes[i].error > boxes[worst].error ? i : worst;
        if (boxes[worst].end - boxes[worst].begin < 2)
            break; /* every box holds one colour: the palette is exact */
        split_box(list, &boxes[worst], &boxes[count]);
    }
    palette->count = count;
    for (int i = 0; i < count; ++i)
        box_mean(list, &boxes[i], palette->rgb[i]);
    free(list);
    return IM_OK;
}

/* ---- mapping pixels ---- */

static int nearest(const gif_palette *p, const int rgb[3])
{
    int best = 0;
    long best_distance = LONG_MAX;
    for (int i = 0; i < p->count; ++i) {
        long d = 0;
        for (int k = 0; k < 3; ++k)
            d += (long)(rgb[k] - p->rgb[i][k]) * (rgb[k] - p->rgb[i][k]);
        if (d < best_distance)
            best_distance = d, best = i;
    }
    return best;
}

/* The palette index of a colour, remembered in the table; -1 for IM_ENOMEM. */
static int index_of(colour_table *t, const gif_palette *p, const int rgb[3])
{
    size_t slot = 0;
    if (table_slot(t, (uint32_t)rgb[0] << 16 | (uint32_t)rgb[1] << 8 | (uint32_t)rgb[2], &slot) != IM_OK)
        return -1;
    if (t->index[slot] < 0)
        t->index[slot] = (int16_t)nearest(p, rgb);
    return t->index[slot];
}

static int clamp_channel(double v)
{
    long r = lround(v);
    return r < 0 ? 0 : r > 255 ? 255 : (int)r;
}

/* One row of Floyd–Steinberg, left to right (direction 1) or right to left (-1): the error of each pixel
 * goes 7/16 to the next pixel of the row and 3/16, 5/16, 1/16 to the row below (errors are indexed from
 * 1, with a spare entry at each end). */
static int dither_row(colour_table *t, const gif_palette *p, const uint8_t *rgba, int width, int direction,
                      float *here, float *below, uint8_t *indices)
{
    memset(below, 0, (size_t)(width + 2) * 3 * sizeof *below);
    for (int step = 0; step < width; ++step) {
        int x = direction > 0 ? step : width - 1 - step, e = 3 * (x + 1), wanted[3];
        for (int k = 0; k < 3; ++k)
            wanted[k] = clamp_channel(rgba[4 * x + k] + here[e + k]);
        int index = index_of(t, p, wanted);
        if (index < 0)
            return im_fail(IM_ENOMEM, "GIF palette: out of memory");
        indices[x] = (uint8_t)index;
        for (int k = 0; k < 3; ++k) {
            float error = (float)(rgba[4 * x + k] + here[e + k] - p->rgb[index][k]);
            here[e + 3 * direction + k] += error * 7.0f / 16.0f;
            below[e - 3 * direction + k] += error * 3.0f / 16.0f;
            below[e + k] += error * 5.0f / 16.0f;
            below[e + 3 * direction + k] += error * 1.0f / 16.0f;
        }
    }
    return IM_OK;
}

static int dither_frame(colour_table *t, const gif_palette *p, const im_image *frame, uint8_t *indices)
{
    size_t length = (size_t)(frame->width + 2) * 3;
    float *here = calloc(length, sizeof *here), *below = calloc(length, sizeof *below);
    int status = here && below ? IM_OK : im_fail(IM_ENOMEM, "GIF dithering: out of memory");
    for (int y = 0; status == IM_OK && y < frame->height; ++y) {
        status = dither_row(t, p, frame->rgba + (size_t)y * frame->width * 4, frame->width, y % 2 ? -1 : 1, here,
                            below, indices + (size_t)y * frame->width);
        float *swap = here;
        here = below, below = swap;
    }
    free(here);
    free(below);
    return status;
}

int palette_index_frame(colour_table *table, const gif_palette *palette, const im_image *frame, int dither,
                        uint8_t *indices)
{
    if (dither)
        return dither_frame(table, palette, frame, indices);
    size_t pixels = (size_t)frame->width * frame->height;
    for (size_t i = 0; i < pixels; ++i) {
        const uint8_t *p = frame->rgba + 4 * i;
        int index = index_of(table, palette, (const int[3]){p[0], p[1], p[2]});
        if (index < 0)
            return im_fail(IM_ENOMEM, "GIF palette: out of memory");
        indices[i] = (uint8_t)index;
    }
    return IM_OK;
}
