/* Files as other programs write them (issue 25, docs/surfaces.md): variants of a format that real
 * writers produce and that were misread or refused, each from a real file in tests/data/instruments/
 * and from edited copies of it.
 * - x3p from SurfaceTopography: md5checksum.hex holds the MD5 of bindata/data.bin, not main.xml's.
 * - x3p with a ValidPointsLink (derived from a MountainsMap file): ISO 5436-2's bit array of
 *   valid points; an invalid point is a missing one.
 * - sdf from Gwyddion 2.62: version "aBCR-0.0", header keys NumDataSet and NanPresent. */
#include "support.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zip.h>

/* tests/data/instruments/name in the source tree (IM_SOURCE_DIR), in a static buffer. */
static const char *instrument_file(const char *name)
{
    static char path[4096];
    const char *source = getenv("IM_SOURCE_DIR");
    assert_non_null(source);
    snprintf(path, sizeof path, "%s/tests/data/instruments/%s", source, name);
    return path;
}

/* A copy of the instrument file `name` in the test directory as `copy`; its path. */
static const char *copied(const char *name, const char *copy)
{
    FILE *in = fopen(instrument_file(name), "rb");
    assert_non_null(in);
    const char *path = test_path(copy);
    FILE *out = fopen(path, "wb");
    assert_non_null(out);
    char buffer[65536];
    for (size_t got; (got = fread(buffer, 1, sizeof buffer, in)) > 0;)
        assert_int_equal(fwrite(buffer, 1, got, out), got);
    fclose(in);
    assert_int_equal(fclose(out), 0);
    return path;
}

/* The bytes of an archive's entry (malloc'ed, with room for a terminating NUL) and their count. */
static uint8_t *entry_bytes(const char *path, const char *entry, size_t *size)
{
    int error;
    zip_t *archive = zip_open(path, ZIP_RDONLY, &error);
    assert_non_null(archive);
    zip_stat_t info;
    assert_int_equal(zip_stat(archive, entry, 0, &info), 0);
    uint8_t *bytes = malloc(info.size + 1);
    zip_file_t *file = zip_fopen(archive, entry, 0);
    assert_true(bytes && file);
    assert_int_equal(zip_fread(file, bytes, info.size), (zip_int64_t)info.size);
    zip_fclose(file);
    zip_discard(archive);
    *size = (size_t)info.size;
    return bytes;
}

/* Replaces (or adds) an archive's entry with size bytes (copied). */
static void replace_entry(const char *path, const char *entry, const void *bytes, size_t size)
{
    int error;
    zip_t *archive = zip_open(path, 0, &error);
    assert_non_null(archive);
    void *copy = size ? malloc(size) : NULL; /* libzip frees a buffer it is given, but not an empty one */
    assert_true(copy || !size);
    if (copy)
        memcpy(copy, bytes, size);
    zip_source_t *source = zip_source_buffer(archive, copy, size, copy != NULL);
    assert_non_null(source);
    assert_true(zip_file_add(archive, entry, source, ZIP_FL_OVERWRITE) >= 0);
    assert_int_equal(zip_close(archive), 0);
}

static void replace_text_entry(const char *path, const char *entry, const char *text)
{
    replace_entry(path, entry, text, strlen(text));
}

/* Replaces the one occurrence of `old` in a text entry by `new`. */
static void edit_entry(const char *path, const char *entry, const char *old, const char *new)
{
    size_t size = 0;
    char *text = (char *)entry_bytes(path, entry, &size);
    text[size] = '\0';
    char *at = strstr(text, old);
    assert_non_null(at);
    size_t edited_size = size - strlen(old) + strlen(new);
    char *edited = malloc(edited_size + 1);
    assert_non_null(edited);
    snprintf(edited, edited_size + 1, "%.*s%s%s", (int)(at - text), text, new, at + strlen(old));
    replace_text_entry(path, entry, edited);
    free(edited);
    free(text);
}

/* Reads path keeping its missing points (NaN), as field_values does; the test fails on a refusal. */
static im_field *read_keeping_missing_points(const char *path)
{
    im_surface_read_options options = {.field_values = 1};
    im_field *field = NULL;
    if (im_surface_read_with(path, &options, &field, NULL) != IM_OK)
        fail_msg("%s", im_last_error());
    return field;
}

/* reader refuses path with IM_EFORMAT and a message naming the path and holding `phrase`. */
static void expect_refusal(int (*reader)(const char *, im_field **), const char *path, const char *phrase)
{
    im_field *field = NULL;
    int status = reader(path, &field);
    if (status != IM_EFORMAT || !strstr(im_last_error(), phrase) || !strstr(im_last_error(), path))
        fail_msg("%s: status %d, message '%s': expected IM_EFORMAT and '%s'", path, status, im_last_error(), phrase);
    assert_null(field);
}

/* sqrt(<(h - mean)^2>) over the finite values, and their count. */
static double finite_rms(const im_field *field, size_t *finite)
{
    size_t count = im_field_count(field), n = 0;
    double sum = 0.0, squares = 0.0;
    for (size_t i = 0; i < count; ++i)
        if (isfinite(field->data[i]))
            sum += field->data[i], ++n;
    double mean = sum / (double)n;
    for (size_t i = 0; i < count; ++i)
        if (isfinite(field->data[i]))
            squares += (field->data[i] - mean) * (field->data[i] - mean);
    *finite = n;
    return sqrt(squares / (double)n);
}

/* ---- x3p: md5checksum.hex names the entry whose MD5 it holds ---- */

/* From md5sum of the entries of surfacetopography-written.x3p. */
static const char ST_MAIN_MD5[] = "8ca9a93db8a155e03a00badd8db72697";
static const char ST_DATA_MD5[] = "BC50BECEDF300696C0ACBBB7FCB4534A";

/* SurfaceTopography writes "<MD5 of bindata/data.bin> *bindata/data.bin" (Gwyddion and SurfaceTopography
 * read the file); it was refused as damaged, its line taken for main.xml's MD5. Values from Python's
 * struct over data.bin. */
static void surfacetopography_x3p_is_read(void **state)
{
    (void)state;
    im_field *field = NULL;
    if (im_x3p_read(instrument_file("surfacetopography-written.x3p"), &field) != IM_OK)
        fail_msg("%s", im_last_error());
    assert_int_equal(field->nx, 96);
    assert_int_equal(field->ny, 64);
    assert_true(field->delta == 5e-8);
    assert_string_equal(field->unit, "m");
    assert_true(field->data[0] == -1.2570293491525695e-08);
    assert_true(field->data[96] == -2.2203571462119322e-08);
    size_t finite = 0;
    assert_close(finite_rms(field, &finite), 1.813315026308279e-08, 1e-20);
    assert_int_equal(finite, 96 * 64);
    im_field_free(field);
}

/* A byte of the named entry changed (and the zip rewritten, so that its CRC-32 is right): the line's
 * MD5 catches it before the data are read. */
static void surfacetopography_x3p_with_damaged_data_is_refused(void **state)
{
    (void)state;
    const char *path = copied("surfacetopography-written.x3p", "st-damaged.x3p");
    size_t size = 0;
    uint8_t *data = entry_bytes(path, "bindata/data.bin", &size);
    data[size / 2] ^= 0x10;
    replace_entry(path, "bindata/data.bin", data, size);
    free(data);
    expect_refusal(im_x3p_read, path, "bindata/data.bin: MD5 ");
    expect_refusal(im_x3p_read, path,
                   "but md5checksum.hex states BC50BECEDF300696C0ACBBB7FCB4534A: the file is damaged");
}

/* Each line of md5checksum.hex (md5sum's binary '*' or text mode, LF or CRLF) is checked against the
 * entry it names, main.xml's bytes when it names none. */
static void checksum_lines_are_checked_against_their_entries(void **state)
{
    (void)state;
    char text[256];
    const char *path = copied("surfacetopography-written.x3p", "st-lines.x3p");
    const char *accepted[] = {"%s *main.xml\n", "%s\n", "%s", "%s  main.xml\r\n"};
    for (size_t i = 0; i < sizeof accepted / sizeof *accepted; ++i) {
        snprintf(text, sizeof text, accepted[i], ST_MAIN_MD5);
        replace_text_entry(path, "md5checksum.hex", text);
        im_field *field = NULL;
        if (im_x3p_read(path, &field) != IM_OK)
            fail_msg("md5checksum.hex '%s': %s", text, im_last_error());
        im_field_free(field);
    }
    snprintf(text, sizeof text, "%s *main.xml\r\n%s  bindata/data.bin\r\n", ST_MAIN_MD5, ST_DATA_MD5);
    replace_text_entry(path, "md5checksum.hex", text);
    im_field *field = NULL;
    if (im_x3p_read(path, &field) != IM_OK)
        fail_msg("two lines: %s", im_last_error());
    im_field_free(field);

    snprintf(text, sizeof text, "%s *main.xml\n0123456789abcdef0123456789abcdef *bindata/data.bin\n", ST_MAIN_MD5);
    replace_text_entry(path, "md5checksum.hex", text);
    expect_refusal(im_x3p_read, path,
                   "bindata/data.bin: MD5 bc50becedf300696c0acbbb7fcb4534a, but md5checksum.hex "
                   "states 0123456789abcdef0123456789abcdef");
    replace_text_entry(path, "md5checksum.hex", "0123456789abcdef0123456789abcdef\n");
    expect_refusal(im_x3p_read, path, "main.xml: MD5 8ca9a93db8a155e03a00badd8db72697, but md5checksum.hex");
    snprintf(text, sizeof text, "%s *bindata/other.bin\n", ST_DATA_MD5);
    replace_text_entry(path, "md5checksum.hex", text);
    expect_refusal(im_x3p_read, path, "md5checksum.hex's entry 'bindata/other.bin' is not in the archive");
}

/* ---- x3p: ValidPointsLink ---- */

/* bindata/valid.bin holds 5000 bytes, a bit per point of the 200 x 200 grid; 400 are 0. Those points
 * hold 0 in data.bin and were read as heights (Offset, -3.7e-8 m): h_rms 9.91056e-08 over all points,
 * 9.96049e-08 over the valid ones (Python over the entries: bits least significant first). */
static void invalid_points_are_missing_points(void **state)
{
    (void)state;
    const char *path = instrument_file("x3p-2-crop200-L-validpoints.x3p");
    im_field *field = NULL;
    im_surface_read_options fill_off = {0};
    assert_int_equal(im_surface_read_with(path, &fill_off, &field, NULL), IM_EFORMAT);
    assert_null(field);
    if (!strstr(im_last_error(), "value nan at (x=108, y=0): a missing point"))
        fail_msg("expected the first invalid point (x=108, y=0) refused: %s", im_last_error());

    field = read_keeping_missing_points(path);
    size_t finite = 0;
    assert_close(finite_rms(field, &finite), 9.960489911416533e-08, 1e-20);
    assert_int_equal(finite, 200 * 200 - 400);
    assert_true(isnan(field->data[108]) && field->data[0] == 6.579781341994847e-08);
    im_field_free(field);

    im_surface_read_options fill_on = {.fill = 1};
    im_surface_read_info info;
    assert_int_equal(im_surface_read_with(path, &fill_on, &field, &info), IM_OK);
    assert_int_equal(info.filled, 400);
    im_field_free(field);
}

/* The bits of a 3 x 2 grid from an edited copy: least significant first, 0 invalid, and the two bits
 * past the sixth point padding, whatever they hold. */
static void valid_point_bits_are_least_significant_first(void **state)
{
    (void)state;
    const char *path = copied("surfacetopography-written.x3p", "bits.x3p");
    edit_entry(path, "main.xml", "<SizeX>96</SizeX>", "<SizeX>3</SizeX>");
    edit_entry(path, "main.xml", "<SizeY>64</SizeY>", "<SizeY>2</SizeY>");
    edit_entry(path, "main.xml", "<MD5ChecksumPointData>BC50BECEDF300696C0ACBBB7FCB4534A</MD5ChecksumPointData>",
               "<ValidPointsLink>bindata/valid.bin</ValidPointsLink>");
    replace_text_entry(path, "md5checksum.hex", "");
    const double heights[6] = {1e-9, 2e-9, 3e-9, 4e-9, 5e-9, 6e-9}; /* float64 as the host stores it: little-endian */
    replace_entry(path, "bindata/data.bin", heights, sizeof heights);
    const uint8_t masks[2] = {0x2D, 0xED}; /* 0b00101101 and 0b11101101: points 1 and 4 invalid */
    for (int m = 0; m < 2; ++m) {
        replace_entry(path, "bindata/valid.bin", &masks[m], 1);
        im_field *field = read_keeping_missing_points(path);
        for (int i = 0; i < 6; ++i)
            if (i == 1 || i == 4 ? !isnan(field->data[i]) : field->data[i] != heights[i])
                fail_msg("mask %#x, point %d: %g", masks[m], i, field->data[i]);
        im_field_free(field);
    }
}

/* valid.bin must hold exactly a bit per point, match its MD5ChecksumValidPoints, and be there. */
static void damaged_valid_points_are_refused(void **state)
{
    (void)state;
    const char *path = copied("x3p-2-crop200-L-validpoints.x3p", "valid-damaged.x3p");
    size_t size = 0;
    uint8_t *bits = entry_bytes(path, "bindata/valid.bin", &size);
    assert_int_equal(size, 5000);
    replace_entry(path, "bindata/valid.bin", bits, size - 1);
    expect_refusal(im_x3p_read, path,
                   "bindata/valid.bin holds 4999 bytes, SizeX x SizeY = 200 x 200 points of a "
                   "bit each need 5000");
    bits[0] ^= 0x01;
    replace_entry(path, "bindata/valid.bin", bits, size);
    expect_refusal(im_x3p_read, path, "bindata/valid.bin: MD5 ");
    expect_refusal(im_x3p_read, path,
                   "but Record3/DataLink/MD5ChecksumValidPoints states "
                   "5C4E6385CAC7F188CBF4D7E00B1C4C19: the file is damaged");
    free(bits);
    int error;
    zip_t *archive = zip_open(path, 0, &error);
    assert_non_null(archive);
    assert_int_equal(zip_delete(archive, (zip_uint64_t)zip_name_locate(archive, "bindata/valid.bin", 0)), 0);
    assert_int_equal(zip_close(archive), 0);
    expect_refusal(im_x3p_read, path, "ValidPointsLink 'bindata/valid.bin' is not in the archive");
}

/* ---- sdf: Gwyddion's version and keys ---- */

/* Gwyddion 2.62's export of SurfaceTopography's mi-1.mi was refused at its version, aBCR-0.0. Its
 * .gsf export reads the same (docs/surfaces.md); values from Python over the file's text. */
static void gwyddion_sdf_is_read(void **state)
{
    (void)state;
    im_field *field = NULL;
    if (im_sdf_read(instrument_file("mi-1-mi-gwyddion.sdf"), &field) != IM_OK)
        fail_msg("%s", im_last_error());
    assert_int_equal(field->nx, 256);
    assert_int_equal(field->ny, 256);
    assert_true(field->delta == 7.8125e-08);
    assert_string_equal(field->unit, "m");
    assert_true(field->data[0] == -4.9869e-07 && field->data[256] == -4.97804e-07);
    size_t finite = 0;
    assert_close(finite_rms(field, &finite), 3.3215426341495554e-08, 1e-20);
    im_field_free(field);
}

/* A 2 x 2 ASCII file as Gwyddion writes it, with these NumDataSet and NanPresent values and third
 * value; its path. */
static const char *gwyddion_ascii_sdf(const char *name, const char *data_sets, const char *nan_present,
                                      const char *third)
{
    char text[512];
    int length = snprintf(text, sizeof text,
                          "aBCR-0.0\nManufacID   = Gwyddion\nNumPoints   = 2\nNumProfiles = 2\n"
                          "Xscale      = 1.000000e-06\nYscale      = 1.000000e-06\nZscale      = 1.000000e-09\n"
                          "Zresolution = -1\nCompression = 0\nDataType    = 3\nCheckType   = 0\n"
                          "NumDataSet  = %s\nNanPresent  = %s\n*\n1\n2\n%s\n4\n",
                          data_sets, nan_present, third);
    const char *path = test_path(name);
    test_write_bytes(path, text, (size_t)length);
    return path;
}

/* NumDataSet must be 1 (a file of more data sets is refused naming it), NanPresent 0 or 1. */
static void gwyddion_sdf_keys_are_checked(void **state)
{
    (void)state;
    im_field *field = NULL;
    assert_int_equal(im_sdf_read(gwyddion_ascii_sdf("one.sdf", "1", "0", "3"), &field), IM_OK);
    assert_close(field->data[2], 3e-9, 1e-24);
    assert_true(field->delta == 1e-6);
    im_field_free(field);
    field = read_keeping_missing_points(gwyddion_ascii_sdf("nan.sdf", "1", "1", "BAD"));
    assert_true(isnan(field->data[2]));
    assert_close(field->data[3], 4e-9, 1e-24);
    im_field_free(field);
    expect_refusal(im_sdf_read, gwyddion_ascii_sdf("two.sdf", "2", "0", "3"),
                   "NumDataSet = 2: only files of one data set (1) are read");
    expect_refusal(im_sdf_read, gwyddion_ascii_sdf("none.sdf", "0", "0", "3"), "NumDataSet = 0");
    expect_refusal(im_sdf_read, gwyddion_ascii_sdf("word.sdf", "one", "0", "3"),
                   "NumDataSet = 'one': expected a decimal integer");
    expect_refusal(im_sdf_read, gwyddion_ascii_sdf("flag.sdf", "1", "2", "3"), "NanPresent = 2: expected 0 or 1");
}

/* The binary form's version "bBCR-0.0" is read; versions beyond the known ones are still refused. */
static void gwyddion_sdf_versions_are_read(void **state)
{
    (void)state;
    im_field *written = NULL, *read = NULL;
    assert_int_equal(im_field_create(3, 2, 2e-6, &written), IM_OK);
    snprintf(written->unit, sizeof written->unit, "m");
    for (int i = 0; i < 6; ++i)
        written->data[i] = 1e-9 * (i - 2.5);
    const char *path = test_path("binary.sdf");
    assert_int_equal(im_sdf_write(path, written), IM_OK);
    FILE *file = fopen(path, "r+b");
    assert_non_null(file);
    assert_int_equal(fwrite("bBCR-0.0", 1, 8, file), 8);
    assert_int_equal(fclose(file), 0);
    if (im_sdf_read(path, &read) != IM_OK)
        fail_msg("%s", im_last_error());
    assert_memory_equal(read->data, written->data, sizeof(double) * 6);
    assert_true(read->delta == 2e-6);
    im_field_free(read);
    im_field_free(written);

    path = gwyddion_ascii_sdf("version.sdf", "1", "0", "3");
    file = fopen(path, "r+b");
    assert_non_null(file);
    assert_int_equal(fwrite("aBCR-0.1", 1, 8, file), 8);
    assert_int_equal(fclose(file), 0);
    expect_refusal(im_sdf_read, path, "not an ISO 25178-71 surface data file");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(surfacetopography_x3p_is_read),
        cmocka_unit_test(surfacetopography_x3p_with_damaged_data_is_refused),
        cmocka_unit_test(checksum_lines_are_checked_against_their_entries),
        cmocka_unit_test(invalid_points_are_missing_points),
        cmocka_unit_test(valid_point_bits_are_least_significant_first),
        cmocka_unit_test(damaged_valid_points_are_refused),
        cmocka_unit_test(gwyddion_sdf_is_read),
        cmocka_unit_test(gwyddion_sdf_keys_are_checked),
        cmocka_unit_test(gwyddion_sdf_versions_are_read),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
