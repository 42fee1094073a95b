/* Layouts of two formats as other programs read and write them (issue 25): .gsf lengths in base SI
 * units, which Gwyddion's reader expects (it drops prefixes); the GSF specification's defaults for
 * absent XReal, YReal and ZUnits; .npy arrays indexed [x, y], as SurfaceTopography's heights() are. */
#include "support.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/scene.h"
#include "indentmap/status.h"
#include "scene/contents.h"

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

/* Gwyddion's reading of path, run by indentmap-gwyddion-read: the extents and units of its "field"
 * line (XRES YRES XREAL YREAL XYUNIT ZUNIT). 0 when this build has no such program. */
static int gwyddion_extents(const char *path, double *xreal, double *yreal, char xy_unit[16], char z_unit[16])
{
    const char *reader = im_gwyddion_reader();
    if (!reader)
        return 0;
    char command[8400], line[512] = "";
    snprintf(command, sizeof command, "'%s' '%s'", reader, path);
    FILE *out = popen(command, "r");
    assert_non_null(out);
    while (strncmp(line, "field ", 6) != 0 && fgets(line, sizeof line, out))
        ;
    pclose(out);
    int index, nx, ny;
    assert_int_equal(
        sscanf(line, "field %d %d %d %lf %lf %15s %15s", &index, &nx, &ny, xreal, yreal, xy_unit, z_unit), 7);
    return 1;
}

/* Gwyddion's reader sees the extents written here in metres. */
static void gwyddion_reads_the_written_extent(void **state)
{
    (void)state;
    im_field *f = ramp_field(96, 64, 0.05, "\u00b5m");
    const char *path = test_path("for_gwyddion.gsf");
    assert_int_equal(im_gsf_write(path, f), IM_OK);
    im_field_free(f);
    double xreal, yreal;
    char xy_unit[16], z_unit[16];
    if (!gwyddion_extents(path, &xreal, &yreal, xy_unit, z_unit))
        skip();
    assert_close(xreal, 4.8e-6, 4.8e-6 * 1e-15);
    assert_close(yreal, 3.2e-6, 3.2e-6 * 1e-15);
    assert_string_equal(xy_unit, "m");
    assert_string_equal(z_unit, "m");
}

/* A .gsf of nx x ny values i * 1e-3 with the given header lines after the magic line. */
static const char *write_gsf(const char *name, const char *lines, int nx, int ny)
{
    const char *path = test_path(name);
    FILE *out = fopen(path, "wb");
    assert_non_null(out);
    int length = fprintf(out, "Gwyddion Simple Field 1.0\n%s", lines);
    for (int i = length % 4; i < 4; ++i)
        fputc('\0', out);
    for (int i = 0; i < nx * ny; ++i) {
        float value = (float)(i * 1e-3);
        fwrite(&value, sizeof value, 1, out);
    }
    fclose(out);
    return path;
}

static void expect_read_refused(const char *path, const im_surface_read_options *options, const char *phrase)
{
    im_field *f = NULL;
    assert_int_equal(im_surface_read_with(path, options, &f, NULL), IM_EFORMAT);
    assert_null(f);
    if (!strstr(im_last_error(), phrase))
        fail_msg("message '%s' lacks '%s'", im_last_error(), phrase);
}

/* D12: without XReal and YReal the extents are 1.0 each, in XYUnits: a 4 x 4 grid has a spacing of
 * 0.25 m (it was 1 m, "none stated"), as Gwyddion reads it. */
static void gsf_extents_default_to_one(void **state)
{
    (void)state;
    const char *path = write_gsf("no_extents.gsf", "XRes = 4\nYRes = 4\nXYUnits = m\nZUnits = m\n", 4, 4);
    im_field *f = NULL;
    im_surface_read_info info;
    assert_int_equal(im_surface_read_with(path, NULL, &f, &info), IM_OK);
    assert_true(f->delta == 0.25);
    assert_string_equal(f->unit, "m");
    assert_true(info.file.delta_x == 0.25 && info.file.delta_y == 0.25);
    im_field_free(f);
    double xreal, yreal;
    char xy_unit[16], z_unit[16];
    if (gwyddion_extents(path, &xreal, &yreal, xy_unit, z_unit))
        assert_true(xreal == 1.0 && yreal == 1.0);
}

/* Each absent extent is 1.0 on its own: XReal alone on a 4 x 2 grid gives pixels 1e-6 x 0.5 m, and
 * no extents on a 4 x 2 grid pixels 0.25 x 0.5; both refused as non-square, naming the default;
 * --delta sets square ones. */
static void gsf_absent_extents_are_named(void **state)
{
    (void)state;
    const char *x_only = write_gsf("x_only.gsf", "XRes = 4\nYRes = 2\nXReal = 4e-6\nXYUnits = m\nZUnits = m\n", 4, 2);
    expect_read_refused(x_only, NULL,
                        "(no YReal: 1.0, the GSF default): non-square pixels, x spacing 1e-06 and y "
                        "spacing 0.5 m");
    const char *bare = write_gsf("bare_4x2.gsf", "XRes = 4\nYRes = 2\n", 4, 2);
    expect_read_refused(bare, NULL,
                        "(no XReal, no YReal: 1.0 each, the GSF default): non-square pixels, x spacing "
                        "0.25 and y spacing 0.5 differ");
    im_surface_read_options options = {.set = {.delta_x = 2.0}};
    im_field *f = NULL;
    assert_int_equal(im_surface_read_with(bare, &options, &f, NULL), IM_OK);
    assert_true(f->delta == 2.0 && f->data[7] == (double)(float)7e-3);
    im_field_free(f);
}

/* D12: without ZUnits the heights' unit is unknown, not XYUnits': refused naming ZUnits, read once
 * --height-unit states it (here nm, converted into the lateral metres). */
static void gsf_without_z_units_is_refused(void **state)
{
    (void)state;
    const char *path = write_gsf("no_z.gsf", "XRes = 4\nYRes = 4\nXReal = 4e-6\nYReal = 4e-6\nXYUnits = m\n", 4, 4);
    expect_read_refused(path, NULL,
                        "no ZUnits: the heights' unit is not stated, and is not assumed to be the "
                        "lateral unit (m)");
    im_surface_read_options options = {.set = {.height = "nm"}};
    im_field *f = NULL;
    im_surface_read_info info;
    assert_int_equal(im_surface_read_with(path, &options, &f, &info), IM_OK);
    assert_close(f->data[5], (double)(float)5e-3 * 1e-9, 1e-24);
    assert_true(info.height_factor == 1e-9);
    im_field_free(f);
    double xreal, yreal;
    char xy_unit[16], z_unit[16];
    if (gwyddion_extents(path, &xreal, &yreal, xy_unit, z_unit))
        assert_string_not_equal(z_unit, "m"); /* Gwyddion too: no unit ("-" in its stream) */
}

/* A lateral unit given with --unit to a .gsf without units does not state the heights' unit either;
 * without any unit the file is read as it is, lengths in one unnamed unit. */
static void gsf_with_no_units_is_read_bare(void **state)
{
    (void)state;
    const char *path = write_gsf("bare.gsf", "XRes = 4\nYRes = 4\nXReal = 8\nYReal = 8\n", 4, 4);
    im_surface_read_options options = {.set = {.lateral = "um"}};
    expect_read_refused(path, &options, "no ZUnits");
    im_field *f = NULL;
    assert_int_equal(im_surface_read_with(path, NULL, &f, NULL), IM_OK);
    assert_true(f->delta == 2.0 && f->unit[0] == '\0' && f->data[5] == (double)(float)5e-3);
    im_field_free(f);
}

/* Other formats keep their rule: a Gwyddion text with a Width and no Value units has its heights in
 * the Width's unit. */
static void text_heights_stay_in_the_lateral_unit(void **state)
{
    (void)state;
    const char *path = test_path("width_only.txt");
    FILE *out = fopen(path, "w");
    assert_non_null(out);
    fprintf(out, "# Width: 4 um\n# Height: 4 um\n");
    for (int iy = 0; iy < 4; ++iy)
        fprintf(out, "%d 1 2 3\n", iy);
    fclose(out);
    im_field *f = NULL;
    assert_int_equal(im_surface_read(path, &f), IM_OK);
    assert_string_equal(f->unit, "\u00b5m");
    assert_true(f->delta == 1.0 && f->data[4] == 1.0);
    im_field_free(f);
}

/* D15: a .npy indexed [x, y], as SurfaceTopography's heights() are: value x * 1000 + y at [x, y], of
 * shape (128, 64), so a 128 x 64 grid (nx 128 along x). Written as a field of 64 columns by 128 rows. */
static const char *write_xy_npy(const char *name)
{
    im_field *f = NULL;
    assert_int_equal(im_field_create(64, 128, 1.0, &f), IM_OK);
    for (int x = 0; x < 128; ++x)
        for (int y = 0; y < 64; ++y)
            f->data[(size_t)x * 64 + y] = x * 1000.0 + y;
    const char *path = test_path(name);
    assert_int_equal(im_npy_write(path, f, IM_NPY_FLOAT64), IM_OK);
    im_field_free(f);
    return path;
}

/* The field holds (x, y) of write_xy_npy at data[y * nx + x]: read with rows along y. */
static void assert_rows_are_y(const im_field *f)
{
    assert_int_equal(f->nx, 128);
    assert_int_equal(f->ny, 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 128; ++x)
            assert_true(f->data[(size_t)y * 128 + x] == x * 1000.0 + y);
}

static im_field *read_npy(const char *path, enum im_npy_order order, im_surface_read_info *info)
{
    im_surface_read_options options = {.npy_order = order};
    im_field *f = NULL;
    if (im_surface_read_with(path, &options, &f, info) != IM_OK)
        fail_msg("%s", im_last_error());
    return f;
}

static void write_text(const char *path, const char *text) { test_write_bytes(path, text, strlen(text)); }

/* npy_order = IM_NPY_ORDER_XY transposes, and says so; the default and yx keep the stored rows. */
static void npy_order_xy_transposes(void **state)
{
    (void)state;
    const char *path = write_xy_npy("xy.npy");
    im_surface_read_info info;
    im_field *f = read_npy(path, IM_NPY_ORDER_XY, &info);
    assert_rows_are_y(f);
    assert_string_equal(info.conversion, "indexed [x, y]");
    assert_int_equal(info.stored_nx, 128);
    im_field_free(f);
    for (int order = IM_NPY_ORDER_SIDECAR; order <= IM_NPY_ORDER_YX; ++order) {
        f = read_npy(path, (enum im_npy_order)order, &info);
        assert_true(f->nx == 64 && f->ny == 128 && f->data[5 * 64 + 3] == 5003.0);
        assert_string_equal(info.conversion, "");
        im_field_free(f);
    }
}

/* The sidecar's "order": "xy" transposes by default (im_npy_read too); the option overrides it. */
static void sidecar_order_is_honoured(void **state)
{
    (void)state;
    const char *path = write_xy_npy("sidecar_xy.npy");
    write_text(test_path("sidecar_xy.npy.json"), "{\"delta\": 0.5, \"unit\": \"nm\", \"order\": \"xy\"}");
    im_field *f = read_npy(path, IM_NPY_ORDER_SIDECAR, NULL);
    assert_rows_are_y(f);
    assert_true(f->delta == 0.5);
    assert_string_equal(f->unit, "nm");
    im_field_free(f);
    assert_int_equal(im_npy_read(path, &f), IM_OK);
    assert_rows_are_y(f);
    im_field_free(f);
    f = read_npy(path, IM_NPY_ORDER_YX, NULL);
    assert_true(f->nx == 64 && f->ny == 128);
    im_field_free(f);
}

/* The order is of the indices, not of the memory: a Fortran-ordered [x, y] array (whose bytes are
 * those of a C-ordered [y, x] one) reads the same, both transpositions stated. */
static void fortran_order_is_independent(void **state)
{
    (void)state;
    static const char header[] = "{'descr': '<f8', 'fortran_order': True, 'shape': (128, 64), }";
    char bytes[128] = "\x93NUMPY\x01\x00";
    bytes[8] = 118; /* header length: 10 + 118 = 128 bytes before the data */
    memset(bytes + 10, ' ', 118);
    memcpy(bytes + 10, header, sizeof header - 1);
    bytes[127] = '\n';
    double *values = malloc(128 * 64 * sizeof *values);
    assert_non_null(values);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 128; ++x)
            values[y * 128 + x] = x * 1000.0 + y; /* column-major [x, y]: x fastest */
    const char *path = test_path("fortran_xy.npy");
    FILE *out = fopen(path, "wb");
    assert_non_null(out);
    assert_int_equal(fwrite(bytes, 1, sizeof bytes, out), sizeof bytes);
    assert_int_equal(fwrite(values, sizeof *values, 128 * 64, out), 128 * 64);
    fclose(out);
    free(values);
    im_surface_read_info info;
    im_field *f = read_npy(path, IM_NPY_ORDER_XY, &info);
    assert_rows_are_y(f);
    assert_string_equal(info.conversion, "Fortran order transposed to C order; indexed [x, y]");
    im_field_free(f);
}

/* A sidecar "order" other than "yx" or "xy" is refused naming the sidecar; an npy_order outside the
 * enumeration is misuse; other formats ignore the option. */
static void bad_orders_are_refused(void **state)
{
    (void)state;
    const char *path = write_xy_npy("bad_order.npy");
    const char *orders[] = {"{\"order\": \"x\"}", "{\"order\": \"C\"}", "{\"order\": 1}", "{\"order\": \"yxyx\"}"};
    for (size_t i = 0; i < sizeof orders / sizeof *orders; ++i) {
        write_text(test_path("bad_order.npy.json"), orders[i]);
        im_field *f = NULL;
        assert_int_equal(im_npy_read(path, &f), IM_EFORMAT);
        assert_non_null(strstr(im_last_error(), "bad_order.npy.json: expected"));
        assert_non_null(strstr(im_last_error(), "\"order\" \"yx\" or \"xy\""));
    }
    im_surface_read_options options = {.npy_order = (enum im_npy_order)3};
    im_field *f = NULL;
    assert_int_equal(im_surface_read_with(path, &options, &f, NULL), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "im_surface_read_with: options->npy_order = 3"));
    f = read_npy(write_gsf("order.gsf", "XRes = 4\nYRes = 2\nXReal = 4\nYReal = 2\n", 4, 2), IM_NPY_ORDER_XY, NULL);
    assert_true(f->nx == 4 && f->ny == 2);
    im_field_free(f);
}

/* A scene's npy_order = yx|xy|sidecar; anything else refused at its line. */
static void scene_key_npy_order(void **state)
{
    (void)state;
    const char *path = test_path("order.ini");
    write_text(path, "[surfaces]\nfile = xy.npy\nnpy_order = xy\n");
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(path, &scene), IM_OK);
    assert_int_equal(scene->npy_order, IM_NPY_ORDER_XY);
    im_scene_free(scene);
    write_text(path, "[surfaces]\nfile = xy.npy\nnpy_order = x\n");
    assert_int_equal(im_scene_load(path, &scene), IM_EFORMAT);
    assert_null(scene);
    assert_non_null(strstr(im_last_error(), "order.ini:3: npy_order = 'x': expected one of sidecar|yx|xy"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gsf_is_written_in_metres),
        cmocka_unit_test(gsf_without_unit_states_none),
        cmocka_unit_test(gsf_refuses_a_unit_that_is_not_a_length),
        cmocka_unit_test(gwyddion_reads_the_written_extent),
        cmocka_unit_test(gsf_extents_default_to_one),
        cmocka_unit_test(gsf_absent_extents_are_named),
        cmocka_unit_test(gsf_without_z_units_is_refused),
        cmocka_unit_test(gsf_with_no_units_is_read_bare),
        cmocka_unit_test(text_heights_stay_in_the_lateral_unit),
        cmocka_unit_test(npy_order_xy_transposes),
        cmocka_unit_test(sidecar_order_is_honoured),
        cmocka_unit_test(fortran_order_is_independent),
        cmocka_unit_test(bad_orders_are_refused),
        cmocka_unit_test(scene_key_npy_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
