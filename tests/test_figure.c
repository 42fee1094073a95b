/* Figures (cairo): panels placed pixel-exact, colour bar drawn from the exact table, ticks, PNG
 * metadata, PDF/SVG, atomic refusal of bad paths; frames and animations (GIF read back with
 * giflib and compared with the annotated PNG frames in CIELAB, MP4 when ffmpeg is installed). Needs no GL context: images are made by hand. */
#include "support.h"
#include "gif_compare.h"

#include "typeset/text.h"
#include "indentmap/colormap.h"
#include "indentmap/figure.h"
#include "indentmap/io.h"
#include "indentmap/status.h"

#include <dirent.h>
#include <png.h>
#include <gif_lib.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* A panel image whose pixel (x, y) is (8 x, 9 y, tag): each pixel identifies its position. */
static im_image make_image(int width, int height, int tag)
{
    im_image image = {.width = width,
                      .height = height,
                      .data_x = 2,
                      .data_y = 2,
                      .pixels_per_patch = 2,
                      .nx = (width - 4) / 2,
                      .ny = (height - 4) / 2,
                      .delta = 1.0};
    image.rgba = malloc((size_t)width * height * 4);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            uint8_t *p = image.rgba + ((size_t)y * width + x) * 4;
            p[0] = (uint8_t)(8 * x), p[1] = (uint8_t)(9 * y), p[2] = (uint8_t)tag, p[3] = 255;
        }
    return image;
}

/* The top-left corner of an exact copy of image inside the figure's RGB pixels; fails if absent. */
static void find_image(const uint8_t *rgb, int width, int height, const im_image *image, int *fx, int *fy)
{
    for (int y = 0; y + image->height <= height; ++y)
        for (int x = 0; x + image->width <= width; ++x) {
            int match = 1;
            for (int j = 0; match && j < image->height; ++j)
                for (int i = 0; match && i < image->width; ++i) {
                    const uint8_t *a = rgb + ((size_t)(y + j) * width + x + i) * 3;
                    const uint8_t *b = image->rgba + ((size_t)j * image->width + i) * 4;
                    match = a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
                }
            if (match) {
                *fx = x, *fy = y;
                return;
            }
        }
    fail_msg("panel %d x %d (tag %d) not found pixel-exact in the figure", image->width, image->height,
             image->rgba[2]);
}

static uint8_t *read_rgb(const char *path, int *width, int *height)
{
    uint8_t *pixels;
    int channels;
    assert_int_equal(im_png_read(path, &pixels, width, height, &channels), IM_OK);
    assert_int_equal(channels, 3);
    return pixels;
}

static void test_ticks(void **state)
{
    (void)state;
    double t[32];
    im_colormap c = im_colormap_make(IM_COLORMAP_VIRIDIS, 0.0, 1.0);
    assert_int_equal(im_figure_ticks(&c, t, 32), 6);
    for (int i = 0; i < 6; ++i)
        assert_close(t[i], 0.2 * i, 1e-12);
    c = im_colormap_make(IM_COLORMAP_VIRIDIS, -0.37, 0.73); /* span 1.1: step 0.5 */
    assert_int_equal(im_figure_ticks(&c, t, 32), 2);
    assert_close(t[0], 0.0, 0.0);
    assert_close(t[1], 0.5, 1e-12);
    c = im_colormap_make(IM_COLORMAP_VIRIDIS, 1e-3, 1.0);
    c.logarithmic = 1;
    assert_int_equal(im_figure_ticks(&c, t, 32), 4);
    assert_close(t[0], 1e-3, 1e-15);
    assert_close(t[3], 1.0, 1e-12);
    c = im_colormap_make(IM_COLORMAP_VIRIDIS, 0.3, 2.0); /* under one decade: 0.5, 1, 2 */
    c.logarithmic = 1;
    assert_int_equal(im_figure_ticks(&c, t, 32), 3);
    assert_close(t[0], 0.5, 1e-12);
    assert_close(t[1], 1.0, 1e-12);
    assert_close(t[2], 2.0, 1e-12);
}

/* Log bars spanning under three decades label 1-2-5 multiples, so that at least three labels show;
 * decades read 10^n; tiny physical values get a power of ten, not a string of zeros. */
static void test_tick_labels(void **state)
{
    (void)state;
    double t[32];
    char text[64];
    im_colormap c = im_colormap_make(IM_COLORMAP_MAGMA, 0.01, 0.3);
    c.logarithmic = 1;
    int count = im_figure_ticks(&c, t, 32);
    assert_int_equal(count, 5); /* 0.01 0.02 0.05 0.1 0.2 */
    const char *expected[] = {"0.01", "0.02", "0.05", "0.1", "0.2"};
    for (int i = 0; i < count; ++i) {
        typeset_tick_label(1, t, count, i, text, sizeof text);
        assert_string_equal(text, expected[i]);
    }
    c = im_colormap_make(IM_COLORMAP_MAGMA, 1e-3, 1.0);
    c.logarithmic = 1;
    count = im_figure_ticks(&c, t, 32);
    typeset_tick_label(1, t, count, 0, text, sizeof text);
    assert_string_equal(text, "10⁻³");
    const double thinned[] = {1e-3, 1e-1};
    typeset_tick_label(1, thinned, 2, 1, text, sizeof text);
    assert_string_equal(text, "10⁻¹");
    const double log_small[] = {2e-7, 5e-7};
    typeset_tick_label(1, log_small, 2, 1, text, sizeof text);
    assert_string_equal(text, "5×10⁻⁷");
    const double metres[] = {0.0, 5e-7, 1e-6, 1.5e-6};
    const char *metre_labels[] = {"0", "0.5×10⁻⁶", "1.0×10⁻⁶", "1.5×10⁻⁶"};
    for (int i = 0; i < 4; ++i) {
        typeset_tick_label(0, metres, 4, i, text, sizeof text);
        assert_string_equal(text, metre_labels[i]);
    }
    const double plain[] = {-0.2, 0.0, 0.2};
    typeset_tick_label(0, plain, 3, 0, text, sizeof text);
    assert_string_equal(text, "−0.2");
}

/* Scale bars in metres carry an SI prefix: "5 µm", never "5e-06 m". */
static void test_length_labels(void **state)
{
    (void)state;
    char text[64];
    const double lengths[] = {5e-6, 2e-9, 0.002, 0.5, 1.0, 2000.0, 1e-6};
    const char *labels[] = {"5 µm", "2 nm", "2 mm", "500 mm", "1 m", "2 km", "1 µm"};
    for (int i = 0; i < 7; ++i) {
        typeset_length_label(lengths[i], "m", text, sizeof text);
        assert_string_equal(text, labels[i]);
    }
    typeset_length_label(100.0, "", text, sizeof text);
    assert_string_equal(text, "100 δ");
    typeset_length_label(20.0, "px", text, sizeof text);
    assert_string_equal(text, "20 px");
}

static int is_ink(const uint8_t *rgb, int width, int x, int y)
{
    const uint8_t *p = rgb + ((size_t)y * width + x) * 3;
    return p[0] < 250 || p[1] < 250 || p[2] < 250;
}

/* Fails when any pixel within 2 pixels of the page's edge is not white: text clipped there. */
static void assert_clear_edges(const uint8_t *rgb, int width, int height)
{
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            if ((x < 2 || y < 2 || x >= width - 2 || y >= height - 2) && is_ink(rgb, width, x, y))
                fail_msg("ink at (%d, %d) on the edge of a %d x %d figure: text clipped", x, y, width, height);
}

/* The right-most ink column left of `limit` in rows [top, bottom) (-1: none), and the first from
 * column `from`. */
static int last_ink_column(const uint8_t *rgb, int width, int top, int bottom, int limit)
{
    int last = -1;
    for (int y = top; y < bottom; ++y)
        for (int x = 0; x < limit; ++x)
            if (is_ink(rgb, width, x, y) && x > last)
                last = x;
    return last;
}

static int first_ink_column(const uint8_t *rgb, int width, int top, int bottom, int from)
{
    for (int x = from; x < width; ++x)
        for (int y = top; y < bottom; ++y)
            if (is_ink(rgb, width, x, y))
                return x;
    return -1;
}

/* A small panel (32 x 32 patches at 2 px) with a label, a long title and a long colour bar label:
 * nothing is clipped at the page's edges and the title starts well after the label. */
static void test_small_panel_text_fits(void **state)
{
    (void)state;
    im_image image = make_image(68, 68, 9);
    im_figure_panel panel = {&image, "(a)", NULL};
    im_colormap norm = im_colormap_make(IM_COLORMAP_VIRIDIS, 0.0, 1.0);
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.colormap = &norm;
    figure.colorbar_label = "local force f / (E* δ²)";
    const char *path = test_path("small.png");
    int width, height, x, y;
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    uint8_t *rgb = read_rgb(path, &width, &height);
    find_image(rgb, width, height, &image, &x, &y);
    int label_end = last_ink_column(rgb, width, 0, y, x + image.width);
    assert_true(label_end > x);
    free(rgb);
    panel.title = "a long title";
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    rgb = read_rgb(path, &width, &height);
    assert_clear_edges(rgb, width, height);
    find_image(rgb, width, height, &image, &x, &y);
    double em = 8.0 * 300.0 / 72.0;
    int title_start = first_ink_column(rgb, width, 0, y, label_end + 1);
    assert_true(title_start > label_end + 0.4 * em);
    free(rgb);
    im_image_release(&image);
}

/* The colour bar's gap from the image (its first ink right of it, in the image's rows) in a figure of
 * one panel with the given title. */
static int colorbar_gap(im_image *image, const char *title)
{
    im_figure_panel panel = {image, NULL, title};
    im_colormap norm = im_colormap_make(IM_COLORMAP_VIRIDIS, 0.0, 1.0);
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.colormap = &norm;
    figure.colorbar_label = "height h / δ";
    figure.dpi = 150;
    const char *path = test_path("titled.png");
    int width, height, x, y;
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    uint8_t *rgb = read_rgb(path, &width, &height);
    assert_clear_edges(rgb, width, height);
    find_image(rgb, width, height, image, &x, &y);
    int gap = first_ink_column(rgb, width, y, y + image->height, x + image->width) - (x + image->width);
    free(rgb);
    return gap;
}

/* A title wider than its image (`render height --scale 1` of a 512^2 field) runs on above the colour
 * bar: the bar stays beside the image, as without a title (it stood the title's overhang off). */
static void test_colorbar_beside_an_image_under_a_wide_title(void **state)
{
    (void)state;
    im_image image = make_image(200, 240, 3);
    int plain = colorbar_gap(&image, NULL);
    assert_true(plain > 0 && plain < 40);
    assert_int_equal(
        colorbar_gap(&image, "a title far wider than the image it stands over, as at one pixel per patch"), plain);
    im_image_release(&image);
}

/* The note (e.g. "N* = 37000") sits under the panels and ends at the grid's right edge, clear of
 * the scale bar's text; a note longer than the grid widens the figure instead of being clipped. */
static void test_note_under_the_panels(void **state)
{
    (void)state;
    im_image image = make_image(600, 120, 5);
    im_figure_panel panel = {&image, NULL, NULL};
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    const char *path = test_path("note.png");
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    int width, height, x, y;
    uint8_t *rgb = read_rgb(path, &width, &height);
    find_image(rgb, width, height, &image, &x, &y);
    int bottom = y + image.height, plain_width = width, plain_height = height;
    int scale_text_end = last_ink_column(rgb, width, bottom, height, width);
    free(rgb);
    figure.note = "N* = 37000";
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    rgb = read_rgb(path, &width, &height);
    assert_int_equal(width, plain_width);
    assert_int_equal(height, plain_height);
    assert_clear_edges(rgb, width, height);
    int note_end = last_ink_column(rgb, width, bottom, height, width);
    assert_true(note_end <= x + image.width && note_end >= x + image.width - 3); /* right-aligned */
    int note_start = first_ink_column(rgb, width, bottom + 1, height, scale_text_end + 1);
    assert_true(note_start > scale_text_end + 8.0 * 300.0 / 72.0 * 0.9); /* a gap after the scale bar */
    free(rgb);
    figure.note = "a note much longer than the narrow panel it is written under";
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    rgb = read_rgb(path, &width, &height);
    assert_true(width > plain_width);
    assert_clear_edges(rgb, width, height);
    free(rgb);
    im_image_release(&image);
}

/* The tick labels right of a colour bar whose ink ends at column bar_right: the runs of rows holding
 * their ink, each at most one line high with at least 0.2 em of blank rows before the next. */
static int tick_label_runs(const uint8_t *rgb, int width, int height, int bar_right, double em)
{
    int from = bar_right + (int)ceil(0.55 * em), runs = 0, run = 0, gap = 1000;
    for (int row = 0; row <= height; ++row) {
        int ink = 0;
        for (int column = from; row < height && column < width && !ink; ++column)
            ink = is_ink(rgb, width, column, row);
        if (ink) {
            if (run == 0 && runs > 0)
                assert_true(gap >= 0.2 * em);
            ++run;
            gap = 0;
        } else {
            if (run > 0) {
                ++runs;
                assert_true(run <= 1.05 * em);
            }
            run = 0;
            ++gap;
        }
    }
    return runs;
}

/* A short colour bar: its tick labels are thinned, so that the labels' ink forms separate runs
 * of rows at most one line high with blank rows between them. */
static void test_short_colorbar_labels_apart(void **state)
{
    (void)state;
    im_image image = make_image(40, 30, 4);
    im_figure_panel panel = {&image, NULL, NULL};
    im_colormap norm = im_colormap_make(IM_COLORMAP_GREY, 0.0, 1.0);
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.colormap = &norm;
    figure.scale_bar = -1.0;
    figure.dpi = 150;
    const char *path = test_path("short.png");
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    int width, height, x, y;
    uint8_t *rgb = read_rgb(path, &width, &height);
    find_image(rgb, width, height, &image, &x, &y);
    assert_clear_edges(rgb, width, height);
    int bar_right = first_ink_column(rgb, width, y + 10, y + 11, x + image.width + 1);
    while (is_ink(rgb, width, bar_right + 1, y + 10))
        ++bar_right;
    assert_true(tick_label_runs(rgb, width, height, bar_right, 8.0 * 150.0 / 72.0) >= 2);
    free(rgb);
    im_image_release(&image);
}

/* Fig. 4's layout: 2 x 3 panels at their own pixel size in a regular grid, one colour bar. */
static void test_panel_grid_and_colorbar(void **state)
{
    (void)state;
    im_image images[6];
    im_figure_panel panels[6];
    const char *labels[6] = {"(a)", "(b)", "(c)", "(d)", "(e)", "(f)"};
    for (int i = 0; i < 6; ++i) {
        images[i] = make_image(28, 24, 100 + i);
        panels[i] = (im_figure_panel){&images[i], labels[i], i == 0 ? "smooth" : "h′rms = 0.01"};
    }
    im_colormap norm = im_colormap_make(IM_COLORMAP_MAGMA, 0.0, 2.0);
    im_figure figure = im_figure_default();
    figure.rows = 2, figure.columns = 3, figure.panels = panels;
    figure.colormap = &norm;
    figure.colorbar_label = "local force f / (E* δ²)";
    figure.dpi = 150;
    const char *path = test_path("grid.png");
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    int width, height, x[6], y[6];
    uint8_t *rgb = read_rgb(path, &width, &height);
    for (int i = 0; i < 6; ++i)
        find_image(rgb, width, height, &images[i], &x[i], &y[i]);
    for (int i = 0; i < 3; ++i) {
        assert_int_equal(y[i], y[0]);
        assert_int_equal(y[i + 3], y[3]);
        assert_int_equal(x[i + 3], x[i]);
    }
    assert_true(x[1] > x[0] + 28 && x[2] - x[1] == x[1] - x[0]);
    assert_true(y[3] > y[0] + 24);
    /* The colour bar, right of the panels: every pixel of its middle column is a table entry,
     * running from the last entry at the top to the first at the bottom. */
    const uint8_t(*table)[3] = im_colormap_table(IM_COLORMAP_MAGMA);
    int bar_x = -1;
    for (int column = x[2] + 28; column < width && bar_x < 0; ++column)
        for (int k = 200; k < 256 && bar_x < 0; ++k)
            if (memcmp(rgb + ((size_t)(y[0] + 2) * width + column) * 3, table[k], 3) == 0)
                bar_x = column;
    assert_true(bar_x > 0);
    int previous = 256, first = -1, rows = 0;
    for (int row = y[0]; row < y[3] + 24; ++row) {
        const uint8_t *p = rgb + ((size_t)row * width + bar_x + 3) * 3;
        int entry = -1;
        for (int k = 255; k >= 0 && entry < 0; --k)
            if (memcmp(p, table[k], 3) == 0)
                entry = k;
        if (entry < 0)
            continue; /* the outline or a tick */
        assert_true(entry <= previous);
        previous = entry;
        first = first < 0 ? entry : first;
        ++rows;
    }
    /* The bar spans the panels' height: its ends are within two rows' worth of entries. */
    double per_row = 256.0 / rows;
    assert_true(rows >= 2 * 24);
    assert_true(first >= 255 - 2 * per_row && previous <= 2 * per_row);
    free(rgb);
    for (int i = 0; i < 6; ++i)
        im_image_release(&images[i]);
}

/* Extension triangles: pixels of the over colour above the bar and of the under colour below it,
 * none without the flags. */
static int count_colour(const uint8_t *rgb, int width, int height, const uint8_t colour[3], int above_row,
                        int below_row)
{
    int count = 0;
    for (int row = 0; row < height; ++row)
        for (int x = 0; x < width; ++x)
            if (memcmp(rgb + ((size_t)row * width + x) * 3, colour, 3) == 0 && (row < above_row || row > below_row))
                ++count;
    return count;
}

/* Over and under colours that no test image nor colour map holds. */
static const uint8_t over[3] = {255, 0, 255}, under[3] = {0, 200, 255};

/* A figure at 150 dpi of one panel beside the bar of a norm on [0, 1] of map with those over and under
 * colours, which *norm receives. */
static im_figure extended_figure(im_figure_panel *panel, im_colormap_id map, im_colormap *norm)
{
    *norm = im_colormap_make(map, 0.0, 1.0);
    memcpy(norm->over, over, 3);
    memcpy(norm->under, under, 3);
    im_figure figure = im_figure_default();
    figure.panels = panel;
    figure.colormap = norm;
    figure.dpi = 150;
    return figure;
}

static void test_colorbar_extensions(void **state)
{
    (void)state;
    im_image image = make_image(40, 40, 5);
    im_figure_panel panel = {&image, NULL, NULL};
    im_colormap norm;
    im_figure figure = extended_figure(&panel, IM_COLORMAP_GREY, &norm);
    const char *path = test_path("extend.png");
    int width, height, x, y;
    for (int extend = 0; extend <= 1; ++extend) {
        figure.extend_under = figure.extend_over = extend;
        assert_int_equal(im_figure_write(&figure, path), IM_OK);
        uint8_t *rgb = read_rgb(path, &width, &height);
        find_image(rgb, width, height, &image, &x, &y);
        int middle = y + 20;
        int n_over = count_colour(rgb, width, height, over, middle, height);
        int n_under = count_colour(rgb, width, height, under, -1, middle);
        if (extend) {
            assert_true(n_over > 20 && n_under > 20);
        } else {
            assert_int_equal(n_over + n_under, 0);
        }
        free(rgb);
    }
    im_image_release(&image);
}

/* The index of the map's table entry with this colour, -1 if none. */
static int table_index(im_colormap_id map, const uint8_t *rgb)
{
    const uint8_t(*ramp)[3] = im_colormap_table(map);
    for (int k = 0; k < 256; ++k)
        if (memcmp(ramp[k], rgb, 3) == 0)
            return k;
    return -1;
}

/* The column holding the most pixels of the map's table, and how many; -1 and 0 when none does. */
static int table_column(im_colormap_id map, const uint8_t *rgb, int width, int height, int *most)
{
    int best = -1;
    *most = 0;
    for (int x = 0; x < width; ++x) {
        int count = 0;
        for (int row = 0; row < height; ++row)
            count += table_index(map, rgb + ((size_t)row * width + x) * 3) >= 0;
        if (count > *most)
            *most = count, best = x;
    }
    return best;
}

/* The tension's bar: right of the force's (grey) bar, a column of ramp colours from the last entry at
 * the top down to the first, each pixel's entry no higher than the one above it; a figure without a
 * tension norm has no ramp colour anywhere. */
static void test_tension_colorbar(void **state)
{
    (void)state;
    im_image image = make_image(60, 200, 5);
    im_figure_panel panel = {&image, NULL, NULL};
    im_colormap norm = im_colormap_make(IM_COLORMAP_GREY, 0.0, 1.0);
    im_colormap tension = im_contact_tension_norm(0.3);
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.colormap = &norm;
    figure.colorbar_label = "local force f / N";
    figure.dpi = 150;
    const char *path = test_path("tension.png");
    int width, height, x, y, most;
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    uint8_t *rgb = read_rgb(path, &width, &height);
    assert_int_equal(table_column(IM_COLORMAP_TENSION, rgb, width, height, &most), -1);
    free(rgb);
    int width_without = width;
    figure.tension_colormap = &tension;
    figure.tension_label = "tensile force −f / N";
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    rgb = read_rgb(path, &width, &height);
    find_image(rgb, width, height, &image, &x, &y);
    int column = table_column(IM_COLORMAP_TENSION, rgb, width, height, &most), grey_bar = 0;
    assert_true(width > width_without && most > 150);
    for (int c = x + image.width; c < column; ++c) { /* the force's bar: its middle, left of the ramp */
        const uint8_t *p = rgb + ((size_t)(y + 100) * width + c) * 3;
        grey_bar |= p[0] == p[1] && p[1] == p[2] && abs(p[0] - 128) < 8;
    }
    assert_true(grey_bar);
    int first = -1, last = -1;
    for (int row = 0; row < height; ++row) {
        int k = table_index(IM_COLORMAP_TENSION, rgb + ((size_t)row * width + column) * 3);
        if (k < 0)
            continue;
        if (last >= 0 && k > last)
            fail_msg("row %d: ramp entry %d below entry %d", row, k, last);
        first = first < 0 ? k : first;
        last = k;
    }
    if (!(first >= 250 && last <= 5)) /* the ends: less the outline and nearest sampling's rounding */
        fail_msg("ramp entries %d (top) to %d (bottom)", first, last);
    figure.tension_label = NULL;
    tension.hi = tension.lo; /* no bar for a bad norm: an error naming it */
    assert_int_equal(im_figure_write(&figure, path), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "tension colour bar"));
    free(rgb);
    im_image_release(&image);
}

/* Beside a strip 16 patches high (a 16 x 1024 scan at 2 px per patch) the colour bar keeps a readable
 * length: it was the strip's height less its two triangles, here -4 px, the triangles drawn over each
 * other and one tick labelled. Now at least 2.4 em of the table (two labels 1.2 em apart), the over
 * triangle wholly above it, the under triangle below, and two or more tick labels. */
static void test_colorbar_beside_a_strip(void **state)
{
    (void)state;
    im_image image = make_image(600, 36, 6);
    im_figure_panel panel = {&image, NULL, NULL};
    im_colormap norm;
    im_figure figure = extended_figure(&panel, IM_COLORMAP_VIRIDIS, &norm);
    figure.extend_under = figure.extend_over = 1;
    const char *path = test_path("strip.png");
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    int width, height, most;
    uint8_t *rgb = read_rgb(path, &width, &height);
    assert_clear_edges(rgb, width, height);
    double em = 8.0 * 150.0 / 72.0;
    int column = table_column(IM_COLORMAP_VIRIDIS, rgb, width, height, &most), top = height, bottom = -1;
    assert_true(column >= 0 && most >= 2.4 * em);
    for (int row = 0; row < height; ++row)
        if (table_index(IM_COLORMAP_VIRIDIS, rgb + ((size_t)row * width + column) * 3) >= 0)
            top = row < top ? row : top, bottom = row;
    assert_true(count_colour(rgb, width, height, over, height, height) > 20);
    assert_true(count_colour(rgb, width, height, under, height, height) > 20);
    assert_int_equal(count_colour(rgb, width, height, over, 0, top - 1), 0);
    assert_int_equal(count_colour(rgb, width, height, under, bottom + 1, height), 0);
    int bar_right = column;
    while (is_ink(rgb, width, bar_right + 1, top + 1))
        ++bar_right;
    assert_true(tick_label_runs(rgb, width, height, bar_right, em) >= 2);
    free(rgb);
    im_image_release(&image);
}

/* The rightmost ink below the image, as columns right of the image's left edge, in a figure of one
 * small panel with or without a colour bar (whose bar then starts at *bar_left, likewise). */
static int ink_below_small_panel(im_image *image, const im_colormap *norm, int *bar_left)
{
    im_figure_panel panel = {image, NULL, NULL};
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.colormap = norm;
    figure.dpi = 150;
    const char *path = test_path("small_bar.png");
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    int width, height, x, y, most;
    uint8_t *rgb = read_rgb(path, &width, &height);
    assert_clear_edges(rgb, width, height);
    find_image(rgb, width, height, image, &x, &y);
    int limit = width, column = norm ? table_column(norm->map, rgb, width, height, &most) : -1;
    if (norm) {
        *bar_left = column;
        while (is_ink(rgb, width, *bar_left - 1, height / 2))
            --*bar_left;
        *bar_left -= x;
        limit = x + *bar_left;
    }
    int end = last_ink_column(rgb, width, y + image->height, height, limit) - x;
    free(rgb);
    return end;
}

/* Under a panel of 3 x 3 patches the scale bar's text ("0.5 δ") is wider than the panel: the colour bar,
 * lengthened below the panel, stands right of it (it stood over the text's δ). */
static void test_colorbar_right_of_the_scale_text(void **state)
{
    (void)state;
    im_image image = make_image(10, 10, 7);
    im_colormap norm = im_colormap_make(IM_COLORMAP_VIRIDIS, 0.0, 1.0);
    int bar_left = 0, text_end = ink_below_small_panel(&image, NULL, NULL);
    assert_true(text_end > image.width);
    ink_below_small_panel(&image, &norm, &bar_left);
    assert_true(bar_left > text_end);
    im_image_release(&image);
}

/* The rows from the bottom of the bottom-left panel (of side `small`, the others of side `large`, 2 x 2 panels)
 * down to the top of the scale bar under it, measured in the PNG's pixels: the first dark pixel below the
 * panel in a column of the bar (its data's third pixel). */
static int scale_bar_drop(int small, int large)
{
    im_image images[4];
    im_figure_panel panels[4];
    for (int i = 0; i < 4; ++i) {
        images[i] = make_image(i == 2 ? small : large, i == 2 ? small : large, 40 + i);
        panels[i] = (im_figure_panel){&images[i], NULL, NULL};
    }
    im_figure figure = im_figure_default();
    figure.rows = 2, figure.columns = 2, figure.panels = panels;
    figure.dpi = 150;
    const char *path = test_path("scale_bar.png");
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    int width, height, x, y;
    uint8_t *rgb = read_rgb(path, &width, &height);
    find_image(rgb, width, height, &images[2], &x, &y);
    int row = y + images[2].height;
    for (const uint8_t *p; row < height; ++row)
        if (p = rgb + ((size_t)row * width + x + images[2].data_x + 2) * 3, p[0] < 64 && p[1] < 64 && p[2] < 64)
            break;
    assert_true(row < height);
    free(rgb);
    for (int i = 0; i < 4; ++i)
        im_image_release(&images[i]);
    return row - (y + small);
}

/* The scale bar gives the bottom-left panel's scale and sits under it as under panels of one size, though the
 * other panels are twice its side (S13: it sat under the larger cell, far below a 64^2 panel among 128^2). */
static void test_scale_bar_under_its_panel(void **state)
{
    (void)state;
    const int drop = scale_bar_drop(68, 68);
    assert_true(drop > 0 && drop < 20);
    assert_int_equal(scale_bar_drop(68, 132), drop);
}

/* The length in pixels of the first dark run in the 40 rows below image (found in the figure's PNG pixels), in
 * the column of its data's third pixel and to the right of it: its scale bar; 0 where none hangs from it. */
static int scale_bar_under(const uint8_t *rgb, int width, int height, const im_image *image)
{
    int x, y;
    find_image(rgb, width, height, image, &x, &y);
    const int left = x + image->data_x;
#define DARK(row, column)                                                                                            \
    (rgb[((size_t)(row)*width + (column)) * 3] < 64 && rgb[((size_t)(row)*width + (column)) * 3 + 1] < 64 &&         \
     rgb[((size_t)(row)*width + (column)) * 3 + 2] < 64)
    for (int row = y + image->height; row < height && row < y + image->height + 40; ++row)
        if (DARK(row, left + 2)) {
            int end = left;
            while (end < width && DARK(row, end))
                ++end;
            return end - left;
        }
#undef DARK
    return 0;
}

/* Panels of different spacings have a scale bar each (a bar under the bottom-left panel gave its scale only): 1
 * and 2 nm patches side by side, a 10 nm bar 10 and 5 patches long (2 pixels a patch); panels of one spacing
 * keep their one bar; one panel above the other, each with its bar. Measured in the PNG. */
static void test_a_scale_bar_per_spacing(void **state)
{
    (void)state;
    im_image images[2] = {make_image(64, 64, 50), make_image(64, 64, 51)};
    im_figure_panel panels[2];
    for (int i = 0; i < 2; ++i) {
        snprintf(images[i].unit, sizeof images[i].unit, "nm");
        images[i].delta = i + 1.0;
        panels[i] = (im_figure_panel){&images[i], NULL, NULL};
    }
    im_figure figure = im_figure_default();
    figure.rows = 1, figure.columns = 2, figure.panels = panels, figure.scale_bar = 10.0;
    const char *path = test_path("spacings.png");
    int width, height;
    for (int same = 0; same < 2; ++same) {
        images[1].delta = same ? 1.0 : 2.0;
        assert_int_equal(im_figure_write(&figure, path), IM_OK);
        uint8_t *rgb = read_rgb(path, &width, &height);
        assert_int_equal(scale_bar_under(rgb, width, height, &images[0]), 20);
        assert_int_equal(scale_bar_under(rgb, width, height, &images[1]), same ? 0 : 10);
        free(rgb);
    }
    figure.rows = 2, figure.columns = 1; /* one above the other: a strip for the upper one's bar */
    images[1].delta = 2.0;
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    uint8_t *rgb = read_rgb(path, &width, &height);
    assert_int_equal(scale_bar_under(rgb, width, height, &images[0]), 20);
    assert_int_equal(scale_bar_under(rgb, width, height, &images[1]), 10);
    free(rgb);
    for (int i = 0; i < 2; ++i)
        im_image_release(&images[i]);
}

/* Finds a PNG chunk of the given type whose data starts with prefix; returns its data or NULL. */
static const uint8_t *find_chunk(const uint8_t *png, size_t size, const char *type, const char *prefix,
                                 size_t prefix_length)
{
    for (size_t at = 8; at + 12 <= size;) {
        size_t length = (size_t)png[at] << 24 | (size_t)png[at + 1] << 16 | (size_t)png[at + 2] << 8 | png[at + 3];
        if (memcmp(png + at + 4, type, 4) == 0 && length >= prefix_length &&
            memcmp(png + at + 8, prefix, prefix_length) == 0)
            return png + at + 8;
        at += length + 12;
    }
    return NULL;
}

static uint8_t *slurp(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    *size = (size_t)ftell(f);
    rewind(f);
    uint8_t *data = malloc(*size + 1);
    assert_int_equal(fread(data, 1, *size, f), *size);
    data[*size] = 0;
    fclose(f);
    return data;
}

/* Whether binary data (a PDF, with NUL bytes in its streams) contains text. */
static int contains(const uint8_t *data, size_t size, const char *text)
{
    size_t length = strlen(text);
    for (size_t at = 0; at + length <= size; ++at)
        if (memcmp(data + at, text, length) == 0)
            return 1;
    return 0;
}

/* The text chunk called key, read back with libpng: its value and compression (the chunk type:
 * PNG_TEXT_COMPRESSION_NONE for tEXt, PNG_ITXT_COMPRESSION_NONE for iTXt); fails if absent. */
static int read_png_text(const char *path, const char *key, char *value, size_t size)
{
    FILE *stream = fopen(path, "rb");
    assert_non_null(stream);
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    assert_non_null(info);
    if (setjmp(png_jmpbuf(png)))
        fail_msg("%s: libpng cannot read it", path);
    png_init_io(png, stream);
    png_read_info(png, info);
    png_textp texts = NULL;
    int count = png_get_text(png, info, &texts, NULL), compression = -100;
    for (int i = 0; i < count; ++i)
        if (strcmp(texts[i].key, key) == 0) {
            snprintf(value, size, "%s", texts[i].text);
            compression = texts[i].compression;
        }
    png_destroy_read_struct(&png, &info, NULL);
    fclose(stream);
    if (compression == -100)
        fail_msg("%s: no text chunk '%s'", path, key);
    return compression;
}

/* UTF-8 beyond ASCII (tEXt must be Latin-1) goes into iTXt; ASCII stays in tEXt. */
static void test_png_text_utf8_in_itxt(void **state)
{
    (void)state;
    im_image image = make_image(12, 12, 3);
    im_figure_panel panel = {&image, NULL, NULL};
    im_png_text texts[] = {{"Quantity", "f / (E* δ²)"}, {"Software", "indentmap"}};
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.texts = texts, figure.text_count = 2;
    const char *path = test_path("utf8.png");
    assert_int_equal(im_figure_write(&figure, path), IM_OK);
    char value[128];
    assert_int_equal(read_png_text(path, "Quantity", value, sizeof value), PNG_ITXT_COMPRESSION_NONE);
    assert_string_equal(value, "f / (E* δ²)");
    assert_int_equal(read_png_text(path, "Software", value, sizeof value), PNG_TEXT_COMPRESSION_NONE);
    assert_string_equal(value, "indentmap");
    size_t size;
    uint8_t *data = slurp(path, &size);
    assert_non_null(find_chunk(data, size, "iTXt", "Quantity\0\0\0\0\0f / (E* δ²)", 9 + 4 + strlen("f / (E* δ²)")));
    assert_null(find_chunk(data, size, "tEXt", "Quantity", 8));
    free(data);
    im_image_release(&image);
}

static void test_png_metadata_pdf_svg(void **state)
{
    (void)state;
    im_image image = make_image(30, 30, 7);
    im_figure_panel panel = {&image, "(a)", NULL};
    im_png_text texts[] = {{"Indenter", "cone alpha=80"}, {"Software", "indentmap"}};
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.texts = texts, figure.text_count = 2;
    const char *png = test_path("meta.png");
    assert_int_equal(im_figure_write(&figure, png), IM_OK);
    size_t size;
    uint8_t *data = slurp(png, &size);
    assert_non_null(find_chunk(data, size, "tEXt", "Indenter\0cone alpha=80", 22));
    const uint8_t *phys = find_chunk(data, size, "pHYs", "", 0);
    assert_non_null(phys);
    uint32_t dpm = (uint32_t)phys[0] << 24 | (uint32_t)phys[1] << 16 | (uint32_t)phys[2] << 8 | phys[3];
    assert_int_equal(dpm, 11811); /* 300 dpi = 11811.02 per metre */
    free(data);
    assert_int_equal(im_figure_write(&figure, test_path("meta.pdf")), IM_OK);
    data = slurp(test_path("meta.pdf"), &size);
    assert_memory_equal(data, "%PDF-", 5);
    assert_true(contains(data, size, "Indenter=cone alpha=80"));
    free(data);
    assert_int_equal(im_figure_write(&figure, test_path("meta.svg")), IM_OK);
    data = slurp(test_path("meta.svg"), &size);
    assert_non_null(strstr((const char *)data, "<svg"));
    assert_non_null(strstr((const char *)data, "<image"));
    free(data);
    im_image_release(&image);
}

static int directory_entries(const char *path)
{
    DIR *dir = opendir(path);
    int count = 0;
    for (struct dirent *e; dir && (e = readdir(dir)) != NULL;)
        count += e->d_name[0] != '.';
    if (dir)
        closedir(dir);
    return count;
}

static void test_bad_figures_refused(void **state)
{
    (void)state;
    im_image image = make_image(10, 10, 1);
    im_figure_panel panel = {&image, NULL, NULL};
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    int before = directory_entries(test_temp_dir());
    assert_int_equal(im_figure_write(&figure, test_path("missing/dir/figure.png")), IM_EIO);
    assert_int_equal(im_figure_write(&figure, test_path("missing/dir/figure.pdf")), IM_EIO);
    assert_int_equal(im_figure_write(&figure, test_path("figure.tiff")), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), ".png, .pdf or .svg"));
    figure.dpi = 0.0;
    assert_int_equal(im_figure_write(&figure, test_path("figure.png")), IM_EINVAL);
    figure = im_figure_default();
    im_figure_panel empty = {NULL, "(a)", NULL};
    figure.panels = &empty;
    assert_int_equal(im_figure_write(&figure, test_path("figure.png")), IM_EINVAL);
    assert_int_equal(directory_entries(test_temp_dir()), before); /* nothing half-written */
    im_image_release(&image);
}

static void test_frame_paths(void **state)
{
    (void)state;
    char path[64];
    assert_int_equal(im_frame_path(path, sizeof path, "run", "contact", 7), IM_OK);
    assert_string_equal(path, "run/contact_0007.png");
    assert_int_equal(im_frame_path(path, sizeof path, "run", "height", 12345), IM_OK);
    assert_string_equal(path, "run/height_12345.png");
    assert_int_equal(im_frame_path(path, 10, "run", "contact", 1), IM_EINVAL);
    assert_int_equal(im_frame_path(path, sizeof path, "run", "contact", -1), IM_EINVAL);
}

/* The colour bar's labels in the fields' units, as issue 29 states them; a quantity of no field is refused. */
static void test_colorbar_labels(void **state)
{
    (void)state;
    static const char *const EXPECTED[][3] = {{"force", "N", "local force f / N"},
                                              {"force", "", "local force f / (E* δ²)"},
                                              {"height", "µm", "height h / µm"},
                                              {"height", "", "height h / δ"},
                                              {"gap", "m", "gap g / m"},
                                              {"displacement", "nm", "displacement u / nm"},
                                              {"plastic", "", "plastic depth d / δ"},
                                              {"tension", "N", "tensile force −f / N"},
                                              {"tension", "", "tensile force −f / (E* δ²)"},
                                              {"force", "E* δ²", "local force f / (E* δ²)"},
                                              {"force", "Pa µm²", "local force f / (Pa µm²)"}};
    char text[64];
    for (size_t i = 0; i < sizeof EXPECTED / sizeof *EXPECTED; ++i) {
        assert_int_equal(im_figure_colorbar_label(EXPECTED[i][0], EXPECTED[i][1], text, sizeof text), IM_OK);
        assert_string_equal(text, EXPECTED[i][2]);
    }
    assert_int_equal(im_figure_colorbar_label("pressure", "Pa", text, sizeof text), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "quantity 'pressure': expected force, height"));
    assert_int_equal(im_figure_colorbar_label("force", "N", text, strlen("local force f / N")), IM_EINVAL);
    assert_int_equal(im_figure_colorbar_label("force", "N", text, strlen("local force f / N") + 1), IM_OK);
}

/* Frames with at most 256 colours between them come back from the GIF pixel for pixel, with one global
 * palette, the frame count and the delay asked for. */
static void test_gif_round_trip(void **state)
{
    (void)state;
    im_image frames[3];
    for (int k = 0; k < 3; ++k) {
        frames[k] = make_image(12, 10, 0);
        for (int i = 0; i < 120; ++i) {
            uint8_t *p = frames[k].rgba + 4 * i;
            const uint8_t *entry = im_colormap_table(IM_COLORMAP_VIRIDIS)[(i * 37 + k * 50) % 256];
            memcpy(p, i % 5 ? entry : (const uint8_t[3]){230, 230, 230}, 3);
        }
    }
    const char *path = test_path("run.gif");
    im_gif_options options = im_gif_options_default();
    options.seconds_per_frame = 0.2;
    assert_int_equal(im_animation_gif_with(frames, 3, &options, path), IM_OK);
    gif_readback g;
    assert_int_equal(gif_read(path, &g), 0);
    assert_int_equal(g.count, 3);
    assert_true(g.palette_size >= 2 && g.palette_size <= 256);
    for (int k = 0; k < 3; ++k) {
        assert_int_equal(g.delays[k], 20);
        assert_memory_equal(g.rgba + k * 120 * 4, frames[k].rgba, 120 * 4);
    }
    free(g.rgba);
    for (int k = 0; k < 3; ++k)
        im_image_release(&frames[k]);
}

/* More colours than a GIF holds: one palette of at most 256 (or the colours asked for), every pixel
 * near its colour; dithering keeps the 3 x 3 means nearer. Measured: 300 colours on 256 entries, mean
 * ΔE 0.54, largest 2.6; on 16 entries mean 7.4 nearest, 8.3 dithered (3 x 3 means: 3.4 and 2.3). */
static void test_gif_quantises(void **state)
{
    (void)state;
    im_image many = make_image(20, 15, 3); /* 300 distinct colours */
    const char *path = test_path("many.gif");
    im_gif_options options = im_gif_options_default();
    assert_int_equal(im_animation_gif_with(&many, 1, &options, path), IM_OK);
    gif_readback g;
    assert_int_equal(gif_read(path, &g), 0);
    assert_int_equal(g.palette_size, 256);
    colour_error e = image_delta_e(g.rgba, many.rgba, 20, 15, 0);
    print_message("300 colours on 256: mean ΔE %.3f, largest %.2f\n", e.mean, e.max);
    assert_true(e.mean < 1.0 && e.max < 5.0);
    free(g.rgba);
    double blurred[2];
    for (int dither = 0; dither < 2; ++dither) {
        options.colours = 16;
        options.dither = dither;
        assert_int_equal(im_animation_gif_with(&many, 1, &options, path), IM_OK);
        assert_int_equal(gif_read(path, &g), 0);
        assert_int_equal(g.palette_size, 16);
        e = image_delta_e(g.rgba, many.rgba, 20, 15, 0);
        blurred[dither] = image_delta_e(g.rgba, many.rgba, 20, 15, 1).mean;
        print_message("16 colours, dither %d: mean ΔE %.2f (3 x 3 means: %.2f)\n", dither, e.mean, blurred[dither]);
        assert_true(e.mean < 10.0);
        free(g.rgba);
    }
    assert_true(blurred[1] < blurred[0]);
    im_image_release(&many);
}

/* Bad options are refused naming the option and what was expected; nothing is written. */
static void test_gif_options_refused(void **state)
{
    (void)state;
    im_image frame = make_image(8, 8, 1);
    const char *path = test_path("refused.gif");
    const struct {
        im_gif_options options;
        const char *says;
    } cases[] = {{{0.001, 256, 0}, "s per frame: expected [0.01, 600]"},
                 {{0.1, 1, 0}, "1 colours: expected 2 to 256"},
                 {{0.1, 257, 0}, "257 colours: expected 2 to 256"},
                 {{0.1, 256, 2}, "dither = 2: expected 0 or 1"}};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; ++i) {
        assert_int_equal(im_animation_gif_with(&frame, 1, &cases[i].options, path), IM_EINVAL);
        assert_non_null(strstr(im_last_error(), cases[i].says));
    }
    struct stat st;
    assert_int_not_equal(stat(path, &st), 0);
    im_image out = {0};
    im_figure figure = im_figure_default();
    im_figure_panel panel = {&frame, NULL, NULL};
    figure.panels = &panel;
    assert_int_equal(im_figure_write_frame(&figure, test_path("frame.pdf"), &out), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "expected a path ending in .png"));
    assert_null(out.rgba);
    im_image_release(&frame);
}

/* A column of the image whose pixels, top to bottom, run through the colour map's table in order over
 * at least 200 of its 256 entries: the colour bar. Returns the column or -1. */
static int colorbar_column(const uint8_t *rgba, int width, int height, im_colormap_id map)
{
    const uint8_t(*table)[3] = im_colormap_table(map);
    for (int x = 0; x < width; ++x) {
        int first = -1, last = -1, monotone = 1, matched = 0;
        for (int y = 0; y < height && monotone; ++y) {
            const uint8_t *p = rgba + ((size_t)y * width + x) * 4;
            int best = -1, best_d = 3 * 3 * 3;
            for (int i = 0; i < 256; ++i) {
                int d = 0;
                for (int k = 0; k < 3; ++k)
                    d += (p[k] - table[i][k]) * (p[k] - table[i][k]);
                if (d < best_d)
                    best_d = d, best = i;
            }
            if (best < 0)
                continue;
            monotone = last < 0 || best <= last; /* the top of the bar is the norm's high end */
            first = first < 0 ? best : first;
            last = best;
            ++matched;
        }
        if (monotone && matched > 100 && first - last >= 200)
            return x;
    }
    return -1;
}

/* Near-black pixels (text, ticks, the scale bar; magma's low end too): returns their count (channels
 * below 50) and how many of them are dark in other too (below 70: a margin for the palette). */
static int dark_pixels(const uint8_t *rgba, const uint8_t *other, size_t pixels, int *also)
{
    int count = 0;
    *also = 0;
    for (size_t i = 0; i < pixels; ++i) {
        const uint8_t *p = rgba + 4 * i, *q = other + 4 * i;
        if (p[0] < 50 && p[1] < 50 && p[2] < 50) {
            ++count;
            *also += q[0] < 70 && q[1] < 70 && q[2] < 70;
        }
    }
    return count;
}

/* Writes three annotated frames (a map in the colour map's colours, a title, the colour bar, a scale
 * bar) as PNG frames and a GIF of the pixels im_figure_write_frame gave back, and returns the PNGs'
 * pixels as RGBA. */
static void write_annotated_frames(im_image frames[3], im_image pngs[3], const char *gif)
{
    im_colormap norm = im_colormap_make(IM_COLORMAP_MAGMA, 0.0, 1.0);
    im_image data = make_image(200, 160, 0);
    for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < 200 * 160; ++i)
            memcpy(data.rgba + 4 * i, im_colormap_table(IM_COLORMAP_MAGMA)[(i % 200 + i / 200 + 40 * k) % 256], 3);
        char title[32], path[64];
        snprintf(title, sizeof title, "N* = %d", 100 * (k + 1));
        snprintf(path, sizeof path, "annotated_%d.png", k);
        im_figure_panel panel = {&data, NULL, title};
        im_figure figure = im_figure_default();
        figure.panels = &panel;
        figure.colormap = &norm;
        figure.colorbar_label = "local force f / (E* δ²)";
        figure.dpi = 150;
        assert_int_equal(im_figure_write_frame(&figure, test_path(path), &frames[k]), IM_OK);
        pngs[k] = (im_image){0};
        uint8_t *rgb = read_rgb(test_path(path), &pngs[k].width, &pngs[k].height);
        assert_int_equal(pngs[k].width, frames[k].width);
        assert_int_equal(pngs[k].height, frames[k].height);
        pngs[k].rgba = malloc((size_t)pngs[k].width * pngs[k].height * 4);
        for (int i = 0; i < pngs[k].width * pngs[k].height; ++i)
            memcpy(pngs[k].rgba + 4 * i, rgb + 3 * i, 3), pngs[k].rgba[4 * i + 3] = 255;
        free(rgb);
        assert_memory_equal(pngs[k].rgba, frames[k].rgba, (size_t)pngs[k].width * pngs[k].height * 4);
    }
    im_image_release(&data);
    im_gif_options options = im_gif_options_default();
    options.seconds_per_frame = 0.5;
    assert_int_equal(im_animation_gif_with(frames, 3, &options, gif), IM_OK);
}

/* The GIF shows the annotated PNG frames: the colour bar in the colour map's order in the same
 * column, the text and scale bar where the PNG has them, every pixel near its PNG colour. Measured
 * (330 x 251 frames): mean ΔE 0.16-0.17, 99th percentile 1.1, largest 2.3. */
static void test_gif_annotated_like_png(void **state)
{
    (void)state;
    im_image frames[3], pngs[3];
    const char *path = test_path("annotated.gif");
    write_annotated_frames(frames, pngs, path);
    gif_readback g;
    assert_int_equal(gif_read(path, &g), 0);
    assert_int_equal(g.count, 3);
    assert_true(g.palette_size <= 256);
    assert_int_equal(g.width, pngs[0].width);
    assert_int_equal(g.height, pngs[0].height);
    size_t pixels = (size_t)g.width * g.height;
    for (int k = 0; k < 3; ++k) {
        const uint8_t *shown = g.rgba + k * pixels * 4;
        assert_int_equal(g.delays[k], 50);
        int bar = colorbar_column(pngs[k].rgba, g.width, g.height, IM_COLORMAP_MAGMA);
        assert_true(bar > 0);
        assert_int_equal(colorbar_column(shown, g.width, g.height, IM_COLORMAP_MAGMA), bar);
        int also = 0, dark = dark_pixels(pngs[k].rgba, shown, pixels, &also);
        colour_error e = image_delta_e(shown, pngs[k].rgba, g.width, g.height, 0);
        print_message("frame %d: %d x %d, %d palette entries, colour bar at x = %d, %d dark pixels (%d in the "
                      "GIF), mean ΔE %.3f, p99 %.2f, largest %.1f\n",
                      k, g.width, g.height, g.palette_size, bar, dark, also, e.mean, e.p99, e.max);
        assert_true(dark > 100);
        assert_true(also >= 0.99 * dark);
        assert_true(e.mean < 0.5 && e.p99 < 2.0 && e.max < 6.0);
        im_image_release(&frames[k]);
        im_image_release(&pngs[k]);
    }
    free(g.rgba);
}

/* Two frames of three encoded are the video of a folder holding those two alone (a frame left from a
 * longer run is not read): the same bytes (x264 is deterministic for the same input). */
static void assert_mp4_reads_count_frames(const char *three, const im_image *image)
{
    const char *two = test_path("two_frames");
    assert_int_equal(im_make_directories(two), IM_OK);
    for (int i = 0; i < 2; ++i) {
        char path[4096];
        assert_int_equal(im_frame_path(path, sizeof path, two, "contact", i), IM_OK);
        assert_int_equal(im_png_write(path, image->rgba, image->width, image->height, 4, image->width * 4, NULL),
                         IM_OK);
    }
    const char *first = test_path("first_two.mp4"), *alone = test_path("alone.mp4");
    assert_int_equal(im_animation_mp4(three, "contact", 2, 5.0, first), IM_OK);
    assert_int_equal(im_animation_mp4(two, "contact", 2, 5.0, alone), IM_OK);
    size_t a_size = 0, b_size = 0;
    uint8_t *a = slurp(first, &a_size), *b = slurp(alone, &b_size);
    assert_true(a && b && a_size == b_size && memcmp(a, b, a_size) == 0);
    free(a);
    free(b);
}

static void test_mp4_or_its_absence(void **state)
{
    (void)state;
    const char *directory = test_path("frames");
    assert_int_equal(im_make_directories(directory), IM_OK);
    im_image image = make_image(21, 17, 9);
    for (int i = 0; i < 3; ++i) {
        char path[4096];
        assert_int_equal(im_frame_path(path, sizeof path, directory, "contact", i), IM_OK);
        assert_int_equal(im_png_write(path, image.rgba, image.width, image.height, 4, 21 * 4, NULL), IM_OK);
    }
    const char *video = test_path("run.mp4");
    int status = im_animation_mp4(directory, "contact", 3, 5.0, video);
    struct stat st;
    if (!im_ffmpeg_available()) {
        assert_int_equal(status, IM_EUNSUPPORTED);
        assert_non_null(strstr(im_last_error(), "ffmpeg not found"));
        assert_int_not_equal(stat(video, &st), 0);
        assert_int_equal(directory_entries(directory), 3); /* the frames are kept */
    } else {
        assert_int_equal(status, IM_OK);
        assert_int_equal(stat(video, &st), 0);
        assert_true(st.st_size > 0);
        assert_mp4_reads_count_frames(directory, &image);
    }
    assert_int_equal(im_animation_mp4(directory, "contact", 0, 5.0, video), IM_EINVAL);
    im_image_release(&image);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ticks),
        cmocka_unit_test(test_tick_labels),
        cmocka_unit_test(test_length_labels),
        cmocka_unit_test(test_small_panel_text_fits),
        cmocka_unit_test(test_colorbar_beside_an_image_under_a_wide_title),
        cmocka_unit_test(test_note_under_the_panels),
        cmocka_unit_test(test_short_colorbar_labels_apart),
        cmocka_unit_test(test_panel_grid_and_colorbar),
        cmocka_unit_test(test_colorbar_extensions),
        cmocka_unit_test(test_tension_colorbar),
        cmocka_unit_test(test_colorbar_beside_a_strip),
        cmocka_unit_test(test_colorbar_right_of_the_scale_text),
        cmocka_unit_test(test_scale_bar_under_its_panel),
        cmocka_unit_test(test_a_scale_bar_per_spacing),
        cmocka_unit_test(test_png_metadata_pdf_svg),
        cmocka_unit_test(test_png_text_utf8_in_itxt),
        cmocka_unit_test(test_bad_figures_refused),
        cmocka_unit_test(test_frame_paths),
        cmocka_unit_test(test_colorbar_labels),
        cmocka_unit_test(test_gif_round_trip),
        cmocka_unit_test(test_gif_quantises),
        cmocka_unit_test(test_gif_options_refused),
        cmocka_unit_test(test_gif_annotated_like_png),
        cmocka_unit_test(test_mp4_or_its_absence),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
