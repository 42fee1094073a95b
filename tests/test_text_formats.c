/* What a text surface file is: a matrix, x y z points on a grid, or a line scan (refused); the
 * headers of Gwyddion (English and German) and Wyko/Vision; decimal commas. Each case is one that
 * SurfaceTopography's example files showed read wrong or refused (issue 25, real-data.md). */
#include "support.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/status.h"

#include <math.h>
#include <string.h>
#include <zlib.h>

static im_field *read_text(const char *name, const char *text, im_surface_read_info *info)
{
    test_write_bytes(test_path(name), text, strlen(text));
    im_field *f = NULL;
    int status = im_surface_read_with(test_path(name), NULL, &f, info);
    if (status != IM_OK)
        fail_msg("%s: %s", name, im_last_error());
    return f;
}

/* A file already written, read with its info. */
static im_field *read_text_file(const char *name, im_surface_read_info *info)
{
    im_field *f = NULL;
    if (im_surface_read_with(test_path(name), NULL, &f, info) != IM_OK)
        fail_msg("%s: %s", name, im_last_error());
    return f;
}

static void expect_text_refused(const char *name, const char *text, const char *phrase)
{
    test_write_bytes(test_path(name), text, strlen(text));
    im_field *f = NULL;
    int status = im_surface_read(test_path(name), &f);
    if (status != IM_EFORMAT || !strstr(im_last_error(), phrase))
        fail_msg("%s: status %d, message '%s' (expected to contain '%s')", name, status, im_last_error(), phrase);
    assert_null(f);
    assert_non_null(strstr(im_last_error(), name));
}

static void line_scans_are_refused_as_such(void **state)
{
    (void)state;
    expect_text_refused("heights.txt", "1\n2\n3\n4\n5\n", "1 column x 5 rows of numbers: a line scan");
    expect_text_refused("xz.txt", "0 1.5\n1 2.5\n2 3.5\n3 4.5\n", "2 columns x 4 rows of numbers: a line scan");
    expect_text_refused("row.txt", "1 2 3 4 5 6\n", "6 columns x 1 row of numbers: a line scan");
    expect_text_refused("two_rows.csv", "1,2,3,4\n5,6,7,8\n", "4 columns x 2 rows");
}

/* Points in scrambled order give the matrix of the same heights; the steps are the spacing. */
static void xyz_points_on_a_grid_are_a_map(void **state)
{
    (void)state;
    const char *points = "0.5 0 3\n0 0 1\n1.0 0 5\n0 0.5 2\n0.5 0.5 4\n1.0 0.5 6\n0 1 7\n1.0 1 9\n0.5 1 8\n";
    im_field *f = read_text("points.txt", points, NULL);
    assert_int_equal(f->nx, 3);
    assert_int_equal(f->ny, 3);
    assert_close(f->delta, 0.5, 1e-15);
    const double expected[] = {1, 3, 5, 2, 4, 6, 7, 8, 9};
    for (int k = 0; k < 9; ++k)
        assert_close(f->data[k], expected[k], 0.0);
    im_field_free(f);
    expect_text_refused("repeat.txt", "0 0 1\n1 0 2\n2 0 3\n0 1 4\n1 1 5\n2 1 6\n0 2 7\n0 2 8\n2 2 9\n",
                        "point 8 repeats (x, y) = (0, 2)");
    expect_text_refused("profile.txt", "0 0 1\n1 0 2\n2 0 3\n0 1 4\n1 1 5\n2 1 6\n", "on a 3 x 2 grid: a line scan");
    /* a NaN position sorted into the middle of the x values placed a point far off the grid (SIGSEGV) */
    expect_text_refused("nan_x.txt", "0 0 1\n0 1 4\nnan 0 2\n2 0 3\n2 1 5\n2 1 6\n",
                        "point 3 has (x, y) = (nan, 0): expected finite positions");
    expect_text_refused("uneven.txt", "0 0 1\n1 0 2\n3 0 3\n0 1 4\n1 1 5\n3 1 6\n", "x or y not equally spaced");
    expect_text_refused("scattered.txt", "0 0 1\n0.3 0.7 2\n0.9 0.1 3\n0.2 0.4 4\n", "not a regular grid");
}

/* "1,5" is one and a half, never the two numbers 1 and 5; commas between values stay separators. */
static void decimal_commas_are_read_as_decimals(void **state)
{
    (void)state;
    im_field *f = read_text("komma.txt", "1,5\t-2,25\t3\t4,125\n0,5 1 2 3\n7,5;8;9;10\n", NULL);
    assert_int_equal(f->nx, 4);
    assert_int_equal(f->ny, 3);
    const double expected[] = {1.5, -2.25, 3, 4.125, 0.5, 1, 2, 3, 7.5, 8, 9, 10};
    for (int k = 0; k < 12; ++k)
        assert_close(f->data[k], expected[k], 0.0);
    im_field_free(f);
    f = read_text("plain.csv", "1,5,2,3\n0.5,1,2,3\n4,5,6,7\n", NULL);
    assert_int_equal(f->nx, 4);
    assert_close(f->data[1], 5.0, 0.0);
    im_field_free(f);
}

/* A German Gwyddion export, Height in nm beside Width in µm: one lateral unit, square pixels. */
static void gwyddion_headers_in_german_and_two_prefixes(void **state)
{
    (void)state;
    const char *german = "# Kanal: Topographie\n# Breite: 3 \u00b5m\n# H\u00f6he: 3000 nm\n# Value units: nm\n"
                         "1 2 3\n4 5 6\n7 8 9\n";
    im_field *f = read_text("deutsch.txt", german, NULL);
    assert_close(f->delta, 1.0, 1e-15);
    assert_string_equal(f->unit, "\u00b5m");
    assert_close(f->data[8], 9e-3, 2e-18); /* 9 nm in µm, to a rounding */
    im_field_free(f);
    expect_text_refused("odd_units.txt", "# Width: 3 um\n# Height: 3 furlongs\n1 2 3\n4 5 6\n7 8 9\n",
                        "expected two length units");
}

/* Wyko/Vision ASCII: values times the height conversion factor are metres; pixel size the spacing. */
static void vision_headers_convert_the_values(void **state)
{
    (void)state;
    const char *vision = "h=3 w=4\npixel size=3.69862e-007 m\ndata unit=rad\n"
                         "height conversion factor (-> m)=6.30079e-008\n1 2 3 4\n5 6 7 8\n9 10 11 -12\n";
    im_surface_read_info info;
    im_field *f = read_text("vision.txt", vision, &info);
    assert_int_equal(f->nx, 4);
    assert_int_equal(f->ny, 3);
    assert_close(f->delta, 3.69862e-7, 1e-21);
    assert_string_equal(f->unit, "m");
    assert_close(f->data[11], -12 * 6.30079e-8, 1e-22);
    assert_non_null(strstr(info.conversion, "height conversion factor"));
    im_field_free(f);
    expect_text_refused("vision_rows.txt", "h=4 w=4\npixel size=1 um\n1 2 3 4\n5 6 7 8\n9 10 11 12\n",
                        "the header states 4 columns x 4 rows");
    expect_text_refused("vision_phase.txt", "h=3 w=3\npixel size=1 um\ndata unit=rad\n1 2 3\n4 5 6\n7 8 9\n",
                        "data unit = 'rad' is not a length");
    expect_text_refused("vision_key.txt", "h=3 w=3\nwavelength=633 nm\n1 2 3\n4 5 6\n7 8 9\n",
                        "a header line of a kind this reader does not know");
}

/* UTF-16 text (little- and big-endian, by its byte-order mark) is read as the UTF-8 it spells: a
 * matrix under a Gwyddion header in µm, with a character outside the BMP (a surrogate pair) in a comment. */
static void utf16_text_is_decoded(void **state)
{
    (void)state;
    const char *utf8 = "# \xf0\x9d\x91\xa7 map\n# Width: 6 \xc2\xb5m\n1 2 3\n4 5 6\n7 8 9\n";
    for (int big = 0; big <= 1; ++big) {
        char utf16[256] = {big ? '\xfe' : '\xff', big ? '\xff' : '\xfe'};
        size_t length = 2;
        static const unsigned short PAIR[2] = {0xd835, 0xdc67}; /* U+1D467 */
        for (const unsigned char *at = (const unsigned char *)utf8; *at; ++at) {
            unsigned unit = *at < 0x80 ? *at : *at == 0xc2 ? (at[1] & 0x3fu) | 0x80u : PAIR[0];
            if (*at == 0xf0) { /* the 4-byte character: its pair */
                utf16[length++] = (char)(big ? PAIR[0] >> 8 : PAIR[0] & 0xff);
                utf16[length++] = (char)(big ? PAIR[0] & 0xff : PAIR[0] >> 8);
                unit = PAIR[1];
                at += 3;
            } else if (*at == 0xc2) {
                ++at;
            }
            utf16[length++] = (char)(big ? unit >> 8 : unit & 0xff);
            utf16[length++] = (char)(big ? unit & 0xff : unit >> 8);
        }
        test_write_bytes(test_path("unicode.txt"), utf16, length);
        im_surface_read_info info;
        im_field *f = read_text_file("unicode.txt", &info);
        assert_int_equal(f->nx, 3);
        assert_int_equal(f->ny, 3);
        assert_close(f->delta, 2.0, 1e-15);
        assert_string_equal(f->unit, "\xc2\xb5m");
        assert_close(f->data[5], 6.0, 0.0);
        assert_non_null(strstr(info.conversion, big ? "UTF-16BE text" : "UTF-16LE text"));
        im_field_free(f);
    }
}

/* UTF-16 that is not text is refused naming the byte: lone surrogates, a NUL, an odd length. */
static void broken_utf16_is_refused_by_offset(void **state)
{
    (void)state;
    static const struct {
        const char *name, *bytes;
        size_t length;
        const char *phrase;
    } CASES[] = {
        {"high.txt",
         "\xff\xfe"
         "1\0"
         "\x00\xd8"
         " \0",
         8, "a lone high surrogate 0xD800 at byte 4"},
        {"low.txt",
         "\xfe\xff"
         "\0"
         "1"
         "\xdc\x00",
         6, "a lone low surrogate 0xDC00 at byte 4"},
        {"nul.txt",
         "\xff\xfe"
         "1\0"
         "\0\0",
         6, "a NUL character (U+0000) at byte 4"},
        {"odd.txt",
         "\xff\xfe"
         "1\0"
         "2",
         5, "UTF-16 text of 5 bytes, an odd number"},
    };
    for (size_t k = 0; k < sizeof CASES / sizeof CASES[0]; ++k) {
        test_write_bytes(test_path(CASES[k].name), CASES[k].bytes, CASES[k].length);
        im_field *f = NULL;
        assert_int_equal(im_text_read(test_path(CASES[k].name), &f), IM_EFORMAT);
        if (!strstr(im_last_error(), CASES[k].phrase) || !strstr(im_last_error(), CASES[k].name))
            fail_msg("%s: '%s' (expected '%s')", CASES[k].name, im_last_error(), CASES[k].phrase);
        assert_null(f);
    }
}

/* Text above the numbers says what they are (issue 25): column names with units in them, a row of
 * units, a count, an index or validity column, a profiler's report; a line scan whatever the
 * separators (commas, semicolons, decimal commas), refused naming the text; text above a matrix, or
 * no numbers at all, refused for what it is. */
static void text_above_a_line_scan_names_it(void **state)
{
    (void)state;
    expect_text_refused("names.csv", "X_(microns),y1\n0.0386,2.10425\n0.0772,2.08494\n0.1158,2.06564\n",
                        "3 rows of numbers under the header row 'X_(microns),y1' (line 1): a line scan (a 1-D "
                        "profile)");
    expect_text_refused(
        "index.csv", "index,x in \xc2\xb5m,y in \xc2\xb5m\n0,-1,2\n1,0,3\n2,1,4\n",
        "3 columns x 3 rows of numbers under the header row 'index,x in \xc2\xb5m,y in \xc2\xb5m' (line 1): "
        "a line scan (a 1-D profile), not a map (positions and heights, beside an index column 'index')");
    expect_text_refused("valid.hfm", "X;Y;valid\r\n[mm];[mm];[1/0]\r\n8.6722;106.6;1\r\n8.6727;106.7;1\r\n",
                        "a row of units '[mm];[mm];[1/0]' (line 2): a line scan (a 1-D profile), not a map "
                        "(positions and "
                        "heights, beside a validity column 'valid')");
    expect_text_refused("units.txt", "\xc2\xb5m \xc2\xb5m\n3\n 1.5,  2.5\n 2.5,  3.5\n 3.5,  4.5\n",
                        "2 columns x 3 rows of numbers under a row of units '\xc2\xb5m \xc2\xb5m' (line 1), a lone "
                        "number, 3 "
                        "(line 2): a line scan");
    expect_text_refused("commas.csv", "x;h\n0,5;1,25\n1,0;2,5\n1,5;3,75\n", "2 columns x 3 rows of numbers under");
    expect_text_refused("dektak.csv",
                        "Scan Parameters\nScan Type,Standard Scan\n\nScan Data\nLateral um,Raw Micrometer,\n"
                        "0.0,-0.00933,,\n0.2,-0.00760,,\n",
                        "under a Bruker Dektak profilometer's CSV export of a stylus "
                        "profile ('Scan Parameters', line 1), the header row 'Lateral um,Raw Micrometer,' (line 5): "
                        "a line scan");
    expect_text_refused("above_matrix.txt", "[nm]\n1 2 3\n4 5 6\n7 8 9\n",
                        "above_matrix.txt:1: '[nm]' is text above 3 columns of numbers");
    expect_text_refused("names_matrix.txt", "some words\n1 2 3\n4 5 6\n7 8 9\n",
                        "names_matrix.txt:1: header row 'some words' of 2 column names");
    expect_text_refused("count_matrix.txt", "3\n1 2 3\n4 5 6\n7 8 9\n",
                        ":1: a lone number, 3, above rows of 3 values");
    expect_text_refused("nonsense.txt", "This is nonsense.\n",
                        "no numbers: 1 line of text (line 1: 'This is nonsense.')");
}

/* gzip-compressed text reads as the text it holds (matrix-4.txt.gz); cut short, it is refused. */
static void gzip_text_is_read_decompressed(void **state)
{
    (void)state;
    const char *text = "h=3 w=4\npixel size=2 um\n1 2 3 4\n5 6 7 8\n9 10 11 12\n";
    gzFile gz = gzopen(test_path("matrix.txt.gz"), "wb");
    assert_non_null(gz);
    assert_int_equal(gzwrite(gz, text, (unsigned)strlen(text)), (int)strlen(text));
    assert_int_equal(gzclose(gz), Z_OK);
    im_surface_read_info info;
    im_field *f = read_text_file("matrix.txt.gz", &info);
    assert_int_equal(f->nx, 4);
    assert_int_equal(f->ny, 3);
    assert_close(f->delta, 2.0, 0.0);
    assert_close(f->data[11], 12.0, 0.0);
    assert_non_null(strstr(info.conversion, "gzip-compressed text"));
    im_field_free(f);
    FILE *in = fopen(test_path("matrix.txt.gz"), "rb");
    char bytes[256];
    size_t size = fread(bytes, 1, sizeof bytes, in);
    fclose(in);
    test_write_bytes(test_path("cut.txt.gz"), bytes, size - 4); /* the length of the trailer cut off */
    assert_int_equal(im_surface_read(test_path("cut.txt.gz"), &f), IM_EFORMAT);
    assert_non_null(strstr(im_last_error(), "the gzip stream ends early or is damaged"));
    assert_null(f);
}

/* --unit on a file that states its unit converts into it (finding D2: the spacing's number was kept
 * and relabelled, slopes off by the ratio); with --delta it restates both, as for a file stating none. */
static void unit_converts_a_stated_unit(void **state)
{
    (void)state;
    const char *text = "# Width: 3 um\n# Value units: um\n1 2 3\n4 5 6\n7 8 9\n";
    test_write_bytes(test_path("stated.txt"), text, strlen(text));
    im_surface_read_options options = {.set = {.lateral = "nm"}};
    im_field *f = NULL;
    assert_int_equal(im_surface_read_with(test_path("stated.txt"), &options, &f, NULL), IM_OK);
    assert_string_equal(f->unit, "nm");
    assert_close(f->delta, 1000.0, 1e-9);
    assert_close(f->data[8], 9000.0, 1e-9); /* the slopes are the file's */
    im_field_free(f);
    im_surface_read_options channel = {.channel = "Height"}; /* one channel: asking for one is a mistake */
    assert_int_equal(im_surface_read_with(test_path("stated.txt"), &channel, &f, NULL), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "channel 'Height' asked of a file read by indentmap's own reader"));
    options.set.delta_x = 2.0;
    assert_int_equal(im_surface_read_with(test_path("stated.txt"), &options, &f, NULL), IM_OK);
    assert_close(f->delta, 2.0, 0.0);
    assert_string_equal(f->unit, "nm");
    assert_close(f->data[8], 9000.0, 1e-9);
    im_field_free(f);
}

/* The points of xyz_points_on_a_grid_are_a_map, as rows under a header row (sep between values). */
static void write_points(const char *name, const char *header_row, const char *sep)
{
    static const double xyz[9][3] = {{0.5, 0, 3}, {0, 0, 1}, {1, 0, 5}, {0, 0.5, 2}, {0.5, 0.5, 4},
                                     {1, 0.5, 6}, {0, 1, 7}, {1, 1, 9}, {0.5, 1, 8}};
    char text[1024];
    size_t used = (size_t)snprintf(text, sizeof text, "%s", header_row);
    for (int k = 0; k < 9; ++k)
        used += (size_t)snprintf(text + used, sizeof text - used, "%g%s%g%s%g\n", xyz[k][0], sep, xyz[k][1], sep,
                                 xyz[k][2]);
    test_write_bytes(test_path(name), text, used);
}

/* The file read in metres, with its units given (lateral, height: "" none) as --unit and --height-unit. */
static im_field *read_in_metres(const char *name, const char *lateral, const char *height)
{
    im_surface_read_options options = {.express_in = "m"};
    snprintf(options.set.lateral, sizeof options.set.lateral, "%s", lateral);
    snprintf(options.set.height, sizeof options.set.height, "%s", height);
    im_field *f = NULL;
    if (im_surface_read_with(test_path(name), &options, &f, NULL) != IM_OK)
        fail_msg("%s: %s", name, im_last_error());
    return f;
}

static void expect_same_field(const im_field *a, const im_field *b)
{
    assert_int_equal(a->nx, b->nx);
    assert_int_equal(a->ny, b->ny);
    assert_string_equal(a->unit, b->unit);
    assert_close(a->delta, b->delta, 1e-12 * b->delta);
    for (int k = 0; k < a->nx * a->ny; ++k)
        assert_close(a->data[k], b->data[k], 1e-12 * fabs(b->data[k]));
}

/* A header row of column names (issue 25): its units are the units given as options, converted (the
 * height alone when only its unit differs); the same numbers without it give the same metres. */
static void header_rows_of_column_names_state_units(void **state)
{
    (void)state;
    static const struct {
        const char *name, *row, *sep, *lateral, *height;
    } cases[] = {
        {"names.txt", "x y z\n", " ", "", ""},
        {"brackets.txt", "x[um] y[um] z[nm]\n", " ", "um", "nm"},
        {"parens.tsv", "X (\u00b5m)\tY (\u00b5m)\tHeight (nm)\r\n", "\t", "um", "nm"},
        {"quoted.csv", "\"x\",\"y\",\"height\"\n", ",", "", ""},
        {"quoted_units.csv", "\"x [mm]\";\"y [mm]\";\"z [mm]\"\n", ";", "mm", "mm"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof *cases; ++c) {
        write_points(cases[c].name, cases[c].row, cases[c].sep);
        write_points("bare.txt", "", cases[c].sep);
        im_field *headed = cases[c].lateral[0] ? read_in_metres(cases[c].name, "", "")
                                               : read_text_file(cases[c].name, NULL);
        im_field *bare = cases[c].lateral[0] ? read_in_metres("bare.txt", cases[c].lateral, cases[c].height)
                                             : read_text_file("bare.txt", NULL);
        expect_same_field(headed, bare);
        im_field_free(headed);
        im_field_free(bare);
    }
    im_surface_read_info info;
    write_points("z_in_nm.txt", "x[um] y[um] z[nm]\n", " ");
    im_field *f = read_text_file("z_in_nm.txt", &info);
    assert_string_equal(f->unit, "\u00b5m");
    assert_close(f->delta, 0.5, 1e-15);    /* x and y as stated */
    assert_close(f->data[8], 9e-3, 1e-17); /* 9 nm in µm */
    assert_close(info.height_factor, 1e-3, 1e-18);
    im_field_free(f);
}

static void bad_header_rows_are_refused_by_line(void **state)
{
    (void)state;
    static const struct {
        const char *name, *text, *phrase;
    } cases[] = {
        {"names_abc.txt", "# points\nx y w\n0 0 1\n",
         ":2: header row names its columns 'x', 'y', 'w': expected three"},
        {"names_order.txt", "y x z\n0 0 1\n", ":1: header row names its columns 'y', 'x', 'z'"},
        {"names_furlong.txt", "x[furlong] y[furlong] z[nm]\n0 0 1\n",
         ":1: header row: column 'x' in 'furlong': "
         "expected a length unit"},
        {"names_partial.txt", "x y z[nm]\n0 0 1\n", ":1: header row states units for 1 of its 3 columns"},
        {"names_xy.txt", "x[um] y[nm] z[nm]\n0 0 1\n", ":1: header row states x in 'um' but y in 'nm'"},
        {"names_open.txt", "x[um y[um] z[nm]\n0 0 1\n", ":1: header row 'x[um y[um] z[nm]': column 1 is not a name"},
        {"names_four.txt", "x y z w\n0 0 1 2\n", ":1: header row 'x y z w' of at least 4 column names"},
        {"names_matrix.txt", "x y z\n1 2 3 4\n5 6 7 8\n9 10 11 12\n",
         ":1: a header row of x, y and height names "
         "above rows of another number of values"},
        {"names_value.txt", "# Value units: um\nx[um] y[um] z[nm]\n0 0 1\n",
         ":2: header row states the height in "
         "'nm' but '# Value units:' in 'um'"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof *cases; ++c)
        expect_text_refused(cases[c].name, cases[c].text, cases[c].phrase);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(line_scans_are_refused_as_such),
        cmocka_unit_test(xyz_points_on_a_grid_are_a_map),
        cmocka_unit_test(decimal_commas_are_read_as_decimals),
        cmocka_unit_test(gwyddion_headers_in_german_and_two_prefixes),
        cmocka_unit_test(vision_headers_convert_the_values),
        cmocka_unit_test(utf16_text_is_decoded),
        cmocka_unit_test(broken_utf16_is_refused_by_offset),
        cmocka_unit_test(text_above_a_line_scan_names_it),
        cmocka_unit_test(gzip_text_is_read_decompressed),
        cmocka_unit_test(unit_converts_a_stated_unit),
        cmocka_unit_test(header_rows_of_column_names_state_units),
        cmocka_unit_test(bad_header_rows_are_refused_by_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
