/* Square pixels (issue 25): im_surface_resample_square against functions it must reproduce and the
 * error bound of linear interpolation; the readers' tolerance for spacings that differ by rounding;
 * resample_square on files, among them a real instrument file with pixels 2.46 times taller than
 * wide. */
#include "support.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef double (*surface_function)(double x, double y);

/* f sampled on nx x ny points spaced dx along x and dy along y. */
static im_field *sampled(surface_function f, int nx, int ny, double dx, double dy)
{
    im_field *field = NULL;
    assert_int_equal(im_field_create(nx, ny, 1.0, &field), IM_OK);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            field->data[(size_t)j * nx + i] = f(i * dx, j * dy);
    return field;
}

static im_field *resampled(const im_field *field, double dx, double dy)
{
    im_field *out = NULL;
    if (im_surface_resample_square(field, dx, dy, &out) != IM_OK)
        fail_msg("resample: %s", im_last_error());
    return out;
}

/* The largest |resampled - f| over the nodes of the square grid, each at (i delta, j delta). */
static double largest_error(const im_field *square, surface_function f)
{
    double largest = 0.0;
    for (int j = 0; j < square->ny; ++j)
        for (int i = 0; i < square->nx; ++i)
            largest = fmax(largest,
                           fabs(square->data[(size_t)j * square->nx + i] - f(i * square->delta, j * square->delta)));
    return largest;
}

static double plane(double x, double y) { return 0.75 - 1.25 * x + 2.5 * y; }
static double bilinear(double x, double y) { return (1.0 + 0.5 * x) * (2.0 - 0.25 * y) + 3.0 * x * y; }

/* Both orientations (y coarser, then x coarser), with ratios 7/3 and 2.5 so that nodes fall
 * between the old points at every fraction; the grid: the finer axis keeps its points, the coarser
 * gets floor((n - 1) ratio) + 1 nodes, none beyond the old extent. */
static void planes_and_bilinear_functions_are_reproduced(void **state)
{
    (void)state;
    static const struct {
        int nx, ny;
        double dx, dy;
        int square_nx, square_ny;
    } grids[] = {{9, 7, 0.3, 0.7, 9, 15}, {6, 11, 2.5e-6, 1e-6, 13, 11}, {5, 5, 1.0, 1.0, 5, 5}};
    surface_function functions[] = {plane, bilinear};
    double worst = 0.0;
    for (size_t g = 0; g < sizeof grids / sizeof *grids; ++g) {
        for (int k = 0; k < 2; ++k) {
            im_field *field = sampled(functions[k], grids[g].nx, grids[g].ny, grids[g].dx, grids[g].dy);
            snprintf(field->unit, sizeof field->unit, "m");
            im_field *square = resampled(field, grids[g].dx, grids[g].dy);
            assert_int_equal(square->nx, grids[g].square_nx);
            assert_int_equal(square->ny, grids[g].square_ny);
            assert_true(square->delta == fmin(grids[g].dx, grids[g].dy));
            assert_string_equal(square->unit, "m");
            double error = largest_error(square, functions[k]);
            if (!(error <= 4e-13))
                fail_msg("grid %zu, function %d: largest error %g", g, k, error);
            worst = fmax(worst, error);
            im_field_free(square);
            im_field_free(field);
        }
    }
    print_message("planes and bilinear functions: largest error %.3g (values of order 10)\n", worst);
}

static const double WAVE_X = 0.37, WAVE_Y = 0.61, AMPLITUDE = 1.5;
static double sine(double x, double y) { return AMPLITUDE * sin(WAVE_X * x) * cos(WAVE_Y * y + 0.3); }

/* Linear interpolation over a step h is off by at most (h^2 / 8) max |f''|; along the finer axis the
 * nodes are the old points, so the whole error is the coarser axis's: h = dy, f_yy = -k_y^2 f. The
 * nodes fall at fractions 0, 0.4, 0.8, 0.2, 0.6 of a step (ratio 2.5), where the error reaches
 * w (1 - w) / 2 = 0.96 of the bound's h^2 / 8: the measured error must come near it, not only under. */
static void a_sine_is_within_the_interpolation_bound(void **state)
{
    (void)state;
    const double dx = 0.4, dy = 1.0;
    im_field *field = sampled(sine, 200, 120, dx, dy);
    im_field *square = resampled(field, dx, dy);
    assert_int_equal(square->ny, 119 * 5 / 2 + 1);
    double bound = dy * dy / 8.0 * AMPLITUDE * WAVE_Y * WAVE_Y, error = largest_error(square, sine);
    print_message("sine: largest error %.6g, bound (h^2/8) max|f_yy| %.6g: %.3f of it\n", error, bound,
                  error / bound);
    assert_true(error <= bound);
    assert_true(error >= 0.9 * bound);
    im_field_free(square);
    im_field_free(field);
}

/* A missing point spreads to the nodes whose blend it enters (|y - y_missing| < dy on its column)
 * and to no other. */
static void a_missing_point_spreads_to_the_nodes_it_touches(void **state)
{
    (void)state;
    const double dx = 1.0, dy = 2.5;
    im_field *field = sampled(plane, 6, 8, dx, dy);
    const int column = 3, row = 4;
    field->data[row * 6 + column] = NAN;
    im_field *square = resampled(field, dx, dy);
    int missing = 0;
    for (int j = 0; j < square->ny; ++j)
        for (int i = 0; i < square->nx; ++i) {
            int touches = i == column && fabs(j - 2.5 * row) < 2.5;
            double value = square->data[(size_t)j * square->nx + i];
            if (touches != (isnan(value) != 0))
                fail_msg("node (%d, %d): %g", i, j, value);
            missing += touches;
        }
    assert_int_equal(missing, 5); /* y = 8 to 12 in units of dx: nodes 8, 9, 10, 11, 12 */
    im_field_free(square);
    im_field_free(field);
}

static void impossible_grids_are_refused(void **state)
{
    (void)state;
    im_field *field = sampled(plane, 4, 3, 1.0, 1.0), *out = NULL;
    assert_int_equal(im_surface_resample_square(field, 1.0, 1e6, &out), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "4 x 3 pixels of 1 x 1e+06 onto square pixels of 1: 4 x 2000001 nodes, "
                                            "more than 65536"));
    assert_null(out);
    assert_int_equal(im_surface_resample_square(field, 0.0, 1.0, &out), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "spacings 0 and 1: expected finite values > 0"));
    assert_int_equal(im_surface_resample_square(field, 1.0, INFINITY, &out), IM_EINVAL);
    im_field_free(field);
}

/* A Gwyddion text export of 4 x 4 heights 0..15, Width 4 µm and Height 4 (1 + stretch) µm. */
/* Both extents printed to 17 digits, which leave the spacings open by less than 2^-16: the tolerance is
 * IM_SQUARE_PIXEL_TOLERANCE itself. */
static const char *write_export(const char *name, double stretch)
{
    char text[512];
    snprintf(text, sizeof text,
             "# Width: 4.0000000000000000 um\n# Height: %.16f um\n0 1 2 3\n4 5 6 7\n8 9 10 11\n12 13 14 15\n",
             4.0 * (1.0 + stretch));
    test_write_bytes(test_path(name), text, strlen(text));
    return test_path(name);
}

/* Within IM_SQUARE_PIXEL_TOLERANCE the pixels are square: the mean spacing, the difference recorded;
 * just beyond it they are refused with both spacings, the difference, the tolerance and the option. */
static void spacings_within_rounding_are_square(void **state)
{
    (void)state;
    const double within = 0.9 * IM_SQUARE_PIXEL_TOLERANCE, beyond = 1.1 * IM_SQUARE_PIXEL_TOLERANCE;
    im_field *f = NULL;
    im_surface_read_info info;
    assert_int_equal(im_surface_read_with(write_export("within.txt", within), NULL, &f, &info), IM_OK);
    assert_close(f->delta, 1.0 + within / 2, 1e-15);
    assert_close(info.spacing_difference, within / (1.0 + within / 2), 1e-15);
    assert_string_equal(info.resampled, "");
    assert_int_equal(f->nx * f->ny, 16);
    im_field_free(f);
    assert_int_equal(im_surface_read_with(write_export("square.txt", 0.0), NULL, &f, &info), IM_OK);
    assert_true(f->delta == 1.0 && info.spacing_difference == 0.0);
    im_field_free(f);
    const char *path = write_export("beyond.txt", beyond);
    assert_int_equal(im_surface_read_with(path, NULL, &f, &info), IM_EFORMAT);
    assert_null(f);
    const char *message = im_last_error();
    static const char *const phrases[] = {"beyond.txt: Width / columns and Height / rows: non-square pixels",
                                          "x spacing 1 and y spacing 1.00001678 um",
                                          "differ by 1.68e-05 of their mean",
                                          "beyond the 1.53e-05 (2^-16) that rounding explains", "--resample-square"};
    for (size_t i = 0; i < sizeof phrases / sizeof *phrases; ++i)
        if (!strstr(message, phrases[i]))
            fail_msg("message '%s' lacks '%s'", message, phrases[i]);
}

/* A Gwyddion text export of columns x rows points whose header prints the extents width and height. */
static const char *write_printed_export(const char *name, const char *width, const char *height, int columns,
                                        int rows)
{
    size_t size = 128 + (size_t)columns * rows * 4;
    char *text = malloc(size);
    assert_non_null(text);
    int used = snprintf(text, size, "# Width: %s\n# Height: %s\n# Value units: m\n", width, height);
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i)
            used += snprintf(text + used, size - (size_t)used, "%d%c", (i * 7 + j * 3) % 10,
                             i + 1 < columns ? ' ' : '\n');
    test_write_bytes(test_path(name), text, (size_t)used);
    free(text);
    return test_path(name);
}

/* A header that prints its extents with few digits leaves their ratio open by half a unit of each last
 * digit: al3d-1.al3d exported by Gwyddion as text said "Width: 87.6 µm" and "Height: 129.7 µm" for 200 x
 * 296 points (spacings 0.438 and 0.438176 µm, 4.0e-4 apart; its .gsf export reads square), refused at
 * 2^-16. The tolerance is 0.05 / 87.6 + 0.05 / 129.7 there; the same extents printed to more digits, a
 * hand-written 5% difference and the same file with --delta are held to 2^-16 or the limit. */
static void printed_digits_widen_the_tolerance(void **state)
{
    (void)state;
    im_field *f = NULL;
    im_surface_read_info info;
    const char *al3d = write_printed_export("al3d.txt", "87.6 \u00b5m", "129.7 \u00b5m", 200, 296);
    if (im_surface_read_with(al3d, NULL, &f, &info) != IM_OK)
        fail_msg("%s", im_last_error());
    const double dx = 87.6 / 200, dy = 129.7 / 296, open = 0.05 / 87.6 + 0.05 / 129.7;
    assert_close(info.square_tolerance, open, 1e-12);
    assert_close(info.spacing_difference, fabs(dx - dy) / (0.5 * (dx + dy)), 1e-12);
    assert_true(info.spacing_difference > IM_SQUARE_PIXEL_TOLERANCE && info.spacing_difference < open);
    assert_close(f->delta, 0.5 * (dx + dy), 1e-15);
    assert_string_equal(info.resampled, "");
    im_field_free(f);
    const char *exponent = write_printed_export("exponent.txt", "8.76e-5 m", "1.297e-4 m", 200, 296);
    assert_int_equal(im_surface_read_with(exponent, NULL, &f, &info), IM_OK);
    assert_close(info.square_tolerance, open, 1e-12);
    im_field_free(f);
    const char *digits = write_printed_export("digits.txt", "87.600000 \u00b5m", "129.700000 \u00b5m", 200, 296);
    assert_int_equal(im_surface_read_with(digits, NULL, &f, &info), IM_EFORMAT);
    assert_non_null(strstr(im_last_error(), "beyond the 1.53e-05 (2^-16) that rounding explains"));
    const char *hand = write_printed_export("hand.txt", "4 um", "4.2 um", 4, 4);
    assert_int_equal(im_surface_read_with(hand, NULL, &f, &info), IM_EFORMAT);
    assert_non_null(strstr(im_last_error(), "differ by 0.0488 of their mean, beyond the 0.002 (the extents' printed "
                                            "digits) that rounding explains"));
    im_surface_read_options exact = {.set = {.delta_x = 0.438, .delta_y = 0.438175676}};
    assert_int_equal(im_surface_read_with(al3d, &exact, &f, &info), IM_EFORMAT);
    assert_non_null(strstr(im_last_error(), "--delta: non-square pixels"));
}

/* Width 3 µm, Height 6 µm on 3 x 3 points: pixels 1 x 2 µm, resampled onto 3 x 5 of 1 µm (rows 1
 * and 3 the means of their neighbours); the missing point is filled on the stored grid first, and
 * the spacings are recorded in the unit read into (here m). */
static void resample_square_reads_rectangular_pixels(void **state)
{
    (void)state;
    const char *text = "# Width: 3 um\n# Height: 6 um\n1 2 3\n4 nan 6\n7 8 9\n";
    test_write_bytes(test_path("rect.txt"), text, strlen(text));
    im_field *f = NULL;
    im_surface_read_info info;
    im_surface_read_options options = {.fill = 1, .express_in = "m"};
    assert_int_equal(im_surface_read_with(test_path("rect.txt"), &options, &f, &info), IM_EFORMAT);
    options.resample_square = 1;
    assert_int_equal(im_surface_read_with(test_path("rect.txt"), &options, &f, &info), IM_OK);
    assert_int_equal(f->nx, 3);
    assert_int_equal(f->ny, 5);
    assert_close(f->delta, 1e-6, 1e-21);
    assert_string_equal(f->unit, "m");
    const double expected[15] = {1, 2, 3, 2.5, 3.5, 4.5, 4, 5, 6, 5.5, 6.5, 7.5, 7, 8, 9};
    for (int i = 0; i < 15; ++i)
        assert_close(f->data[i], expected[i] * 1e-6, 1e-21); /* the filled point: (2 + 4 + 6 + 8) / 4 */
    assert_string_equal(info.resampled, "bilinear");
    assert_true(info.resampled_delta == f->delta);
    assert_int_equal(info.stored_nx, 3);
    assert_int_equal(info.stored_ny, 3);
    assert_int_equal(info.filled, 1);
    assert_close(info.used.delta_x, 1e-6, 1e-21);
    assert_close(info.used.delta_y, 2e-6, 1e-21);
    assert_string_equal(info.used.lateral, "m");
    assert_close(info.spacing_difference, 2.0 / 3.0, 1e-15);
    im_field_free(f);
}

/* x3p-2.x3p (SurfaceTopography's test data, MIT): 650 x 650 points of 1.2765651e-07 x 3.14582114e-07 m.
 * Refused as it is; resampled onto 650 x 1600 of 1.2765651e-07 m, the last node within the stored
 * extent, each node the linear blend of the stored rows around it. */
static void an_instrument_file_with_tall_pixels(void **state)
{
    (void)state;
    const char *source = getenv("IM_SOURCE_DIR");
    char path[4096];
    struct stat folder;
    snprintf(path, sizeof path, "%s/../shared/test-data/surfaces", source ? source : ".");
    if (!source || stat(path, &folder) != 0) {
        print_message("%s: absent, skipped\n", path);
        skip();
    }
    snprintf(path + strlen(path), sizeof path - strlen(path), "/x3p-2.x3p");
    const double dx = 1.27656509837346e-007, dy = 3.14582113527746e-007; /* main.xml's Increments */
    im_field *stored = NULL, *square = NULL;
    im_surface_read_options options = {0};
    assert_int_equal(im_surface_read_with(path, &options, &square, NULL), IM_EFORMAT);
    assert_non_null(
        strstr(im_last_error(), "x spacing 1.2765651e-07 and y spacing 3.14582114e-07 m differ by 0.845"));
    options.resample_square = 1;
    im_surface_read_info info;
    if (im_surface_read_with(path, &options, &square, &info) != IM_OK)
        fail_msg("%s", im_last_error());
    assert_int_equal(square->nx, 650);
    assert_int_equal(square->ny, 1600);
    assert_true(square->delta == dx);
    assert_string_equal(square->unit, "m");
    assert_true(1599 * dx <= 649 * dy);
    assert_int_equal(info.stored_nx, 650);
    assert_int_equal(info.stored_ny, 650);
    assert_string_equal(info.resampled, "bilinear");
    options = (im_surface_read_options){.set = {.delta_x = 1.0}}; /* the stored values, on a square grid */
    assert_int_equal(im_surface_read_with(path, &options, &stored, NULL), IM_OK);
    double largest = 0.0, worst = 0.0;
    for (int j = 0; j < square->ny; ++j) {
        double at = j * (dx / dy);
        int row = (int)at < 649 ? (int)at : 648;
        double w = at - row;
        for (int i = 0; i < 650; ++i) {
            double a = stored->data[row * 650 + i], b = stored->data[(row + 1) * 650 + i];
            double expected = w == 0.0 ? a : (1.0 - w) * a + w * b;
            largest = fmax(largest, fabs(a));
            worst = fmax(worst, fabs(square->data[(size_t)j * 650 + i] - expected));
        }
    }
    assert_true(worst <= 1e-15 * largest);
    im_field_free(stored);
    im_field_free(square);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(planes_and_bilinear_functions_are_reproduced),
        cmocka_unit_test(a_sine_is_within_the_interpolation_bound),
        cmocka_unit_test(a_missing_point_spreads_to_the_nodes_it_touches),
        cmocka_unit_test(impossible_grids_are_refused),
        cmocka_unit_test(spacings_within_rounding_are_square),
        cmocka_unit_test(printed_digits_widen_the_tolerance),
        cmocka_unit_test(resample_square_reads_rectangular_pixels),
        cmocka_unit_test(an_instrument_file_with_tall_pixels),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
