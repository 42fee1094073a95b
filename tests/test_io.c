/* Tests of the file formats: exact round trips and clear refusals of bad files. */
#include "support.h"

#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "core/memory.h"
#include "io/json_file.h"

#include <math.h>
#include <netcdf.h>
#include <zip.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static im_field *sample_field(int nx, int ny)
{
    im_field *f = NULL;
    assert_int_equal(im_field_create(nx, ny, 1.0, &f), IM_OK);
    for (size_t i = 0; i < im_field_count(f); ++i)
        f->data[i] = sin(0.37 * (double)i) * 1e3 + 1.0 / 3.0 + (double)i * 1e-9;
    return f;
}

static void assert_fields_equal(const im_field *a, const im_field *b)
{
    assert_int_equal(a->nx, b->nx);
    assert_int_equal(a->ny, b->ny);
    assert_memory_equal(a->data, b->data, im_field_count(a) * sizeof(double));
}

static void npy_float64_round_trip_is_exact(void **state)
{
    (void)state;
    im_field *f = sample_field(7, 5), *g = NULL;
    const char *path = test_path("f64.npy");
    assert_int_equal(im_npy_write(path, f, IM_NPY_FLOAT64), IM_OK);
    assert_int_equal(im_npy_read(path, &g), IM_OK);
    assert_fields_equal(f, g);
    /* the header is a multiple of 64 bytes, as NumPy writes it */
    struct stat info;
    assert_int_equal(stat(path, &info), 0);
    assert_int_equal((info.st_size - 7 * 5 * 8) % 64, 0);
    im_field_free(f);
    im_field_free(g);
}

static void npy_float32_round_trip_is_exact_in_float(void **state)
{
    (void)state;
    im_field *f = sample_field(6, 4), *g = NULL;
    for (size_t i = 0; i < im_field_count(f); ++i)
        f->data[i] = (float)f->data[i];
    assert_int_equal(im_npy_write(test_path("f32.npy"), f, IM_NPY_FLOAT32), IM_OK);
    assert_int_equal(im_npy_read(test_path("f32.npy"), &g), IM_OK);
    assert_fields_equal(f, g);
    im_field_free(f);
    im_field_free(g);
}

static void text_and_gsf_round_trips(void **state)
{
    (void)state;
    im_field *f = sample_field(9, 3), *g = NULL;
    f->delta = 0.25;
    strcpy(f->unit, "um");
    assert_int_equal(im_text_write(test_path("f.txt"), f), IM_OK);
    assert_int_equal(im_text_read(test_path("f.txt"), &g), IM_OK);
    assert_fields_equal(f, g);
    assert_close(g->delta, 0.25, 1e-15);
    assert_string_equal(g->unit, "\u00b5m"); /* the canonical spelling */
    im_field_free(g);
    for (size_t i = 0; i < im_field_count(f); ++i)
        f->data[i] = (float)f->data[i];
    f->unit[0] = '\0'; /* a field in µm is written in metres: tests/test_gsf_npy_layouts.c */
    assert_int_equal(im_gsf_write(test_path("f.gsf"), f), IM_OK);
    assert_int_equal(im_gsf_read(test_path("f.gsf"), &g), IM_OK);
    assert_fields_equal(f, g);
    assert_close(g->delta, 0.25, 1e-15);
    im_field_free(f);
    im_field_free(g);
}

/* An infinite height is refused by every surface writer before anything is written (the text writer
 * wrote "inf", which its own reader refused): the message names the file and the point. */
static void non_finite_heights_are_not_written(void **state)
{
    (void)state;
    const char *names[] = {"nonfinite.txt", "nonfinite.gsf", "nonfinite.sdf",
                           "nonfinite.nc",  "nonfinite.x3p", "nonfinite.npy"};
    im_field *f = sample_field(5, 4);
    strcpy(f->unit, "um");
    for (int k = 0; k < 2; ++k) {
        f->data[1 * 5 + 2] = k == 0 ? INFINITY : -INFINITY;
        for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
            const char *path = test_path(names[i]);
            assert_int_equal(im_surface_write(path, f), IM_EINVAL);
            assert_non_null(strstr(im_last_error(), path));
            assert_non_null(strstr(im_last_error(), "(x=2, y=1)"));
            assert_int_equal(access(path, F_OK), -1);
        }
    }
    f->data[1 * 5 + 2] = INFINITY;
    assert_int_equal(im_text_write(test_path("direct.txt"), f), IM_EINVAL); /* each writer, not only the dispatcher */
    assert_int_equal(im_x3p_write(test_path("direct.x3p"), f), IM_EINVAL);
    f->data[1 * 5 + 2] = 1.0;
    assert_int_equal(im_surface_write(test_path("good.txt"), f), IM_OK);
    im_field_free(f);
}

/* The bytes of an archive's entry (at most size), and how many there were. */
static size_t zip_entry_bytes(const char *path, const char *entry, unsigned char *bytes, size_t size)
{
    int error = 0;
    zip_t *archive = zip_open(path, ZIP_RDONLY, &error);
    assert_non_null(archive);
    zip_file_t *file = zip_fopen(archive, entry, 0);
    assert_non_null(file);
    zip_int64_t read = zip_fread(file, bytes, size);
    zip_fclose(file);
    zip_discard(archive);
    assert_true(read >= 0);
    return (size_t)read;
}

/* Missing points (NaN) written to any surface format come back missing, where they were (.x3p in its
 * validity mask, whose MD5 the reader checks; .gsf as NaN, which Gwyddion masks too): read as heights
 * the first is refused naming it; read as values they are the NaN, the first and last points among them
 * (the mask's first bit and, in its third byte, its last). */
static void missing_points_are_written_where_they_can_be_read_back(void **state)
{
    (void)state;
    const char *names[] = {"missing.txt", "missing.sdf", "missing.nc", "missing.npy", "missing.gsf", "missing.x3p"};
    const size_t missing[] = {0, 1 * 5 + 2, 19};
    im_field *f = sample_field(5, 4);
    strcpy(f->unit, "um");
    for (size_t k = 0; k < 3; ++k)
        f->data[missing[k]] = NAN;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
        const char *path = test_path(names[i]);
        assert_int_equal(im_surface_write(path, f), IM_OK);
        im_field *back = NULL;
        assert_int_equal(im_surface_read(path, &back), IM_EFORMAT);
        assert_non_null(strstr(im_last_error(), "(x=0, y=0): a missing point"));
        im_surface_read_options values = {.field_values = 1};
        assert_int_equal(im_surface_read_with(path, &values, &back, NULL), IM_OK);
        for (size_t j = 0; j < 20; ++j)
            assert_true(j == missing[0] || j == missing[1] || j == missing[2] ? isnan(back->data[j])
                                                                              : isfinite(back->data[j]));
        if (strstr(path, ".x3p")) { /* ISO 25178-72's bits: least significant first, 1 valid, unused bits 0 */
            unsigned char bits[8], expected[] = {0x7e, 0xff, 0x07};
            assert_int_equal(zip_entry_bytes(path, "bindata/valid.bin", bits, sizeof bits), sizeof expected);
            assert_memory_equal(bits, expected, sizeof expected);
        }
        im_field_free(back);
    }
    im_field_free(f);
}

/* A Gwyddion text export stating only its Height (rows x spacing) states square pixels of Height / rows
 * in its unit, as one stating only its Width does (it was read in units of delta, the extent ignored). */
static void a_height_alone_states_the_spacing(void **state)
{
    (void)state;
    const char *only_height = "# Height: 3 um\n1 2 3\n4 5 6\n7 8 9\n",
               *only_width = "# Width: 3 um\n1 2 3\n4 5 6\n7 8 9\n";
    const char *texts[] = {only_height, only_width};
    for (int k = 0; k < 2; ++k) {
        test_write_bytes(test_path("extent.txt"), texts[k], strlen(texts[k]));
        im_field *f = NULL;
        assert_int_equal(im_text_read(test_path("extent.txt"), &f), IM_OK);
        assert_int_equal(f->nx, 3);
        assert_int_equal(f->ny, 3);
        assert_close(f->delta, 1.0, 1e-15);
        assert_string_equal(f->unit, "\u00b5m");
        im_field_free(f);
    }
}

/* Builds a .npy file from a header dictionary and a payload of `values` doubles, each `value`. */
static void write_npy(const char *path, const char *dict, size_t values, double value)
{
    size_t dict_length = strlen(dict), header = 10 + dict_length + 1;
    size_t padding = (64 - header % 64) % 64, length = dict_length + 1 + padding;
    size_t size = 10 + length + values * 8;
    unsigned char *bytes = calloc(size, 1);
    memcpy(bytes, "\x93NUMPY\x01\x00", 8);
    bytes[8] = (unsigned char)(length & 0xff);
    bytes[9] = (unsigned char)(length >> 8);
    memcpy(bytes + 10, dict, dict_length);
    memset(bytes + 10 + dict_length, ' ', padding);
    bytes[10 + length - 1] = '\n';
    for (size_t i = 0; i < values; ++i)
        memcpy(bytes + 10 + length + 8 * i, &value, 8);
    test_write_bytes(path, bytes, size);
    free(bytes);
}

static void expect_refusal(int (*reader)(const char *, im_field **), const char *path, int status, const char *phrase)
{
    im_field *f = NULL;
    int got = reader(path, &f);
    if (got != status || !strstr(im_last_error(), phrase))
        fail_msg("%s: status %d (expected %d), message '%s' (expected to contain '%s')", path, got, status,
                 im_last_error(), phrase);
    assert_null(f);
    assert_non_null(strstr(im_last_error(), path));
}

static void bad_npy_files_are_refused(void **state)
{
    (void)state;
    const char *ok = "{'descr': '<f8', 'fortran_order': False, 'shape': (4, 3), }";
    write_npy(test_path("short.npy"), ok, 11, 1.5);
    expect_refusal(im_npy_read, test_path("short.npy"), IM_EFORMAT, "truncated");
    write_npy(test_path("long.npy"), ok, 13, 1.5);
    expect_refusal(im_npy_read, test_path("long.npy"), IM_EFORMAT, "more data");
    static const char *const unsupported[] = {"'<c16'", "'<f2'", "'|i2'", "'<i3'", "'<U8'", "'O'"};
    for (size_t i = 0; i < sizeof unsupported / sizeof *unsupported; ++i) {
        char dict[128];
        snprintf(dict, sizeof dict, "{'descr': %s, 'fortran_order': False, 'shape': (4, 3), }", unsupported[i]);
        write_npy(test_path("type.npy"), dict, 12, 1.5);
        expect_refusal(im_npy_read, test_path("type.npy"), IM_EFORMAT, "is not supported");
    }
    write_npy(test_path("order.npy"), "{'descr': '<f8', 'fortran_order': Maybe, 'shape': (4, 3), }", 12, 1.5);
    expect_refusal(im_npy_read, test_path("order.npy"), IM_EFORMAT, "fortran_order Maybe");
    write_npy(test_path("3d.npy"), "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2, 3), }", 12, 1.5);
    expect_refusal(im_npy_read, test_path("3d.npy"), IM_EFORMAT, "2-D");
    write_npy(test_path("nan.npy"), ok, 12, NAN);
    expect_refusal(im_npy_read, test_path("nan.npy"), IM_EFORMAT, "finite");
    expect_refusal(im_npy_read, test_path("nan.npy"), IM_EFORMAT, "(x=0, y=0)");
    write_npy(test_path("inf.npy"), ok, 12, INFINITY);
    expect_refusal(im_npy_read, test_path("inf.npy"), IM_EFORMAT, "value inf at (x=0, y=0): expected finite");
    write_npy(test_path("-inf.npy"), ok, 12, -INFINITY);
    expect_refusal(im_npy_read, test_path("-inf.npy"), IM_EFORMAT, "value -inf");
    /* 2^32 x 2^32 doubles = 2^67 bytes: more than any 64-bit address space, refused on every machine
     * before the side limit and before allocating; the estimate (2^47 MiB) is in the message */
    write_npy(test_path("huge.npy"), "{'descr': '<f8', 'fortran_order': False, 'shape': (4294967296, 4294967296), }",
              12, 1.5);
    expect_refusal(im_npy_read, test_path("huge.npy"), IM_ENOMEM, "needs about 140737488355328.0 MiB");
    /* within memory but past the largest side: a format error naming the limit */
    write_npy(test_path("wide.npy"), "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 65537), }", 12, 1.5);
    expect_refusal(im_npy_read, test_path("wide.npy"), IM_EFORMAT, "expected each side in [1, 65536]");
    test_write_bytes(test_path("junk.npy"), "hello", 5);
    expect_refusal(im_npy_read, test_path("junk.npy"), IM_EFORMAT, "magic");
    expect_refusal(im_npy_read, test_path("missing.npy"), IM_EIO, "cannot open");
}

/* A .npy of dict and payload bytes, padded as NumPy does. */
static void write_npy_bytes(const char *path, const char *dict, const void *payload, size_t payload_size)
{
    size_t dict_length = strlen(dict), header = 10 + dict_length + 1;
    size_t padding = (64 - header % 64) % 64, length = dict_length + 1 + padding;
    unsigned char bytes[1024];
    memcpy(bytes, "\x93NUMPY\x01\x00", 8);
    bytes[8] = (unsigned char)(length & 0xff);
    bytes[9] = (unsigned char)(length >> 8);
    memcpy(bytes + 10, dict, dict_length);
    memset(bytes + 10 + dict_length, ' ', padding);
    bytes[10 + length - 1] = '\n';
    memcpy(bytes + 10 + length, payload, payload_size);
    test_write_bytes(path, bytes, 10 + length + payload_size);
}

/* Issue 13: .npy in any byte order, Fortran order and integer dtypes is read, converted to double
 * in C order, and the conversion recorded. Expected values are written by hand, byte by byte. */
static void npy_of_any_type_is_converted(void **state)
{
    (void)state;
    static const struct {
        const char *descr;
        unsigned char payload[48];
        size_t size;
        const char *conversion;
    } cases[] = {
        {"'>f8'", {0x3f, 0xf8, 0, 0, 0, 0, 0, 0, 0xc0, 0x02, 0, 0, 0, 0, 0, 0}, 16, "'>f8' (float64) converted"},
        {"'<f4'", {0, 0, 0xc0, 0x3f, 0, 0, 0x20, 0xc0}, 8, "'<f4' (float32) converted"},
        {"'<i2'", {0x05, 0x00, 0xfd, 0xff}, 4, "'<i2' (int16) converted"},
        {"'>i4'", {0, 0, 0x01, 0x00, 0xff, 0xff, 0xff, 0xfe}, 8, "'>i4' (int32) converted"},
        {"'>u2'", {0xff, 0xff, 0x00, 0x07}, 4, "'>u2' (uint16) converted"},
        {"'|u1'", {200, 3}, 2, "'|u1' (uint8) converted"},
        {"'|i1'", {0xff, 0x7f}, 2, "'|i1' (int8) converted"},
        {"'<i8'", {0xfe, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 9, 0, 0, 0, 0, 0, 0, 0}, 16, "'<i8' (int64)"},
    };
    static const double expected[][2] = {{1.5, -2.25}, {1.5, -2.5}, {5, -3},   {256, -2},
                                         {65535, 7},   {200, 3},    {-1, 127}, {-2, 9}};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; ++i) {
        char dict[128];
        snprintf(dict, sizeof dict, "{'descr': %s, 'fortran_order': False, 'shape': (1, 2), }", cases[i].descr);
        write_npy_bytes(test_path("typed.npy"), dict, cases[i].payload, cases[i].size);
        im_field *g = NULL;
        im_surface_read_info info;
        if (im_surface_read_with(test_path("typed.npy"), NULL, &g, &info) != IM_OK)
            fail_msg("%s: %s", cases[i].descr, im_last_error());
        assert_close(g->data[0], expected[i][0], 0.0);
        assert_close(g->data[1], expected[i][1], 0.0);
        assert_non_null(strstr(info.conversion, cases[i].conversion));
        im_field_free(g);
    }
    /* Fortran order: a 2 x 3 array stored column by column */
    const double columns[6] = {11, 21, 12, 22, 13, 23};
    write_npy_bytes(test_path("fortran.npy"), "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }", columns,
                    sizeof columns);
    im_field *g = NULL;
    im_surface_read_info info;
    assert_int_equal(im_surface_read_with(test_path("fortran.npy"), NULL, &g, &info), IM_OK);
    assert_int_equal(g->nx, 3);
    assert_int_equal(g->ny, 2);
    const double rows[6] = {11, 12, 13, 21, 22, 23};
    assert_memory_equal(g->data, rows, sizeof rows);
    assert_string_equal(info.conversion, "Fortran order transposed to C order");
    im_field_free(g);
}

/* ISO 25178-71 .sdf: a binary round trip keeps heights, spacing and units (metres); an ASCII file
 * written by hand is read with its Zscale and a missing point; bad files are refused naming the
 * file and the field. */
static void sdf_files_round_trip_and_refuse(void **state)
{
    (void)state;
    im_field *f = sample_field(7, 5), *g = NULL;
    f->delta = 0.25;
    strcpy(f->unit, "\u00b5m");
    assert_int_equal(im_sdf_write(test_path("f.sdf"), f), IM_OK);
    assert_int_equal(im_surface_read(test_path("f.sdf"), &g), IM_OK);
    assert_string_equal(g->unit, "m");
    assert_close(g->delta, 0.25e-6, 1e-22);
    for (size_t i = 0; i < im_field_count(f); ++i)
        assert_close(g->data[i], f->data[i] * 1e-6, 1e-21 * fabs(f->data[i]) + 1e-30);
    im_field_free(g);
    f->unit[0] = '\0';
    assert_int_equal(im_sdf_write(test_path("none.sdf"), f), IM_EINVAL);
    im_field_free(f);
    static const char head[] = "aISO-1.0\nManufacID = test\nNumPoints = 3\nNumProfiles = 2\nXscale = 1e-6\n"
                               "Yscale = 1e-6\nZscale = 1e-9\nCompression = 0\nDataType = 5\n*\n";
    char text[1024];
    snprintf(text, sizeof text, "%s1 2 3\n4 BAD -6\n*\n", head);
    test_write_bytes(test_path("a.sdf"), text, strlen(text));
    im_surface_read_options fill = {.fill = 1};
    assert_int_equal(im_surface_read_with(test_path("a.sdf"), &fill, &g, NULL), IM_OK);
    assert_close(g->data[2], 3e-9, 1e-24);
    assert_close(g->data[5], -6e-9, 1e-24);
    assert_close(g->data[4], (2e-9 + 4e-9 - 6e-9) / 3.0, 1e-24); /* BAD filled from its neighbours */
    im_field_free(g);
    static const struct {
        const char *from, *to, *phrase;
    } edits[] = {
        {"aISO-1.0", "aXYZ-1.0", "not an ISO 25178-71 surface data file"},
        {"Xscale = 1e-6", "Xscale = 0", "Xscale = 0: expected a finite length in metres > 0"},
        {"Yscale = 1e-6", "Yscale = nan", "Yscale = nan: expected a finite length"},
        {"Yscale = 1e-6", "Yscale = 2e-6", "Xscale and Yscale: non-square pixels"},
        {"NumPoints = 3", "NumPoints = 3x", "NumPoints = '3x': expected a decimal integer"},
        {"NumProfiles = 2", "NumProfiles = 3", "truncated data"},
        {"NumProfiles = 2", "Profiles = 2", "the header lacks NumProfiles"},
        {"Compression = 0", "Compression = 1", "Compression = 1: only uncompressed data"},
        {"DataType = 5", "DataType = 9", "DataType = 9: expected 0 to 7"},
        {"1 2 3", "1 2 3 4", "more values than NumPoints x NumProfiles"},
        {"4 5", "4 x", "value 5 (x=1, y=1): 'x' is not a number"},
    };
    for (size_t i = 0; i < sizeof edits / sizeof *edits; ++i) {
        char body[1024];
        snprintf(body, sizeof body, "%s1 2 3\n4 5 6\n*\n", head);
        char *at = strstr(body, edits[i].from);
        assert_non_null(at);
        char edited[1024];
        snprintf(edited, sizeof edited, "%.*s%s%s", (int)(at - body), body, edits[i].to, at + strlen(edits[i].from));
        test_write_bytes(test_path("bad.sdf"), edited, strlen(edited));
        expect_refusal(im_sdf_read, test_path("bad.sdf"), IM_EFORMAT, edits[i].phrase);
    }
    test_write_bytes(test_path("cut.sdf"), "bISO-1.0indentmap", 17);
    expect_refusal(im_sdf_read, test_path("cut.sdf"), IM_EFORMAT, "truncated header");
}

/* A NetCDF file with dimensions x = 3, y = 2 and what `edit` defines (heights and coordinates). */
static const char *write_nc(const char *name, void (*edit)(int ncid, int x, int y))
{
    int ncid, dims[2];
    const char *path = test_path(name);
    assert_int_equal(nc_create(path, NC_CLOBBER | NC_64BIT_OFFSET, &ncid), NC_NOERR);
    nc_def_dim(ncid, "x", 3, &dims[0]);
    nc_def_dim(ncid, "y", 2, &dims[1]);
    edit(ncid, dims[0], dims[1]);
    assert_int_equal(nc_close(ncid), NC_NOERR);
    return path;
}

static void no_heights(int ncid, int x, int y)
{
    int dims[2] = {x, y}, var;
    nc_def_var(ncid, "height", NC_DOUBLE, 2, dims, &var); /* not the name the layout asks for */
}
static void heights_3d(int ncid, int x, int y)
{
    int z, dims[3] = {x, y, 0}, var;
    nc_def_dim(ncid, "z", 2, &z);
    dims[2] = z;
    nc_def_var(ncid, "heights", NC_DOUBLE, 3, dims, &var);
}
static void heights_text(int ncid, int x, int y)
{
    int dims[2] = {x, y}, var;
    nc_def_var(ncid, "heights", NC_CHAR, 2, dims, &var);
}
static void heights_with_length(int ncid, int x, int y, double length, const char *x_unit, const char *y_unit)
{
    int dims[2] = {x, y}, var, xv, yv;
    nc_def_var(ncid, "heights", NC_DOUBLE, 2, dims, &var);
    nc_def_var(ncid, "x", NC_DOUBLE, 1, &x, &xv);
    nc_def_var(ncid, "y", NC_DOUBLE, 1, &y, &yv);
    nc_put_att_double(ncid, xv, "length", NC_DOUBLE, 1, &length);
    nc_put_att_text(ncid, xv, "length_unit", strlen(x_unit), x_unit);
    nc_put_att_text(ncid, yv, "length_unit", strlen(y_unit), y_unit);
}
static void negative_length(int ncid, int x, int y) { heights_with_length(ncid, x, y, -3.0, "um", "um"); }
static void nan_length(int ncid, int x, int y) { heights_with_length(ncid, x, y, NAN, "um", "um"); }
static void two_units(int ncid, int x, int y) { heights_with_length(ncid, x, y, 3.0, "um", "nm"); }

/* SurfaceTopography and contact.engineering today: x:unit, y:unit and heights:unit (nc-1.nc of its
 * examples); heights 1..6 in um on a grid of nm. */
static void heights_with_unit_attributes(int ncid, int x, int y)
{
    int dims[2] = {x, y}, var, xv, yv;
    double length = 3.0, heights[6] = {1, 2, 3, 4, 5, 6};
    nc_def_var(ncid, "heights", NC_DOUBLE, 2, dims, &var);
    nc_def_var(ncid, "x", NC_DOUBLE, 1, &x, &xv);
    nc_def_var(ncid, "y", NC_DOUBLE, 1, &y, &yv);
    nc_put_att_double(ncid, xv, "length", NC_DOUBLE, 1, &length);
    nc_put_att_text(ncid, xv, "unit", 2, "nm");
    nc_put_att_text(ncid, yv, "unit", 2, "nm");
    nc_put_att_text(ncid, var, "unit", 2, "um");
    nc_enddef(ncid);
    nc_put_var_double(ncid, var, heights);
}

static void netcdf_unit_attributes_are_read_and_written(void **state)
{
    (void)state;
    im_field *g = NULL;
    assert_int_equal(im_surface_read(write_nc("unit.nc", heights_with_unit_attributes), &g), IM_OK);
    assert_close(g->delta, 1.0, 0.0);
    assert_string_equal(g->unit, "nm");
    assert_close(g->data[1], 3000.0, 1e-12); /* heights(x = 1, y = 0) = 3 um, in nm */
    int ncid, var;
    char unit[16] = "";
    assert_int_equal(im_netcdf_write(test_path("written.nc"), g), IM_OK);
    assert_int_equal(nc_open(test_path("written.nc"), NC_NOWRITE, &ncid), NC_NOERR);
    const char *names[] = {"x", "y", "heights"};
    for (int k = 0; k < 3; ++k) {
        memset(unit, 0, sizeof unit);
        assert_int_equal(nc_inq_varid(ncid, names[k], &var), NC_NOERR);
        assert_int_equal(nc_get_att_text(ncid, var, "unit", unit), NC_NOERR);
        assert_string_equal(unit, "nm");
    }
    nc_close(ncid);
    im_field_free(g);
}

/* NetCDF in SurfaceTopography's layout: a round trip keeps heights (exactly), spacing and unit,
 * through the heights(x, y) transpose of a non-square grid; malformed files are refused naming the
 * file and the dimension, variable or attribute. */
static void netcdf_round_trip_and_refusals(void **state)
{
    (void)state;
    im_field *f = sample_field(7, 5), *g = NULL;
    f->delta = 0.5;
    strcpy(f->unit, "\u00b5m");
    assert_int_equal(im_netcdf_write(test_path("f.nc"), f), IM_OK);
    assert_int_equal(im_surface_read(test_path("f.nc"), &g), IM_OK);
    assert_fields_equal(f, g);
    assert_close(g->delta, 0.5, 0.0);
    assert_string_equal(g->unit, "\u00b5m");
    im_field_free(g);
    int ncid, var, dims[2];
    size_t length;
    assert_int_equal(nc_open(test_path("f.nc"), NC_NOWRITE, &ncid), NC_NOERR);
    assert_int_equal(nc_inq_varid(ncid, "heights", &var), NC_NOERR);
    nc_inq_vardimid(ncid, var, dims);
    nc_inq_dimlen(ncid, dims[0], &length);
    assert_int_equal(length, 7); /* heights(x, y): x first, as SurfaceTopography writes it */
    size_t at[2] = {4, 3};
    double value;
    nc_get_var1_double(ncid, var, at, &value);
    assert_close(value, f->data[3 * 7 + 4], 0.0);
    nc_close(ncid);
    FILE *in = fopen(test_path("f.nc"), "rb");
    unsigned char bytes[4096];
    size_t size = fread(bytes, 1, sizeof bytes, in);
    fclose(in);
    test_write_bytes(test_path("cut.nc"), bytes, size - 40);
    expect_refusal(im_netcdf_read, test_path("cut.nc"), IM_EFORMAT, "cut.nc: truncated: a variable's data lies past");
    test_write_bytes(test_path("junk.nc"), "CDF\x01 not really", 15);
    expect_refusal(im_netcdf_read, test_path("junk.nc"), IM_EFORMAT,
                   "junk.nc: netCDF header: a count or name runs past");
    test_write_bytes(test_path("hdf.nc"), "\x89HDF\r\n\x1a\n not really", 19);
    expect_refusal(im_netcdf_read, test_path("hdf.nc"), IM_EFORMAT, "cannot open as NetCDF");
    expect_refusal(im_netcdf_read, write_nc("none.nc", no_heights), IM_EFORMAT, "variable 'heights'");
    expect_refusal(im_netcdf_read, write_nc("3d.nc", heights_3d), IM_EFORMAT, "heights has 3 dimensions");
    expect_refusal(im_netcdf_read, write_nc("text.nc", heights_text), IM_EFORMAT, "heights holds text");
    expect_refusal(im_netcdf_read, write_nc("negative.nc", negative_length), IM_EFORMAT,
                   "x:length: expected one finite number > 0");
    expect_refusal(im_netcdf_read, write_nc("nan.nc", nan_length), IM_EFORMAT, "x:length: expected one finite");
    expect_refusal(im_netcdf_read, write_nc("units.nc", two_units), IM_EFORMAT,
                   "x's unit 'um' and y's unit 'nm' differ");
    im_field_free(f);
}

/* An .x3p archive holding main.xml (xml, may be NULL) and bindata/data.bin (data, may be NULL). */
static const char *write_x3p(const char *name, const char *xml, const void *data, size_t size)
{
    const char *path = test_path(name);
    remove(path);
    int error;
    zip_t *archive = zip_open(path, ZIP_CREATE | ZIP_TRUNCATE, &error);
    assert_non_null(archive);
    if (xml)
        zip_file_add(archive, "main.xml", zip_source_buffer(archive, xml, strlen(xml), 0), 0);
    if (data)
        zip_file_add(archive, "bindata/data.bin", zip_source_buffer(archive, data, size, 0), 0);
    assert_int_equal(zip_close(archive), 0);
    return path;
}

/* main.xml of a 3 x 2 grid with the given CX AxisType, CZ DataType, CX Increment and SizeX. */
static void x3p_xml(char *out, size_t size, const char *cx_type, const char *z_type, const char *increment,
                    const char *size_x)
{
    snprintf(out, size,
             "<?xml version=\"1.0\"?>\n<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\">"
             "<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>"
             "<CX><AxisType>%s</AxisType><DataType>D</DataType><Increment>%s</Increment><Offset>0</Offset></CX>"
             "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment><Offset>0</Offset></CY>"
             "<CZ><AxisType>A</AxisType><DataType>%s</DataType><Increment>1e-9</Increment><Offset>2e-9</Offset></CZ>"
             "</Axes></Record1><Record3><MatrixDimension><SizeX>%s</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ>"
             "</MatrixDimension><DataLink><PointDataLink>bindata/data.bin</PointDataLink></DataLink></Record3>"
             "</p:ISO5436_2>\n",
             cx_type, increment, z_type, size_x);
}

/* ISO 25178-72 .x3p: a round trip keeps heights, spacing and unit (metres); an archive written by
 * hand (int16 data, CZ Increment and Offset) reads as Offset + Increment x value; malformed archives
 * are refused naming the file and the element. */
static void x3p_round_trip_and_refusals(void **state)
{
    (void)state;
    im_field *f = sample_field(7, 5), *g = NULL;
    f->delta = 0.5;
    strcpy(f->unit, "nm");
    assert_int_equal(im_x3p_write(test_path("f.x3p"), f), IM_OK);
    assert_int_equal(im_surface_read(test_path("f.x3p"), &g), IM_OK);
    assert_int_equal(g->nx, 7);
    assert_int_equal(g->ny, 5);
    assert_string_equal(g->unit, "m");
    assert_close(g->delta, 0.5e-9, 1e-25);
    for (size_t i = 0; i < im_field_count(f); ++i)
        assert_close(g->data[i], f->data[i] * 1e-9, 0.0); /* the same product, stored as double */
    im_field_free(g);
    char xml[2048];
    const short values[6] = {1, -2, 3, -4, 5, 32767};
    x3p_xml(xml, sizeof xml, "I", "I", "1e-6", "3");
    assert_int_equal(im_surface_read(write_x3p("int16.x3p", xml, values, sizeof values), &g), IM_OK);
    assert_close(g->delta, 1e-6, 0.0);
    assert_close(g->data[1], 2e-9 - 2e-9, 1e-24);
    assert_close(g->data[5], 2e-9 + 32767e-9, 1e-21);
    im_field_free(g);
    static const struct {
        const char *cx_type, *z_type, *increment, *size_x, *phrase;
        size_t bytes;
    } cases[] = {
        {"A", "I", "1e-6", "3", "AxisType CX A, CY I, CZ A: expected I, I, A", 12},
        {"I", "Q", "1e-6", "3", "CZ/DataType 'Q': expected I, L, F or D", 12},
        {"I", "I", "0", "3", "Increment CX 0, CY 1e-06, CZ 1e-09: expected CX, CY > 0", 12},
        {"I", "I", "nan", "3", "CX/Increment 'nan': expected a finite number", 12},
        {"I", "I", "1e-6", "3.5", "MatrixDimension 3.5 x 2 x 1: expected SizeX, SizeY integers", 12},
        {"I", "I", "1e-6", "3", "bindata/data.bin holds 10 bytes, SizeX x SizeY = 3 x 2 values of type I need 12",
         10},
        {"I", "I", "2e-6", "3", "CX/Increment and CY/Increment: non-square pixels", 12},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; ++i) {
        x3p_xml(xml, sizeof xml, cases[i].cx_type, cases[i].z_type, cases[i].increment, cases[i].size_x);
        expect_refusal(im_x3p_read, write_x3p("bad.x3p", xml, values, cases[i].bytes), IM_EFORMAT, cases[i].phrase);
    }
    expect_refusal(im_x3p_read, write_x3p("noxml.x3p", NULL, values, 12), IM_EFORMAT, "no main.xml: not an x3p");
    expect_refusal(im_x3p_read, write_x3p("broken.x3p", "<p:ISO5436_2><Record1>", values, 12), IM_EFORMAT,
                   "not well-formed ISO 5436-2 XML");
    expect_refusal(im_x3p_read,
                   write_x3p("dtd.x3p",
                             "<?xml version=\"1.0\"?><!DOCTYPE ISO5436_2 [<!ENTITY a "
                             "\"aaaaaaaaaa\"><!ENTITY b "
                             "\"&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;\">]><ISO5436_2>&b;</ISO5436_2>",
                             values, 12),
                   IM_EFORMAT, "declares a DTD");
    static const char not_zip[] = "PK\x03\x04 not a zip";
    test_write_bytes(test_path("plain.x3p"), not_zip, sizeof not_zip - 1);
    expect_refusal(im_x3p_read, test_path("plain.x3p"), IM_EFORMAT, "cannot open as an x3p (zip) archive");
    im_field_free(f);
}

/* Adds an entry holding `text` to an existing archive. */
static void add_to_archive(const char *path, const char *entry, const char *text)
{
    int error;
    zip_t *archive = zip_open(path, 0, &error);
    assert_non_null(archive);
    assert_true(zip_file_add(archive, entry, zip_source_buffer(archive, text, strlen(text), 0), ZIP_FL_OVERWRITE) >=
                0);
    assert_int_equal(zip_close(archive), 0);
}

/* The int16 grid of x3p_round_trip_and_refusals with `link` as its DataLink's content, stored (not
 * deflated) so that its bytes can be damaged in place. */
static const char *write_stored_x3p(const char *name, const char *link, const short values[6])
{
    char xml[2048], *at;
    x3p_xml(xml, sizeof xml, "I", "I", "1e-6", "3");
    at = strstr(xml, "<PointDataLink>");
    char tail[1024];
    snprintf(tail, sizeof tail, "%s", strstr(at, "</DataLink>"));
    snprintf(at, sizeof xml - (size_t)(at - xml), "%s%s", link, tail);
    const char *path = write_x3p(name, xml, values, 6 * sizeof *values);
    int error;
    zip_t *archive = zip_open(path, 0, &error);
    assert_non_null(archive);
    assert_int_equal(
        zip_set_file_compression(archive, zip_name_locate(archive, "bindata/data.bin", 0), ZIP_CM_STORE, 0), 0);
    assert_int_equal(zip_close(archive), 0);
    return path;
}

/* ISO 25178-72 checksums on reading: the data's MD5ChecksumPointData (its value here from Python's
 * hashlib) and md5checksum.hex, the MD5 of main.xml, must match when stated; a damaged entry is
 * caught by the zip's CRC-32, which libzip checks only at an entry's end. */
static void x3p_checksums_are_checked(void **state)
{
    (void)state;
    const short values[6] = {1, -2, 3, -4, 5, 32767};
    static const char right[] = "<PointDataLink>bindata/data.bin</PointDataLink>"
                                "<MD5ChecksumPointData>9521F8950F326BFCE7C2BE74EF2E1034</MD5ChecksumPointData>";
    static const char wrong[] = "<PointDataLink>bindata/data.bin</PointDataLink>"
                                "<MD5ChecksumPointData>9521F8950F326BFCE7C2BE74EF2E1035</MD5ChecksumPointData>";
    im_field *g = NULL;
    assert_int_equal(im_x3p_read(write_stored_x3p("md5_right.x3p", right, values), &g), IM_OK);
    assert_close(g->data[5], 2e-9 + 32767e-9, 1e-21);
    im_field_free(g);
    expect_refusal(im_x3p_read, write_stored_x3p("md5_wrong.x3p", wrong, values), IM_EFORMAT,
                   "bindata/data.bin: MD5 9521f8950f326bfce7c2be74ef2e1034, but "
                   "Record3/DataLink/MD5ChecksumPointData "
                   "states 9521F8950F326BFCE7C2BE74EF2E1035: the file is damaged");

    const char *path = write_stored_x3p("main_md5.x3p", right, values);
    add_to_archive(path, "md5checksum.hex", "0123456789abcdef0123456789abcdef *main.xml\n");
    expect_refusal(im_x3p_read, path, IM_EFORMAT, "main.xml: MD5 ");
    expect_refusal(im_x3p_read, path, IM_EFORMAT, "but md5checksum.hex states 0123456789abcdef0123456789abcdef");

    /* one bit of the stored data flipped in the file: its CRC-32 no longer matches */
    path = write_stored_x3p("crc.x3p", "<PointDataLink>bindata/data.bin</PointDataLink>", values);
    FILE *file = fopen(path, "r+b");
    assert_non_null(file);
    unsigned char bytes[4096];
    size_t size = fread(bytes, 1, sizeof bytes, file);
    size_t at = 0;
    while (at + sizeof values <= size && memcmp(bytes + at, values, sizeof values) != 0)
        ++at;
    assert_true(at + sizeof values <= size); /* the stored values are in the file */
    bytes[at + 2] ^= 0x01;                   /* -2 becomes -1 */
    rewind(file);
    assert_int_equal(fwrite(bytes, 1, size, file), size);
    fclose(file);
    expect_refusal(im_x3p_read, path, IM_EFORMAT, "bindata/data.bin: CRC error");
}

/* The caller's cap (im_memory_set_limit) limits the memory the readers may plan for, so a refusal
 * can be tested at a size every machine holds; the library reads no environment variable for it
 * (the program does: IM_MEMORY_LIMIT_MIB, tested in cli_checks.sh). */
/* The probe's readings (core/memory.c): MemAvailable within the machine's physical memory, and the
 * process's virtual size growing by an allocation it maps. */
static void memory_probe_reads_the_machine(void **state)
{
    (void)state;
    double physical = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGESIZE);
    size_t available = memory_meminfo_available();
    assert_true(available > 0 && (double)available <= physical);
    size_t before = memory_virtual_size();
    enum { BYTES = 64 << 20 };
    char *block = malloc(BYTES); /* above glibc's mmap threshold: mapped at once */
    assert_non_null(block);
    size_t after = memory_virtual_size();
    free(block);
    assert_true(before > 0 && after >= before + BYTES);
    im_memory_set_limit(BYTES);
    assert_true(im_memory_available() <= BYTES);
    im_memory_set_limit(0);
}

static void memory_limit_set_by_the_caller(void **state)
{
    (void)state;
    write_npy(test_path("2mib.npy"), "{'descr': '<f8', 'fortran_order': False, 'shape': (512, 512), }", 0, 1.5);
    im_memory_set_limit(1048576);
    assert_int_equal(im_memory_limit(), 1048576);
    expect_refusal(im_npy_read, test_path("2mib.npy"), IM_ENOMEM, "needs about 2.0 MiB but only 1.0 MiB");
    im_memory_set_limit(0);
    assert_int_equal(setenv("IM_MEMORY_LIMIT_MIB", "1", 1), 0);
    expect_refusal(im_npy_read, test_path("2mib.npy"), IM_EFORMAT, "truncated data");
    assert_int_equal(unsetenv("IM_MEMORY_LIMIT_MIB"), 0);
    expect_refusal(im_npy_read, test_path("2mib.npy"), IM_EFORMAT, "truncated data");
}

static void bad_text_matrices_name_the_line(void **state)
{
    (void)state;
    const char *bad_token = "# Channel: Height\n1 2 3\n4 5 6\n7 x8 9\n";
    test_write_bytes(test_path("token.txt"), bad_token, strlen(bad_token));
    expect_refusal(im_text_read, test_path("token.txt"), IM_EFORMAT, "token.txt:4: 'x8' is not a number");
    const char *ragged = "1 2 3\n4 5\n";
    test_write_bytes(test_path("ragged.txt"), ragged, strlen(ragged));
    expect_refusal(im_text_read, test_path("ragged.txt"), IM_EFORMAT, "ragged.txt:2: 2 values");
    const char *infinite = "1 2\n3 inf\n";
    test_write_bytes(test_path("inf.txt"), infinite, strlen(infinite));
    expect_refusal(im_text_read, test_path("inf.txt"), IM_EFORMAT, "inf.txt:2");
    test_write_bytes(test_path("empty.txt"), "# only a header\n", 16);
    expect_refusal(im_text_read, test_path("empty.txt"), IM_EFORMAT, "no data");
}

/* Writes the first `lines` lines of `text` to `name`, then `extra` (may be ""). */
static void write_lines(const char *name, const char *text, int lines, const char *extra)
{
    const char *end = text;
    for (int i = 0; i < lines && *end; ++i)
        end = strchr(end, '\n') + 1;
    FILE *out = fopen(test_path(name), "wb");
    assert_non_null(out);
    fwrite(text, 1, (size_t)(end - text), out);
    fputs(extra, out);
    fclose(out);
}

/* A text matrix whose data disagrees with the grid its header states is refused, naming the header
 * line, what it said and what was found: a 16 x 16 file cut after 11 rows, or with 2 rows added. */
static void text_matrix_must_match_its_header(void **state)
{
    (void)state;
    im_field *f = sample_field(16, 16);
    assert_int_equal(im_text_write(test_path("whole.txt"), f), IM_OK);
    FILE *in = fopen(test_path("whole.txt"), "rb");
    static char text[65536];
    size_t size = fread(text, 1, sizeof text - 1, in);
    fclose(in);
    text[size] = '\0';
    write_lines("cut.txt", text, 3 + 11, ""); /* 3 header lines, then 11 of the 16 rows */
    expect_refusal(im_text_read, test_path("cut.txt"), IM_EFORMAT,
                   "cut.txt:1: the header states 16 columns x 16 rows, but the file has 16 columns x 11 rows");
    write_lines("more.txt", text, 3 + 16,
                "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16\n"
                "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16\n");
    expect_refusal(im_text_read, test_path("more.txt"), IM_EFORMAT,
                   "more.txt:1: the header states 16 columns x 16 rows, but the file has 16 columns x 18 rows");
    const char *narrow = "# Channel: Height\n# grid: 3 columns x 2 rows\n1 2\n3 4\n";
    test_write_bytes(test_path("narrow.txt"), narrow, strlen(narrow));
    expect_refusal(im_text_read, test_path("narrow.txt"), IM_EFORMAT,
                   "narrow.txt:2: the header states 3 columns x 2 rows, but the file has 2 columns x 2 rows");
    im_field *g = NULL;
    assert_int_equal(im_text_read(test_path("whole.txt"), &g), IM_OK);
    assert_fields_equal(f, g);
    im_field_free(g);
    im_field_free(f);
}

/* A copy of the 4 x 4 .gsf `bytes` with value (x=1, y=2) replaced by `value` must be refused. */
static void expect_gsf_value_refused(const unsigned char *bytes, size_t size, float value, const char *name,
                                     const char *phrase)
{
    unsigned char copy[4096];
    memcpy(copy, bytes, size);
    memcpy(copy + size - 16 * sizeof value + (2 * 4 + 1) * sizeof value, &value, sizeof value);
    test_write_bytes(test_path(name), copy, size);
    expect_refusal(im_gsf_read, test_path(name), IM_EFORMAT, phrase);
}

static void bad_gsf_files_are_refused(void **state)
{
    (void)state;
    im_field *f = sample_field(4, 4);
    assert_int_equal(im_gsf_write(test_path("good.gsf"), f), IM_OK);
    FILE *in = fopen(test_path("good.gsf"), "rb");
    unsigned char bytes[4096];
    size_t size = fread(bytes, 1, sizeof bytes, in);
    fclose(in);
    test_write_bytes(test_path("cut.gsf"), bytes, size - 4);
    expect_refusal(im_gsf_read, test_path("cut.gsf"), IM_EFORMAT, "truncated");
    test_write_bytes(test_path("extra.gsf"), bytes, size);
    FILE *append = fopen(test_path("extra.gsf"), "ab");
    fwrite("\0\0\0\0", 1, 4, append);
    fclose(append);
    expect_refusal(im_gsf_read, test_path("extra.gsf"), IM_EFORMAT, "more data");
    static const char no_res[] = "Gwyddion Simple Field 1.0\nXReal = 1\n\0\0\0\0"; /* 40 bytes */
    test_write_bytes(test_path("nores.gsf"), no_res, sizeof no_res - 1);
    expect_refusal(im_gsf_read, test_path("nores.gsf"), IM_EFORMAT, "XRes");
    expect_gsf_value_refused(bytes, size, NAN, "nan.gsf", "value nan at (x=1, y=2)");
    expect_gsf_value_refused(bytes, size, INFINITY, "inf.gsf", "value inf at (x=1, y=2)");
    expect_gsf_value_refused(bytes, size, -INFINITY, "-inf.gsf", "value -inf at (x=1, y=2)");
    im_field_free(f);
}

/* Issue 13: a Gwyddion text export (Width in µm, heights in metres) was read with its heights taken
 * as µm, an h'rms of 6.6e-8 instead of 0.066; the .gsf export of the same data gave 0.066. */
static void gwyddion_text_and_gsf_exports_give_one_slope(void **state)
{
    (void)state;
    im_surface_params params = im_surface_params_default();
    params.nx = params.ny = 64;
    params.lambda_r = 64;
    params.slope_rms = 0.066;
    im_field *surface = NULL, *from_text = NULL, *from_gsf = NULL;
    assert_int_equal(im_surface_generate(&params, &surface), IM_OK);
    const double pixel_metres = 12.8e-6 / 64; /* heights in delta times this are metres */
    FILE *text = fopen(test_path("export.txt"), "w");
    fprintf(text, "# Channel: Height\n# Width: 12.800 \u00b5m\n# Height: 12.800 \u00b5m\n# Value units: m\n");
    for (int iy = 0; iy < 64; ++iy)
        for (int ix = 0; ix < 64; ++ix)
            fprintf(text, "%.17g%c", surface->data[iy * 64 + ix] * pixel_metres, ix == 63 ? '\n' : '\t');
    fclose(text);
    im_field *metres = NULL;
    assert_int_equal(im_field_clone(surface, &metres), IM_OK);
    for (size_t i = 0; i < im_field_count(metres); ++i)
        metres->data[i] *= pixel_metres;
    metres->delta = pixel_metres;
    strcpy(metres->unit, "m");
    assert_int_equal(im_gsf_write(test_path("export.gsf"), metres), IM_OK);
    assert_int_equal(im_surface_read(test_path("export.txt"), &from_text), IM_OK);
    assert_int_equal(im_surface_read(test_path("export.gsf"), &from_gsf), IM_OK);
    double slope_text, slope_gsf;
    assert_int_equal(im_surface_slope_rms(from_text, IM_SLOPE_SPECTRAL, &slope_text), IM_OK);
    assert_int_equal(im_surface_slope_rms(from_gsf, IM_SLOPE_SPECTRAL, &slope_gsf), IM_OK);
    assert_close(slope_text, 0.066, 1e-9);
    assert_close(slope_gsf, 0.066, 1e-6); /* float32 heights */
    assert_close(from_text->delta, 0.2, 1e-15);
    assert_string_equal(from_text->unit, "\u00b5m");
    assert_close(from_gsf->delta, pixel_metres, 1e-20);
    assert_string_equal(from_gsf->unit, "m");
    im_field_free(surface);
    im_field_free(metres);
    im_field_free(from_text);
    im_field_free(from_gsf);
}

/* A 4 x 4 .gsf with the given header lines (after the magic line) and heights 0..15. */
static const char *write_gsf_header(const char *name, const char *lines)
{
    char bytes[1024];
    int length = snprintf(bytes, sizeof bytes, "Gwyddion Simple Field 1.0\n%s", lines);
    int padded = (length / 4 + 1) * 4;
    memset(bytes + length, 0, (size_t)(padded - length));
    for (int i = 0; i < 16; ++i) {
        float value = (float)i;
        memcpy(bytes + padded + 4 * i, &value, 4);
    }
    test_write_bytes(test_path(name), bytes, (size_t)padded + 64);
    return test_path(name);
}

/* Reliability finding 15: "XRes = 16abc" and "XRes = 1.6e1" were read as 16 and 1, XReal <= 0 or NaN
 * fell back to a spacing of 1, and YReal (non-square pixels) and ZUnits were ignored. */
static void gsf_header_values_are_strict(void **state)
{
    (void)state;
    static const struct {
        const char *lines, *phrase;
    } cases[] = {
        {"XRes = 4abc\nYRes = 4\n", "XRes = '4abc': expected a decimal integer"},
        {"XRes = 0.4e1\nYRes = 4\n", "XRes = '0.4e1': expected a decimal integer"},
        {"XRes = 4\nYRes = 4\nXReal = 0\n", "XReal = '0': expected a finite length > 0"},
        {"XRes = 4\nYRes = 4\nXReal = -2\n", "XReal = '-2': expected a finite length > 0"},
        {"XRes = 4\nYRes = 4\nXReal = nan\n", "XReal = 'nan': expected a finite length > 0"},
        {"XRes = 4\nYRes = 4\nXReal = 1\nYReal = 1e999\n", "YReal = '1e999'"},
        {"XRes = 4\nYRes = 4\nXReal = 4e-6\nYReal = 8e-6\nXYUnits = m\n",
         "XReal / XRes and YReal / YRes: non-square pixels, x spacing 1e-06 and y spacing 2e-06 m"},
        {"XRes = 4\nYRes = 4\nXReal = 4\nXYUnits = m\nZUnits = V\n", "ZUnits = 'V': expected a length unit"},
        {"XRes = 4\nYRes = 4\nXReal = 4\nXYUnits = furlong\n", "XYUnits = 'furlong': expected a length unit"},
        {"XRes = 4\nYRes = 4\nZUnits = m\n", "ZUnits = 'm' gives the heights a unit but the lateral spacing"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; ++i)
        expect_refusal(im_gsf_read, write_gsf_header("strict.gsf", cases[i].lines), IM_EFORMAT, cases[i].phrase);
    im_field *g = NULL;
    assert_int_equal(im_gsf_read(write_gsf_header("nm.gsf", "XRes = 4\nYRes = 4\nXReal = 2\nYReal = 2\n"
                                                            "XYUnits = um\nZUnits = nm\n"),
                                 &g),
                     IM_OK);
    assert_close(g->delta, 0.5, 1e-15);
    assert_string_equal(g->unit, "\u00b5m");
    assert_close(g->data[15], 15e-3, 1e-15); /* nm converted to the lateral µm */
    im_field_free(g);
}

/* The text of a small file ("" where there is none), in static storage. */
static const char *file_text(const char *path)
{
    static char text[16384];
    FILE *file = fopen(path, "rb");
    size_t length = file ? fread(text, 1, sizeof text - 1, file) : 0;
    if (file)
        fclose(file);
    text[length] = '\0';
    return text;
}

/* A surface file and its sidecar, one pair (formats.h, im_surface_write_with_sidecar): with a generator, the
 * record `surface --out` writes; without one, a .npy's units replacing that record (none of the generator's
 * is left to be taken for this file's); a text file without a record gets no sidecar, with a source the
 * record naming it. Each file reads back as written. */
static void a_surface_is_written_with_its_sidecar(void **state)
{
    (void)state;
    im_field *f = sample_field(8, 6), *g = NULL;
    snprintf(f->unit, sizeof f->unit, "um");
    im_surface_params p = im_surface_params_default();
    p.nx = 8, p.ny = 6, p.lambda_r = 6, p.lambda_s = 2;
    p.seed = UINT64_MAX; /* beyond JSON's signed integers: the sidecar still reads (its units) */
    const char *npy = test_path("pair.npy"), *npy_sidecar = test_path("pair.npy.json");
    assert_int_equal(im_surface_write_with_sidecar(npy, f, &p, NULL, NULL), IM_OK);
    assert_non_null(strstr(file_text(npy_sidecar), "\"generator\""));
    assert_non_null(strstr(file_text(npy_sidecar), "\"statistics\""));
    assert_non_null(strstr(file_text(npy_sidecar), "\"seed\": 18446744073709551615"));
    assert_int_equal(im_surface_read(npy, &g), IM_OK);
    assert_memory_equal(g->data, f->data, im_field_count(f) * sizeof(double));
    im_field_free(g);
    assert_int_equal(im_surface_write_with_sidecar(npy, f, NULL, NULL, NULL), IM_OK);
    assert_null(strstr(file_text(npy_sidecar), "\"generator\""));
    assert_non_null(strstr(file_text(npy_sidecar), "\"unit\": \"um\""));
    const char *text = test_path("pair.txt"), *text_sidecar = test_path("pair.txt.json");
    assert_int_equal(im_surface_write_with_sidecar(text, f, NULL, NULL, NULL), IM_OK);
    assert_int_equal(access(text_sidecar, F_OK), -1);
    assert_int_equal(im_surface_write_with_sidecar(text, f, NULL, "measured.gsf", NULL), IM_OK);
    assert_non_null(strstr(file_text(text_sidecar), "\"source\": \"measured.gsf\""));
    assert_int_equal(im_surface_read(text, &g), IM_OK);
    assert_int_equal(g->nx * g->ny, f->nx * f->ny);
    im_field_free(g);
    im_field_free(f);
}

/* Unsigned integers in the JSON records (io/json_file.h): written as their decimal, read back from it or from
 * an earlier build's two's complement; other numbers and a string that only begins as the marked ones stay
 * as they are. */
static void json_records_hold_unsigned_integers(void **state)
{
    (void)state;
    json_t *root = json_pack("{s:o, s:o, s:s}", "big", json_unsigned(UINT64_MAX), "small", json_unsigned(7), "text",
                             "\001uint64:x");
    char *text = json_text(root, JSON_COMPACT);
    assert_string_equal(text, "{\"big\":18446744073709551615,\"small\":7,\"text\":\"\\u0001uint64:x\"}");
    json_decref(root);
    free(text);
    root = json_text_load("{\"big\": 18446744073709551615, \"older\": -1, \"real\": 12345678901234567890.5, "
                          "\"exp\": 1e300, \"beyond\": 18446744073709551616, \"name\": \"18446744073709551615\"}",
                          0, NULL);
    assert_non_null(root);
    uint64_t value = 0;
    assert_int_equal(json_unsigned_value(json_object_get(root, "big"), &value), 0);
    assert_true(value == UINT64_MAX);
    assert_int_equal(json_unsigned_value(json_object_get(root, "older"), &value), 0);
    assert_true(value == UINT64_MAX);
    assert_true(json_is_real(json_object_get(root, "real")) && json_is_real(json_object_get(root, "exp")));
    assert_int_equal(json_unsigned_value(json_object_get(root, "beyond"), &value), -1);
    assert_int_equal(json_unsigned_value(json_object_get(root, "name"), &value), -1);
    json_decref(root);
}

/* .npy files state no units: the options set them (and override a file's). */
static void read_options_set_spacing_and_units(void **state)
{
    (void)state;
    im_field *f = sample_field(5, 4), *g = NULL;
    assert_int_equal(im_npy_write(test_path("plain.npy"), f, IM_NPY_FLOAT64), IM_OK);
    im_surface_read_options options = {.set = {.delta_x = 5e-8, .lateral = "m"}};
    im_surface_read_info info;
    assert_int_equal(im_surface_read_with(test_path("plain.npy"), &options, &g, &info), IM_OK);
    assert_close(g->delta, 5e-8, 0.0);
    assert_string_equal(g->unit, "m");
    assert_memory_equal(g->data, f->data, im_field_count(f) * sizeof(double)); /* heights already in m */
    im_field_free(g);
    options = (im_surface_read_options){.set = {.delta_x = 0.1, .lateral = "um", .height = "nm"}};
    assert_int_equal(im_surface_read_with(test_path("plain.npy"), &options, &g, &info), IM_OK);
    assert_close(info.height_factor, 1e-3, 1e-18);
    assert_close(g->data[7], f->data[7] * 1e-3, 1e-15 * fabs(f->data[7]));
    im_field_free(g);
    options = (im_surface_read_options){.set = {.height = "nm"}};
    assert_int_equal(im_surface_read_with(test_path("plain.npy"), &options, &g, &info), IM_EFORMAT);
    assert_non_null(strstr(im_last_error(), "--height-unit = 'nm' gives the heights a unit"));
    im_field_free(f);
}

static void atomic_write_leaves_no_partial_file(void **state)
{
    (void)state;
    const char *path = test_path("atomic.txt");
    assert_int_equal(im_write_file_atomic(path, "first", 5), IM_OK);
    im_atomic_file file;
    assert_int_equal(im_atomic_open(&file, path), IM_OK);
    fputs("half-written", file.stream);
    im_atomic_abort(&file);
    FILE *in = fopen(path, "r");
    char text[16] = "";
    assert_non_null(fgets(text, sizeof text, in));
    fclose(in);
    assert_string_equal(text, "first");
    struct stat info;
    assert_int_not_equal(stat(file.temp_path, &info), 0);
    assert_int_equal(im_write_file_atomic("/nonexistent-dir/x.txt", "x", 1), IM_EIO);
    assert_non_null(strstr(im_last_error(), "/nonexistent-dir/x.txt"));
}

/* Writers never replace what is not a regular file (issue 32): a FIFO, a device node, a symbolic link
 * to one are refused and left as they were; a link to a regular file is written through. */
static void special_files_are_not_replaced(void **state)
{
    (void)state;
    const char *fifo = test_path("fifo");
    assert_int_equal(mkfifo(fifo, 0600), 0);
    assert_int_equal(im_write_file_atomic(fifo, "x", 1), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "is a FIFO, not a regular file"));
    struct stat info;
    assert_int_equal(lstat(fifo, &info), 0);
    assert_true(S_ISFIFO(info.st_mode));
    im_field *h = test_rough_surface(8, 0.1, 1);
    assert_int_equal(im_npy_write("/dev/null", h, IM_NPY_FLOAT64), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "/dev/null is a character device"));
    assert_int_equal(stat("/dev/null", &info), 0);
    assert_true(S_ISCHR(info.st_mode));
    const char *link = test_path("link-to-null");
    assert_int_equal(symlink("/dev/null", link), 0);
    assert_int_equal(im_write_file_atomic(link, "x", 1), IM_EINVAL);
    assert_int_equal(im_write_file_atomic(test_path("plain.txt"), "x", 1), IM_OK);
    im_field_free(h);
}

static void png_round_trip_keeps_pixels(void **state)
{
    (void)state;
    uint8_t pixels[5 * 3 * 3];
    for (size_t i = 0; i < sizeof pixels; ++i)
        pixels[i] = (uint8_t)(i * 17);
    im_png_text text = {"Title", "test"};
    im_png_options options = {&text, 1, 11811.0, 9};
    assert_int_equal(im_png_write(test_path("p.png"), pixels, 5, 3, 3, 15, &options), IM_OK);
    uint8_t *back = NULL;
    int w, h, c;
    assert_int_equal(im_png_read(test_path("p.png"), &back, &w, &h, &c), IM_OK);
    assert_int_equal(w, 5);
    assert_int_equal(h, 3);
    assert_int_equal(c, 3);
    assert_memory_equal(back, pixels, sizeof pixels);
    free(back);
    assert_int_equal(im_png_write(test_path("zero.png"), pixels, 0, 3, 3, 0, NULL), IM_EINVAL);
}

/* Threads writing one file at once: each write has its own temporary file, so every one succeeds
 * and the file ends whole (with PATH.tmp.PID, shared by the threads, renames failed). */
enum { WRITERS = 4, WRITES_EACH = 100 };

static void *write_repeatedly(void *argument)
{
    const char *text = argument;
    long failures = 0;
    for (int i = 0; i < WRITES_EACH; ++i)
        failures += im_write_file_atomic(test_path("shared.txt"), text, strlen(text)) != IM_OK;
    return (void *)failures;
}

static void concurrent_writes_of_one_file_all_succeed(void **state)
{
    (void)state;
    static const char *const TEXTS[WRITERS] = {"first writer\n", "second writer\n", "third writer\n", "fourth\n"};
    pthread_t threads[WRITERS];
    for (int i = 0; i < WRITERS; ++i)
        assert_int_equal(pthread_create(&threads[i], NULL, write_repeatedly, (void *)TEXTS[i]), 0);
    long failures = 0;
    for (int i = 0; i < WRITERS; ++i) {
        void *result;
        pthread_join(threads[i], &result);
        failures += (long)result;
    }
    assert_int_equal(failures, 0);
    FILE *in = fopen(test_path("shared.txt"), "r");
    char text[64] = "";
    assert_non_null(fgets(text, sizeof text, in));
    fclose(in);
    int whole = 0;
    for (int i = 0; i < WRITERS; ++i)
        whole |= strcmp(text, TEXTS[i]) == 0;
    assert_true(whole);
}

static void temporary_names_are_short_and_recognised(void **state)
{
    (void)state;
    char name[256];
    memset(name, 'a', 250);
    memcpy(name + 246, ".npy", 5); /* a legal 250-byte name: the temporary one must fit too */
    char path[4096];
    snprintf(path, sizeof path, "%s", test_path(name));
    assert_int_equal(im_write_file_atomic(path, "x", 1), IM_OK);
    im_atomic_file file;
    assert_int_equal(im_atomic_open(&file, path), IM_OK);
    const char *temporary = strrchr(file.temp_path, '/') + 1;
    assert_true(strlen(temporary) < 40);
    assert_true(im_atomic_is_temporary_name(temporary));
    im_atomic_abort(&file);
    assert_true(im_atomic_is_temporary_name("member_01_3.csv.tmp.4242"));
    assert_true(im_atomic_is_temporary_name("contact.mp4.tmp.17.mp4"));
    assert_false(im_atomic_is_temporary_name("notes.tmp.txt"));
    assert_false(im_atomic_is_temporary_name("force_0001.npy"));
}

static void read_file(const char *path, char *text, size_t size)
{
    FILE *in = fopen(path, "rb");
    assert_non_null(in);
    size_t n = fread(text, 1, size - 1, in);
    text[n] = '\0';
    fclose(in);
}

static void outputs_never_replace_inputs(void **state)
{
    (void)state;
    char input[4096], sidecar[4200], other_name[4200], text[64];
    snprintf(input, sizeof input, "%s", test_path("guarded.txt"));
    snprintf(sidecar, sizeof sidecar, "%s.json", input);
    assert_int_equal(im_write_file_atomic(input, "input\n", 6), IM_OK);
    assert_int_equal(im_output_protect(input), IM_OK);
    snprintf(other_name, sizeof other_name, "%s/./guarded.txt", test_temp_dir());
    assert_int_equal(im_write_file_atomic(other_name, "output\n", 7), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "would overwrite the input file"));
    assert_int_equal(im_write_file_atomic(sidecar, "{}\n", 3), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "the sidecar of the input file"));
    char hard_link[4200];
    snprintf(hard_link, sizeof hard_link, "%s", test_path("guarded-link.txt"));
    unlink(hard_link);
    assert_int_equal(link(input, hard_link), 0);
    assert_int_equal(im_write_file_atomic(hard_link, "output\n", 7), IM_EINVAL);
    read_file(input, text, sizeof text);
    assert_string_equal(text, "input\n");
    im_output_protect_reset();
    assert_int_equal(im_write_file_atomic(other_name, "output\n", 7), IM_OK);
}

static void a_file_of_another_kind_is_not_replaced(void **state)
{
    (void)state;
    const char *scene = test_path("kind.ini"), *png = test_path("kind.png");
    assert_int_equal(im_write_file_atomic(scene, "# a scene\n[scene]\nname = x\n", 27), IM_OK);
    uint8_t pixels[3] = {1, 2, 3};
    assert_int_equal(im_png_write(scene, pixels, 1, 1, 3, 3, NULL), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "holds an INI file (a scene), not a PNG image"));
    char text[64];
    read_file(scene, text, sizeof text);
    assert_string_equal(text, "# a scene\n[scene]\nname = x\n");
    assert_int_equal(im_png_write(png, pixels, 1, 1, 3, 3, NULL), IM_OK);
    assert_int_equal(im_png_write(png, pixels, 1, 1, 3, 3, NULL), IM_OK); /* same kind: replaced */
    assert_int_equal(im_write_file_atomic(png, "text\n", 5), IM_EINVAL);
    enum im_file_kind kind;
    assert_int_equal(im_file_kind_of(png, &kind), IM_OK);
    assert_int_equal(kind, IM_KIND_PNG);
    assert_int_equal(im_file_kind_of("/dev/null", &kind), IM_EINVAL);
    assert_int_equal(im_file_kind_of_bytes("(fftw-3.3.10 fftw_wisdom", 24), IM_KIND_WISDOM);
    assert_int_equal(im_file_kind_of_bytes("\x93NUMPY\x01\x00", 8), IM_KIND_NPY);
    assert_int_equal(im_file_kind_of_bytes("q,c_iso,modes\n1,2,3\n", 20), IM_KIND_TEXT);
}

static void paths_that_are_not_utf8_are_escaped(void **state)
{
    (void)state;
    char out[256];
    assert_int_equal(im_path_utf8("d/\xc3\xa9t\xc3\xa9/s.npy", out, sizeof out), 0);
    assert_string_equal(out, "d/\xc3\xa9t\xc3\xa9/s.npy");
    assert_int_equal(im_path_utf8("d/\xff\xfeutf8\\x/s.npy", out, sizeof out), 1);
    assert_string_equal(out, "d/\\xff\\xfeutf8\\\\x/s.npy");
    assert_int_equal(im_path_utf8("\xc0\xaf", out, sizeof out), 1); /* an overlong '/' */
    assert_string_equal(out, "\\xc0\\xaf");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(npy_float64_round_trip_is_exact),
        cmocka_unit_test(npy_float32_round_trip_is_exact_in_float),
        cmocka_unit_test(text_and_gsf_round_trips),
        cmocka_unit_test(bad_npy_files_are_refused),
        cmocka_unit_test(npy_of_any_type_is_converted),
        cmocka_unit_test(sdf_files_round_trip_and_refuse),
        cmocka_unit_test(netcdf_round_trip_and_refusals),
        cmocka_unit_test(netcdf_unit_attributes_are_read_and_written),
        cmocka_unit_test(x3p_round_trip_and_refusals),
        cmocka_unit_test(x3p_checksums_are_checked),
        cmocka_unit_test(memory_probe_reads_the_machine),
        cmocka_unit_test(memory_limit_set_by_the_caller),
        cmocka_unit_test(bad_text_matrices_name_the_line),
        cmocka_unit_test(text_matrix_must_match_its_header),
        cmocka_unit_test(bad_gsf_files_are_refused),
        cmocka_unit_test(gwyddion_text_and_gsf_exports_give_one_slope),
        cmocka_unit_test(gsf_header_values_are_strict),
        cmocka_unit_test(read_options_set_spacing_and_units),
        cmocka_unit_test(atomic_write_leaves_no_partial_file),
        cmocka_unit_test(special_files_are_not_replaced),
        cmocka_unit_test(png_round_trip_keeps_pixels),
        cmocka_unit_test(concurrent_writes_of_one_file_all_succeed),
        cmocka_unit_test(temporary_names_are_short_and_recognised),
        cmocka_unit_test(outputs_never_replace_inputs),
        cmocka_unit_test(a_file_of_another_kind_is_not_replaced),
        cmocka_unit_test(paths_that_are_not_utf8_are_escaped),
        cmocka_unit_test(non_finite_heights_are_not_written),
        cmocka_unit_test(missing_points_are_written_where_they_can_be_read_back),
        cmocka_unit_test(a_height_alone_states_the_spacing),
        cmocka_unit_test(a_surface_is_written_with_its_sidecar),
        cmocka_unit_test(json_records_hold_unsigned_integers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
