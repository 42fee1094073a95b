/* The norm that turns a value into a table entry (colormap.h): 256 equal bins over [lo, hi] in the
 * value or its logarithm, the ends clamped, under/over/bad outside. Every other colour test compares
 * the renderer with this function, so it is pinned here against the definition itself. */
#include "support.h"

#include "indentmap/colormap.h"
#include "indentmap/status.h"

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linear_bins_are_equal_and_complete),
        cmocka_unit_test(test_log_bins_are_equal_and_complete),
        cmocka_unit_test(test_outside_the_norm),
        cmocka_unit_test(test_colours_are_table_entries),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
