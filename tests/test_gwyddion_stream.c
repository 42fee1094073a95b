/* The stream indentmap-gwyddion-read hands the library (src/formats/gwyddion.h): what it accepts and what
 * it refuses, naming why, whatever the vendor file behind it put into the header; and the choice of
 * the program. The program itself is run on real files by tests/cli_instrument_files.sh. */
#include "support.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/status.h"
#include "formats/gwyddion.h"

#include <math.h>
#include <signal.h>
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
    expect_stream_refused("unknown_format.bin", "no Gwyddion file module reads this format");
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
    fake_reader("hang.sh", "kill -ALRM $$"); /* what the reader's own alarm does to a module that hangs */
    expect_read_refused("Gwyddion's file module ran out of time reading it");
    fake_reader("loader.sh", "echo 'libgwyapp2.so.0: cannot open shared object file' >&2; exit 127");
    expect_read_refused("Gwyddion's reader ended with status 127: libgwyapp2.so.0: cannot open shared object file");
    unsetenv("INDENTMAP_GWYDDION_READER");
}

/* Another part of the process reaping children (SIGCHLD ignored: the status is gone) does not turn a
 * good read into a crash (the status was read uninitialised). */
static void a_reaped_reader_is_judged_by_its_stream(void **state)
{
    (void)state;
    char body[4200];
    snprintf(body, sizeof body, "cat '%s'", seed("valid_heights.bin"));
    fake_reader("good.sh", body);
    void (*before)(int) = signal(SIGCHLD, SIG_IGN);
    im_field *f = NULL;
    for (int k = 0; k < 5; ++k) {
        assert_int_equal(im_surface_read(seed("valid_heights.bin"), &f), IM_OK);
        im_field_free(f);
    }
    signal(SIGCHLD, before);
    unsetenv("INDENTMAP_GWYDDION_READER");
}

/* Values without a unit beside sizes in metres are not taken for metres; --height-unit says what they are. */
static void unitless_values_beside_metres_need_their_unit(void **state)
{
    (void)state;
    const char *stream = "indentmap-gwyddion-read 1\nmodule x\nchannel 0\t3\t3\t-\tCounts\n"
                         "field 0 3 3 3e-06 3e-06 m - 0 Counts\n";
    char bytes[256];
    size_t length = strlen(stream);
    memcpy(bytes, stream, length);
    memset(bytes + length, 0, 9 * sizeof(double));
    test_write_bytes(test_path("counts.bin"), bytes, length + 9 * sizeof(double));
    char body[4200];
    snprintf(body, sizeof body, "cat '%s'", test_path("counts.bin"));
    fake_reader("counts.sh", body);
    expect_read_refused("its values have no unit beside lateral sizes in m: give their unit (--height-unit)");
    im_surface_read_options options = {.set = {.height = "nm"}};
    im_field *f = NULL;
    assert_int_equal(im_surface_read_with(seed("valid_heights.bin"), &options, &f, NULL), IM_OK);
    im_field_free(f);
    unsetenv("INDENTMAP_GWYDDION_READER");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_stream_gives_the_field_with_its_units),
        cmocka_unit_test(a_stream_that_lies_is_refused),
        cmocka_unit_test(the_program_is_chosen_by_the_environment),
        cmocka_unit_test(what_comes_through_the_pipe_is_checked),
        cmocka_unit_test(a_reaped_reader_is_judged_by_its_stream),
        cmocka_unit_test(unitless_values_beside_metres_need_their_unit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
