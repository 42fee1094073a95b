/* Layouts of two formats as other programs read and write them (issue 25): .gsf lengths in base SI
 * units, which Gwyddion's reader expects (it drops prefixes); the GSF specification's defaults for
 * absent XReal, YReal and ZUnits; .npy arrays indexed [x, y], as SurfaceTopography's heights() are. */
#include "support.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A field nx x ny of spacing delta in unit whose heights vary along x and y differently. */
static im_field *ramp_field(int nx, int ny, double delta, const char *unit)
{
    im_field *f = NULL;
    assert_int_equal(im_field_create(nx, ny, delta, &f), IM_OK);
    snprintf(f->unit, sizeof f->unit, "%s", unit);
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix)
            f->data[(size_t)iy * nx + ix] = 0.001 * ix - 0.0003 * iy + 0.01 * sin(0.7 * ix * iy);
    return f;
}

/* The first size - 1 bytes of a file, terminated (NUL bytes of a .gsf end its header). */
static const char *file_head(const char *path, char *head, size_t size)
{
    FILE *in = fopen(path, "rb");
    assert_non_null(in);
    size_t got = fread(head, 1, size - 1, in);
    fclose(in);
    head[got] = '\0';
    return head;
}

/* The number after "KEY = " in a .gsf header. */
static double header_number(const char *head, const char *key)
{
    char pattern[32];
    snprintf(pattern, sizeof pattern, "\n%s = ", key);
    const char *at = strstr(head, pattern);
    assert_non_null(at);
    return strtod(at + strlen(pattern), NULL);
}

/* D11: a field in µm is written in metres (XYUnits = m, ZUnits = m, XReal = nx delta 1e-6) and reads
 * back in metres, equal to the µm field times 1e-6 to float32's rounding. */
static void gsf_is_written_in_metres(void **state)
{
    (void)state;
    im_field *f = ramp_field(96, 64, 0.05, "um"), *g = NULL;
    const char *path = test_path("um.gsf");
    assert_int_equal(im_gsf_write(path, f), IM_OK);
    char head[256];
    file_head(path, head, sizeof head);
    assert_close(header_number(head, "XReal"), 4.8e-6, 4.8e-6 * 1e-15);
    assert_close(header_number(head, "YReal"), 3.2e-6, 3.2e-6 * 1e-15);
    assert_non_null(strstr(head, "\nXYUnits = m\nZUnits = m\n"));
    assert_int_equal(im_gsf_read(path, &g), IM_OK);
    assert_string_equal(g->unit, "m");
    assert_close(g->delta, 5e-8, 5e-8 * 1e-15);
    for (size_t i = 0; i < im_field_count(f); ++i)
        assert_close(g->data[i], f->data[i] * 1e-6, fabs(f->data[i]) * 1e-6 * 6e-8);
    im_field_free(f);
    im_field_free(g);
}

/* A field without a unit is written without units, its numbers as they are. */
static void gsf_without_unit_states_none(void **state)
{
    (void)state;
    im_field *f = ramp_field(9, 3, 0.25, ""), *g = NULL;
    const char *path = test_path("plain.gsf");
    assert_int_equal(im_gsf_write(path, f), IM_OK);
    char head[256];
    assert_null(strstr(file_head(path, head, sizeof head), "Units"));
    assert_int_equal(im_gsf_read(path, &g), IM_OK);
    assert_string_equal(g->unit, "");
    assert_close(g->delta, 0.25, 1e-16);
    for (size_t i = 0; i < im_field_count(f); ++i)
        assert_true(g->data[i] == (double)(float)f->data[i]);
    im_field_free(f);
    im_field_free(g);
}

/* A unit that is not a length cannot be written in metres: refused, nothing written. */
static void gsf_refuses_a_unit_that_is_not_a_length(void **state)
{
    (void)state;
    im_field *f = ramp_field(4, 4, 1.0, "furlong");
    const char *path = test_path("furlong.gsf");
    assert_int_equal(im_gsf_write(path, f), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "unit 'furlong' is not a length unit"));
    assert_int_equal(access(path, F_OK), -1);
    im_field_free(f);
}

/* Gwyddion's reader, run by indentmap-gwyddion-read, sees the extents written here in metres: its
 * "field" line gives XRES YRES XREAL YREAL XYUNIT ZUNIT. */
static void gwyddion_reads_the_written_extent(void **state)
{
    (void)state;
    const char *reader = im_gwyddion_reader();
    if (!reader)
        skip();
    im_field *f = ramp_field(96, 64, 0.05, "\u00b5m");
    const char *path = test_path("for_gwyddion.gsf");
    assert_int_equal(im_gsf_write(path, f), IM_OK);
    char command[8400], line[512] = "";
    snprintf(command, sizeof command, "'%s' '%s'", reader, path);
    FILE *out = popen(command, "r");
    assert_non_null(out);
    while (strncmp(line, "field ", 6) != 0 && fgets(line, sizeof line, out))
        ;
    pclose(out);
    int index, nx, ny;
    double xreal, yreal;
    char xy_unit[16], z_unit[16];
    assert_int_equal(sscanf(line, "field %d %d %d %lf %lf %15s %15s", &index, &nx, &ny, &xreal, &yreal, xy_unit,
                            z_unit), 7);
    assert_int_equal(nx, 96);
    assert_int_equal(ny, 64);
    assert_close(xreal, 4.8e-6, 4.8e-6 * 1e-15);
    assert_close(yreal, 3.2e-6, 3.2e-6 * 1e-15);
    assert_string_equal(xy_unit, "m");
    assert_string_equal(z_unit, "m");
    im_field_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gsf_is_written_in_metres),
        cmocka_unit_test(gsf_without_unit_states_none),
        cmocka_unit_test(gsf_refuses_a_unit_that_is_not_a_length),
        cmocka_unit_test(gwyddion_reads_the_written_extent),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
