/* The norm that turns a value into a table entry (colormap.h): 256 equal bins over [lo, hi] in the
 * value or its logarithm, the ends clamped, under/over/bad outside. Every other colour test compares
 * the renderer with this function, so it is pinned here against the definition itself. */
#include "support.h"

#include "indentmap/colormap.h"
#include "indentmap/render.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The value at fraction t of the norm's range, in the norm's own scale. */
static double value_at(const im_colormap *c, double t)
{
    return c->logarithmic ? c->lo * pow(c->hi / c->lo, t) : c->lo + t * (c->hi - c->lo);
}

/* The middle of bin k is in bin k, and so are points a quarter bin either side of it. */
static void assert_every_bin_centre(const im_colormap *c)
{
    for (int k = 0; k < 256; ++k)
        for (int quarter = -1; quarter <= 1; ++quarter) {
            double t = (k + 0.5 + 0.25 * quarter) / 256.0;
            int index = im_colormap_index(c, value_at(c, t));
            if (index != k)
                fail_msg("value at t = %.6f (bin %d of [%g, %g]%s) got index %d", t, k, c->lo, c->hi,
                         c->logarithmic ? " log" : "", index);
        }
}

static void test_linear_bins_are_equal_and_complete(void **state)
{
    (void)state;
    im_colormap c = im_colormap_make(IM_COLORMAP_VIRIDIS, -0.37, 0.73);
    assert_every_bin_centre(&c);
    assert_int_equal(im_colormap_index(&c, c.lo), 0);
    assert_int_equal(im_colormap_index(&c, c.hi), 255); /* the top edge belongs to the last bin */
}

static void test_log_bins_are_equal_and_complete(void **state)
{
    (void)state;
    im_colormap c = im_colormap_make(IM_COLORMAP_MAGMA, 1e-3, 4.0);
    c.logarithmic = 1;
    assert_int_equal(im_colormap_check(&c), IM_OK);
    assert_every_bin_centre(&c);
    assert_int_equal(im_colormap_index(&c, c.hi), 255);
}

static void test_outside_the_norm(void **state)
{
    (void)state;
    im_colormap c = im_colormap_make(IM_COLORMAP_GREY, 0.0, 1.0);
    assert_int_equal(im_colormap_index(&c, -1e-12), -1);
    assert_int_equal(im_colormap_index(&c, 1.0 + 1e-12), 256);
    assert_int_equal(im_colormap_index(&c, NAN), -2);
    uint8_t rgb[3];
    im_colormap_rgb(&c, -1.0, rgb);
    assert_memory_equal(rgb, c.under, 3);
    im_colormap_rgb(&c, 2.0, rgb);
    assert_memory_equal(rgb, c.over, 3);
    im_colormap_rgb(&c, NAN, rgb);
    assert_memory_equal(rgb, c.bad, 3);
}

/* The colour of a bin centre is that table entry, for every map. */
static void test_colours_are_table_entries(void **state)
{
    (void)state;
    for (int map = 0; map < IM_COLORMAP_COUNT; ++map) {
        im_colormap c = im_colormap_make((im_colormap_id)map, 0.0, 1.0);
        const uint8_t(*table)[3] = im_colormap_table((im_colormap_id)map);
        for (int k = 0; k < 256; ++k) {
            uint8_t rgb[3];
            im_colormap_rgb(&c, (k + 0.5) / 256.0, rgb);
            assert_memory_equal(rgb, table[k], 3);
        }
    }
}

/* CIELAB (D65) of an 8-bit sRGB colour, from the sRGB standard's transfer curve and matrix. */
static void srgb_to_lab(const uint8_t rgb[3], double lab[3])
{
    double linear[3];
    for (int k = 0; k < 3; ++k) {
        double c = rgb[k] / 255.0;
        linear[k] = c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
    }
    double x = (0.4124 * linear[0] + 0.3576 * linear[1] + 0.1805 * linear[2]) / 0.95047;
    double y = 0.2126 * linear[0] + 0.7152 * linear[1] + 0.0722 * linear[2];
    double z = (0.0193 * linear[0] + 0.1192 * linear[1] + 0.9505 * linear[2]) / 1.08883;
    double f[3] = {x, y, z};
    for (int k = 0; k < 3; ++k)
        f[k] = f[k] > 216.0 / 24389.0 ? cbrt(f[k]) : f[k] * 24389.0 / 27.0 / 116.0 + 16.0 / 116.0;
    lab[0] = 116.0 * f[1] - 16.0;
    lab[1] = 500.0 * (f[0] - f[1]);
    lab[2] = 200.0 * (f[1] - f[2]);
}

/* The tension ramp is ordered: CIELAB lightness never rises from one entry to the next and falls over
 * every four, by more than 50 over the table; every entry is a blue (hue 240 to 285 degrees, chroma
 * over 15) far from the no-contact grey (230); and it is no map a user chooses for the forces. */
static void test_tension_ramp_is_an_ordered_blue(void **state)
{
    (void)state;
    const uint8_t(*table)[3] = im_colormap_table(IM_COLORMAP_TENSION);
    const uint8_t grey[3] = {230, 230, 230};
    double lab[256][3], background[3];
    srgb_to_lab(grey, background);
    for (int k = 0; k < 256; ++k) {
        srgb_to_lab(table[k], lab[k]);
        double hue = atan2(lab[k][2], lab[k][1]) * 180.0 / M_PI + 360.0;
        double distance = sqrt(pow(lab[k][0] - background[0], 2) + pow(lab[k][1], 2) + pow(lab[k][2], 2));
        if (!(hue > 240.0 && hue < 285.0 && hypot(lab[k][1], lab[k][2]) > 15.0 && distance > 20.0))
            fail_msg("entry %d (%d, %d, %d): hue %.1f, chroma %.1f, %.1f from the grey", k, table[k][0], table[k][1],
                     table[k][2], hue, hypot(lab[k][1], lab[k][2]), distance);
        if (k >= 1 && lab[k][0] > lab[k - 1][0])
            fail_msg("lightness rises from entry %d (%.2f) to %d (%.2f)", k - 1, lab[k - 1][0], k, lab[k][0]);
        if (k >= 4 && !(lab[k][0] < lab[k - 4][0]))
            fail_msg("lightness does not fall from entry %d to %d", k - 4, k);
    }
    assert_true(lab[0][0] - lab[255][0] > 50.0);
    im_colormap_id map;
    assert_int_equal(im_colormap_from_name(im_colormap_name(IM_COLORMAP_TENSION), &map), IM_EINVAL);
}

/* ---- one norm over several fields (im_colormap_range_*) ---- */

/* The norm of a range gathered from count fields of 4 values each (one row of 4 patches). */
static im_colormap norm_over(im_colormap_values values, double fields[][4], int count, double vmin, double vmax,
                             int logarithmic)
{
    im_colormap_range range = im_colormap_range_empty(values);
    for (int i = 0; i < count; ++i) {
        const im_field field = {4, 1, 1.0, "", fields[i], ""};
        assert_int_equal(im_colormap_range_add(&range, &field), IM_OK);
    }
    return im_colormap_range_norm(&range, IM_COLORMAP_MAGMA, vmin, vmax, logarithmic);
}

static void assert_norm(const im_colormap *c, double lo, double hi, int logarithmic)
{
    if (c->lo != lo || c->hi != hi || c->logarithmic != logarithmic)
        fail_msg("norm %s [%.17g, %.17g], expected %s [%.17g, %.17g]", c->logarithmic ? "log" : "linear", c->lo,
                 c->hi, logarithmic ? "log" : "linear", lo, hi);
}

/* Two frames share the range of both: forces 0 .. the largest force of either (tension, NaN and Inf left
 * out), a log norm over the two decades below it, in which force 1 at the middle of [0.1, 10] is entry
 * 128; heights the smallest .. the largest finite height of either. */
static void test_frames_share_the_range_of_all_their_values(void **state)
{
    (void)state;
    double forces[2][4] = {{0.0, 2.0, -30.0, NAN}, {10.0, INFINITY, 0.5, 0.0}};
    im_colormap log = norm_over(IM_COLORMAP_FORCES, forces, 2, NAN, NAN, 1);
    assert_norm(&log, 0.01 * 10.0, 10.0, 1);
    assert_int_equal(im_colormap_index(&log, 1.0), 128);
    im_colormap_range gathered = im_colormap_range_empty(IM_COLORMAP_FORCES); /* the forces > 0 it holds */
    for (int i = 0; i < 2; ++i)
        assert_int_equal(im_colormap_range_add(&gathered, &(const im_field){4, 1, 1.0, "", forces[i], ""}), IM_OK);
    assert_true(gathered.lo == 0.5 && gathered.hi == 10.0);
    im_colormap linear = norm_over(IM_COLORMAP_FORCES, forces, 2, NAN, NAN, 0);
    assert_norm(&linear, 0.0, 10.0, 0);
    assert_int_equal(im_colormap_index(&linear, 5.0), 128);
    double heights[2][4] = {{-2.0, 1.0, NAN, 0.0}, {3.0, -INFINITY, 0.5, 2.0}};
    im_colormap drawn = norm_over(IM_COLORMAP_HEIGHTS, heights, 2, NAN, NAN, 0);
    assert_norm(&drawn, -2.0, 3.0, 0);
    double first_only[1][4] = {{-2.0, 1.0, NAN, 0.0}};
    im_colormap one = norm_over(IM_COLORMAP_HEIGHTS, first_only, 1, NAN, NAN, 0);
    assert_norm(&one, -2.0, 1.0, 0);
}

/* ---- a range with outliers cut (im_colormap_range_clipped) ---- */

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The reference percentile: every gathered value (kept as im_colormap_values says, written out here
 * apart from the library's rule) sorted, then numpy.percentile's linear interpolation. */
static double sorted_percentile(im_colormap_values values, im_field *const *fields, int count, double percent,
                                size_t *n)
{
    size_t total = 0;
    for (int i = 0; i < count; ++i)
        total += (size_t)fields[i]->nx * fields[i]->ny;
    double *kept = malloc((total + 1) * sizeof *kept);
    *n = 0;
    for (int i = 0; i < count; ++i)
        for (size_t j = 0; j < (size_t)fields[i]->nx * fields[i]->ny; ++j) {
            const double v = fields[i]->data[j];
            if (values == IM_COLORMAP_HEIGHTS  ? isfinite(v)
                : values == IM_COLORMAP_FORCES ? v > 0 && v < INFINITY
                                               : v < 0 && v > -INFINITY)
                kept[(*n)++] = values == IM_COLORMAP_TENSIONS ? -v : v;
        }
    qsort(kept, *n, sizeof *kept, by_value);
    const double rank = percent / 100.0 * (double)(*n - 1);
    const size_t k = (size_t)floor(rank);
    const double result = *n == 0 ? NAN : k + 1 < *n ? kept[k] + (rank - k) * (kept[k + 1] - kept[k]) : kept[k];
    free(kept);
    return result;
}

/* Fields of size n x 1 filled by a seeded generator: each a different kind of trouble for a selection (ties, a
 * row of zeros, spikes, NaN, ±Inf, sorted and reversed runs). */
static im_field *awkward_field(int n, int kind, unsigned *seed)
{
    im_field *field;
    assert_int_equal(im_field_create(n, 1, 1.0, &field), IM_OK);
    for (int i = 0; i < n; ++i) {
        *seed = *seed * 1664525u + 1013904223u;
        const double u = (*seed >> 8) / 16777216.0; /* [0, 1) */
        const double values[] = {u - 0.5,
                                 floor(4.0 * u) - 1.0,
                                 i < n / 8 ? 0.0 : 1e-5 * sin(0.1 * i) + (u < 0.01 ? 3e-4 : 0.0),
                                 u < 0.05   ? NAN
                                 : u < 0.07 ? INFINITY
                                 : u < 0.09 ? -INFINITY
                                            : u - 0.3,
                                 (double)i,
                                 (double)(n - i),
                                 2.5};
        field->data[i] = values[kind % 7];
    }
    return field;
}

/* The cut range is the sorted values' percentiles exactly (equal to the last bit: the same order statistics,
 * found by selection in the library and by sorting here), for each kind of values, over fields of different
 * sizes together, from 0 % (the smallest .. largest of im_colormap_range_add) to 49.99 %; one value, and
 * none (an empty range), too. */
static void test_clipped_range_is_the_sorted_percentile(void **state)
{
    (void)state;
    unsigned seed = 12345u;
    const double percents[] = {0.0, 0.3, 1.0, 2.5, 10.0, 33.3, 49.99};
    const int sizes[] = {1, 2, 3, 17, 256, 1001};
    for (int kind = 0; kind < 7; ++kind)
        for (size_t s = 0; s < sizeof sizes / sizeof *sizes; ++s) {
            im_field *fields[2] = {awkward_field(sizes[s], kind, &seed),
                                   awkward_field(sizes[s] + 5, kind + 3, &seed)};
            for (im_colormap_values values = IM_COLORMAP_FORCES; values <= IM_COLORMAP_TENSIONS; ++values)
                for (size_t p = 0; p < sizeof percents / sizeof *percents; ++p) {
                    im_colormap_range cut = im_colormap_range_empty(values), added = cut;
                    assert_int_equal(im_colormap_range_clipped(values, fields, 2, percents[p], &cut), IM_OK);
                    size_t n;
                    const double lo = sorted_percentile(values, fields, 2, percents[p], &n),
                                 hi = sorted_percentile(values, fields, 2, 100.0 - percents[p], &n);
                    if (n == 0 ? cut.lo != INFINITY || cut.hi != -INFINITY : cut.lo != lo || cut.hi != hi)
                        fail_msg("kind %d, %d + %d values, kind of values %d, %g %%: [%.17g, %.17g], sorted: [%.17g, "
                                 "%.17g] of %zu",
                                 kind, sizes[s], sizes[s] + 5, (int)values, percents[p], cut.lo, cut.hi, lo, hi, n);
                    for (int i = 0; percents[p] == 0.0 && i < 2; ++i)
                        assert_int_equal(im_colormap_range_add(&added, fields[i]), IM_OK);
                    assert_true(percents[p] > 0.0 || (cut.lo == added.lo && cut.hi == added.hi));
                }
            im_field_free(fields[0]);
            im_field_free(fields[1]);
        }
}

/* A scan's row of dropouts and its spikes (S9): 1 % cut at each end leaves the relief's own range. */
static void test_clipped_range_leaves_out_spikes_and_dropouts(void **state)
{
    (void)state;
    im_field *scan;
    assert_int_equal(im_field_create(100, 100, 1.0, &scan), IM_OK);
    for (int i = 0; i < 100 * 100; ++i)
        scan->data[i] = i < 80 ? 0.0 : 1e-3 + 1e-5 * sin(0.37 * i); /* 0.8 % dropouts */
    for (int i = 5000; i < 5030; ++i)
        scan->data[i] = 0.3; /* spikes */
    im_colormap_range cut;
    assert_int_equal(im_colormap_range_clipped(IM_COLORMAP_HEIGHTS, &scan, 1, 1.0, &cut), IM_OK);
    assert_true(cut.lo > 1e-3 - 1e-5 && cut.hi < 1e-3 + 1e-5);
    assert_true(cut.hi - cut.lo > 1.9e-5);
    im_field_free(scan);
}

/* The tension norm two frames share: 0 .. the largest tension -f of either (forces >= 0, NaN and -Inf left
 * out), as the one frame's im_contact_largest_tension and im_contact_tension_norm give it; [0, 1] and hi
 * not > 0 (no tension bar) where no force is < 0. */
static void test_frames_share_the_largest_tension_of_all_their_forces(void **state)
{
    (void)state;
    double forces[2][4] = {{0.0, -2.0, 30.0, NAN}, {-7.5, -INFINITY, -0.5, 0.0}};
    im_colormap_range tensions = im_colormap_range_empty(IM_COLORMAP_TENSIONS);
    for (int i = 0; i < 2; ++i)
        assert_int_equal(im_colormap_range_add(&tensions, &(const im_field){4, 1, 1.0, "", forces[i], ""}), IM_OK);
    assert_true(tensions.lo == 0.5 && tensions.hi == 7.5);
    im_colormap norm = im_colormap_range_norm(&tensions, IM_COLORMAP_TENSION, NAN, NAN, 0);
    assert_norm(&norm, 0.0, 7.5, 0);
    assert_int_equal(im_colormap_index(&norm, 7.5 / 2), 128);
    assert_true(im_contact_largest_tension(&(const im_field){4, 1, 1.0, "", forces[1], ""}) == 7.5);
    im_colormap single = im_contact_tension_norm(7.5);
    assert_norm(&single, 0.0, 7.5, 0);
    assert_true(single.map == IM_COLORMAP_TENSION && norm.map == IM_COLORMAP_TENSION);
    assert_memory_equal(single.over, norm.over, 3);
    im_colormap_range none = im_colormap_range_empty(IM_COLORMAP_TENSIONS);
    double repulsive[4] = {0.0, 3.0, NAN, INFINITY};
    assert_int_equal(im_colormap_range_add(&none, &(const im_field){4, 1, 1.0, "", repulsive, ""}), IM_OK);
    assert_false(none.hi > 0.0);
    norm = im_colormap_range_norm(&none, IM_COLORMAP_TENSION, NAN, NAN, 0);
    assert_norm(&norm, 0.0, 1.0, 0);
    assert_true(im_contact_largest_tension(&(const im_field){4, 1, 1.0, "", repulsive, ""}) == 0.0);
}

/* The caller's bounds replace the range's: vmax moves the log norm's two decades with it; vmin stays as
 * given, also where it is not below vmax (im_colormap_check refuses that norm, naming it). */
static void test_given_bounds_replace_the_range(void **state)
{
    (void)state;
    double forces[1][4] = {{0.0, 2.0, 4.0, 1.0}};
    im_colormap c = norm_over(IM_COLORMAP_FORCES, forces, 1, NAN, 20.0, 1);
    assert_norm(&c, 0.01 * 20.0, 20.0, 1);
    c = norm_over(IM_COLORMAP_FORCES, forces, 1, 0.5, NAN, 1);
    assert_norm(&c, 0.5, 4.0, 1);
    c = norm_over(IM_COLORMAP_FORCES, forces, 1, 0.5, 0.5, 0);
    assert_norm(&c, 0.5, 0.5, 0);
    assert_int_equal(im_colormap_check(&c), IM_EINVAL);
    c = norm_over(IM_COLORMAP_FORCES, forces, 1, NAN, -1.0, 1); /* no decades below a top <= 0 */
    assert_norm(&c, 0.0, -1.0, 1);
    assert_int_equal(im_colormap_check(&c), IM_EINVAL);
}

/* Where the fields give no range, the defaults: no force > 0 (all zero, all tension, all NaN) [0, 1];
 * heights of one value v [v - 1, v + 1]; no finite height [-1, 1]. */
static void test_a_range_without_values_takes_the_defaults(void **state)
{
    (void)state;
    double no_contact[2][4] = {{0.0, 0.0, 0.0, 0.0}, {-1.0, NAN, 0.0, -INFINITY}};
    im_colormap c = norm_over(IM_COLORMAP_FORCES, no_contact, 2, NAN, NAN, 1);
    assert_norm(&c, 0.01, 1.0, 1);
    c = norm_over(IM_COLORMAP_FORCES, no_contact, 0, NAN, NAN, 0);
    assert_norm(&c, 0.0, 1.0, 0);
    double flat[2][4] = {{5.0, 5.0, NAN, 5.0}, {5.0, INFINITY, 5.0, 5.0}};
    c = norm_over(IM_COLORMAP_HEIGHTS, flat, 2, NAN, NAN, 0);
    assert_norm(&c, 4.0, 6.0, 0);
    double none[1][4] = {{NAN, NAN, INFINITY, NAN}};
    c = norm_over(IM_COLORMAP_HEIGHTS, none, 1, NAN, NAN, 0);
    assert_norm(&c, -1.0, 1.0, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linear_bins_are_equal_and_complete),
        cmocka_unit_test(test_log_bins_are_equal_and_complete),
        cmocka_unit_test(test_outside_the_norm),
        cmocka_unit_test(test_colours_are_table_entries),
        cmocka_unit_test(test_tension_ramp_is_an_ordered_blue),
        cmocka_unit_test(test_frames_share_the_range_of_all_their_values),
        cmocka_unit_test(test_clipped_range_is_the_sorted_percentile),
        cmocka_unit_test(test_clipped_range_leaves_out_spikes_and_dropouts),
        cmocka_unit_test(test_frames_share_the_largest_tension_of_all_their_forces),
        cmocka_unit_test(test_given_bounds_replace_the_range),
        cmocka_unit_test(test_a_range_without_values_takes_the_defaults),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
