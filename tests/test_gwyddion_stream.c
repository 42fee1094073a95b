/* The stream indentmap-gwyddion-read hands the library (src/io/gwyddion.h): what it accepts and what
 * it refuses, naming why, whatever the vendor file behind it put into the header; and the choice of
 * the program. The program itself is run on real files by tests/cli_instrument_files.sh. */
#include "support.h"

#include "indentmap/io.h"
#include "indentmap/status.h"
#include "io/gwyddion.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const char *seed(const char *name)
{
    static char path[4096];
    snprintf(path, sizeof path, "%s/fuzz/corpus/gwyddion/%s", getenv("IM_SOURCE_DIR"), name);
    return path;
}

static void expect_stream_refused(const char *name, const char *phrase)
{
    im_field *f = NULL;
    int status = gwyddion_stream_file_read(seed(name), &f);
    if (status != IM_EFORMAT || !strstr(im_last_error(), phrase))
        fail_msg("%s: status %d, '%s' (expected '%s')", name, status, im_last_error(), phrase);
    assert_null(f);
}

static void a_stream_gives_the_field_with_its_units(void **state)
{
    (void)state;
    im_field *f = NULL;
    assert_int_equal(gwyddion_stream_file_read(seed("valid_heights.bin"), &f), IM_OK);
    assert_int_equal(f->nx, 3);
    assert_close(f->delta, 1e-6, 1e-21);
    assert_string_equal(f->unit, "m");
    assert_close(f->data[8], 8e-9, 0.0);
    im_field_free(f);
    assert_int_equal(gwyddion_stream_file_read(seed("valid_no_units.bin"), &f), IM_OK);
    assert_int_equal(f->nx, 4);
    assert_int_equal(f->ny, 3);
    assert_close(f->delta, 1.0, 0.0);
    assert_string_equal(f->unit, "");
    im_field_free(f);
}

static void a_stream_that_lies_is_refused(void **state)
{
    (void)state;
    expect_stream_refused("masked_point.bin", "value nan at (x=1, y=1): a missing point");
    expect_stream_refused("phase_channel.bin", "channel 2 'Phase' holds values in 'deg', not heights");
    expect_stream_refused("error.bin", "Gwyddion's file modules cannot read it: File is truncated.");
    expect_stream_refused("lying_size.bin", "ended inside the heights (30000 x 30000 claimed");
    expect_stream_refused("short_data.bin", "ended inside the heights (3 x 3 claimed, 40 bytes left)");
    expect_stream_refused("extra_data.bin", "wrote more than the field");
    expect_stream_refused("non_square.bin", "non-square pixels");
}

/* INDENTMAP_GWYDDION_READER names the program; one that cannot be run is no program. */
static void the_program_is_chosen_by_the_environment(void **state)
{
    (void)state;
    setenv("INDENTMAP_GWYDDION_READER", seed("valid_heights.bin"), 1); /* a file, not executable */
    assert_null(im_gwyddion_reader());
    setenv("INDENTMAP_GWYDDION_READER", "/bin/true", 1);
    assert_string_equal(im_gwyddion_reader(), "/bin/true");
    im_field *f = NULL; /* a program that writes nothing: refused, not trusted */
    assert_int_equal(im_surface_read(seed("valid_heights.bin"), &f), IM_EFORMAT);
    assert_non_null(strstr(im_last_error(), "Gwyddion's reader gave no answer"));
    assert_null(f);
    unsetenv("INDENTMAP_GWYDDION_READER");
}

/* A stand-in for the program: a script that writes what `body` says (the seeds through a pipe). */
static const char *fake_reader(const char *name, const char *body)
{
    const char *path = test_path(name);
    char script[8192];
    snprintf(script, sizeof script, "#!/bin/sh\n%s\n", body);
    test_write_bytes(path, script, strlen(script));
    chmod(path, 0700);
    setenv("INDENTMAP_GWYDDION_READER", path, 1);
    return path;
}

static void expect_read_refused(const char *phrase)
{
    im_field *f = NULL;
    int status = im_surface_read(seed("valid_heights.bin"), &f); /* binary, not ours: through the reader */
    if (status != IM_EFORMAT || !strstr(im_last_error(), phrase))
        fail_msg("status %d, '%s' (expected '%s')", status, im_last_error(), phrase);
    assert_null(f);
}

/* Through a pipe the values cannot be counted before they are read: a stream cut short is found
 * by the read; a reader that crashes (a vendor parser on a damaged file) refuses the file. */
static void what_comes_through_the_pipe_is_checked(void **state)
{
    (void)state;
    char body[4200];
    snprintf(body, sizeof body, "cat '%s'", seed("short_data.bin"));
    fake_reader("short.sh", body);
    expect_read_refused("ended inside the heights (9 expected)");
    snprintf(body, sizeof body, "cat '%s'", seed("valid_heights.bin"));
    fake_reader("good.sh", body);
    im_field *f = NULL;
    assert_int_equal(im_surface_read(seed("valid_heights.bin"), &f), IM_OK);
    assert_close(f->data[8], 8e-9, 0.0);
    im_field_free(f);
    fake_reader("crash.sh", "printf 'indentmap-gwyddion-read 1\\n'; kill -SEGV $$");
    expect_read_refused("Gwyddion's file module crashed reading it (signal 11)");
    unsetenv("INDENTMAP_GWYDDION_READER");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_stream_gives_the_field_with_its_units),
        cmocka_unit_test(a_stream_that_lies_is_refused),
        cmocka_unit_test(the_program_is_chosen_by_the_environment),
        cmocka_unit_test(what_comes_through_the_pipe_is_checked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
