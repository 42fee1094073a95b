/* Files as other programs write them (issue 25, docs/surfaces.md): the variants of a format that
 * real writers produce beyond what its standard's first reading suggests, each from a real file in
 * tests/data/instruments/ and from edited copies of it.
 * - x3p from SurfaceTopography: md5checksum.hex holds the MD5 of bindata/data.bin, not main.xml's. */
#include "support.h"

#include "indentmap/io.h"
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

/* The bytes of an archive's entry (malloc'ed) and their count. */
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
    void *copy = malloc(size ? size : 1);
    assert_non_null(copy);
    memcpy(copy, bytes, size);
    zip_source_t *source = zip_source_buffer(archive, copy, size, 1);
    assert_non_null(source);
    assert_true(zip_file_add(archive, entry, source, ZIP_FL_OVERWRITE) >= 0);
    assert_int_equal(zip_close(archive), 0);
}

static void replace_text_entry(const char *path, const char *entry, const char *text)
{
    replace_entry(path, entry, text, strlen(text));
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
    expect_refusal(im_x3p_read, path, "bindata/data.bin: MD5 bc50becedf300696c0acbbb7fcb4534a, but md5checksum.hex "
                                      "states 0123456789abcdef0123456789abcdef");
    replace_text_entry(path, "md5checksum.hex", "0123456789abcdef0123456789abcdef\n");
    expect_refusal(im_x3p_read, path, "main.xml: MD5 8ca9a93db8a155e03a00badd8db72697, but md5checksum.hex");
    snprintf(text, sizeof text, "%s *bindata/other.bin\n", ST_DATA_MD5);
    replace_text_entry(path, "md5checksum.hex", text);
    expect_refusal(im_x3p_read, path, "md5checksum.hex's entry 'bindata/other.bin' is not in the archive");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(surfacetopography_x3p_is_read),
        cmocka_unit_test(surfacetopography_x3p_with_damaged_data_is_refused),
        cmocka_unit_test(checksum_lines_are_checked_against_their_entries),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
