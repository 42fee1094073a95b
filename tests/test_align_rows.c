/* Scan-line alignment (im_surface_align_rows): row offsets and tilts removed, the surface's mean kept,
 * a spike not moving a median-aligned row. */
#include "support.h"

#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>

/* z = profile(x) + offset(y) + tilt(y) x: what a drifting feedback makes of one profile. */
static im_field *streaky(int nx, int ny, double tilt)
{
    im_field *f = NULL;
    assert_int_equal(im_field_create(nx, ny, 1.0, &f), IM_OK);
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix)
            f->data[(size_t)iy * nx + ix] = sin(0.3 * ix) + 0.1 * ix + 5.0 * cos(1.7 * iy) + tilt * sin(iy) * ix;
    return f;
}

static double mean(const im_field *f)
{
    double sum = 0.0;
    for (size_t i = 0; i < im_field_count(f); ++i)
        sum += f->data[i];
    return sum / (double)im_field_count(f);
}

/* After alignment every row equals row 0: the offsets are gone, the profile along x is kept. */
static double largest_row_difference(const im_field *f)
{
    double largest = 0.0;
    for (int iy = 1; iy < f->ny; ++iy)
        for (int ix = 0; ix < f->nx; ++ix)
            largest = fmax(largest, fabs(f->data[(size_t)iy * f->nx + ix] - f->data[ix]));
    return largest;
}

static void offsets_are_removed_and_the_mean_kept(void **state)
{
    (void)state;
    enum im_row_alignment methods[] = {IM_ALIGN_MEDIAN, IM_ALIGN_MEAN};
    for (int m = 0; m < 2; ++m) {
        im_field *f = streaky(33, 20, 0.0);
        double before = mean(f), offset_spread = largest_row_difference(f);
        assert_true(offset_spread > 5.0);
        assert_int_equal(im_surface_align_rows(f, methods[m]), IM_OK);
        assert_true(largest_row_difference(f) < 1e-13);
        assert_close(mean(f), before, 1e-12);
        assert_close(f->data[5] - f->data[0], sin(1.5) + 0.5, 1e-13); /* the profile along x is kept */
        im_field_free(f);
    }
}

static void line_alignment_removes_tilts(void **state)
{
    (void)state;
    im_field *f = streaky(40, 16, 0.02);
    assert_int_equal(im_surface_align_rows(f, IM_ALIGN_MEDIAN), IM_OK);
    assert_true(largest_row_difference(f) > 0.1); /* an offset alone does not take a tilt out */
    im_field_free(f);
    f = streaky(40, 16, 0.02);
    assert_int_equal(im_surface_align_rows(f, IM_ALIGN_LINE), IM_OK);
    assert_true(largest_row_difference(f) < 1e-12);
    im_field_free(f);
}

/* A spike (a particle, a glitch) moves a row's mean by spike / nx, its median by one order statistic
 * at most (here about 0.2: the row's range over its 31 points). */
static void a_spike_does_not_move_a_median_aligned_row(void **state)
{
    (void)state;
    im_field *median = streaky(31, 8, 0.0), *mean_aligned = streaky(31, 8, 0.0);
    median->data[3 * 31 + 10] += 1000.0;
    mean_aligned->data[3 * 31 + 10] += 1000.0;
    assert_int_equal(im_surface_align_rows(median, IM_ALIGN_MEDIAN), IM_OK);
    assert_int_equal(im_surface_align_rows(mean_aligned, IM_ALIGN_MEAN), IM_OK);
    double median_shift = median->data[3 * 31 + 11] - median->data[11];
    double mean_shift = mean_aligned->data[3 * 31 + 11] - mean_aligned->data[11];
    assert_true(fabs(median_shift) < 0.25);
    assert_true(fabs(mean_shift) > 30.0); /* 1000 / 31 */
    im_field_free(median);
    im_field_free(mean_aligned);
}

static void refusals(void **state)
{
    (void)state;
    im_field *f = streaky(8, 8, 0.0);
    assert_int_equal(im_surface_align_rows(f, (enum im_row_alignment)7), IM_EINVAL);
    f->data[9] = NAN;
    assert_int_equal(im_surface_align_rows(f, IM_ALIGN_MEDIAN), IM_ENUMERIC);
    assert_int_equal(im_surface_align_rows(f, IM_ALIGN_NONE), IM_OK);
    im_field_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(offsets_are_removed_and_the_mean_kept),
        cmocka_unit_test(line_alignment_removes_tilts),
        cmocka_unit_test(a_spike_does_not_move_a_median_aligned_row),
        cmocka_unit_test(refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
