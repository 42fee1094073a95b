/* HDF5 and NetCDF-4 files read in a child process (src/formats/hdf5_child.c): the child gives the field, the units and the
 * refusals the in-process reader gives, and what comes through its stream is checked as any file is. A
 * constructed file (written here with libhdf5) is checked against the values written; stand-in programs
 * (INDENTMAP_HDF5_READER) crash, hang or lie. The crash inputs themselves: test_fuzz_regressions.c. */
#include "support.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/status.h"
#include "formats/hdf5.h"

#include <hdf5.h>
#include <netcdf.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

enum { NX = 150, NY = 3 }; /* three slabs of x-rows: 64, 64, 22 */

/* A data set "heights" of int16 values 10 x + y, indexed [x, y], and a 1-D "profile" before it by name. */
static const char *constructed_file(void)
{
    const char *path = test_path("constructed.h5");
    short values[NX][NY];
    for (int x = 0; x < NX; ++x)
        for (int y = 0; y < NY; ++y)
            values[x][y] = (short)(10 * x + y);
    hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hsize_t dims[2] = {NX, NY}, line[1] = {7};
    hid_t map = H5Screate_simple(2, dims, NULL), profile = H5Screate_simple(1, line, NULL);
    hid_t heights = H5Dcreate2(file, "heights", H5T_STD_I16LE, map, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    hid_t scan = H5Dcreate2(file, "a_profile", H5T_IEEE_F64LE, profile, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(H5Dwrite(heights, H5T_NATIVE_SHORT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values) >= 0);
    H5Dclose(scan);
    H5Dclose(heights);
    H5Sclose(profile);
    H5Sclose(map);
    H5Fclose(file);
    return path;
}

static void the_child_reads_what_was_written(void **state)
{
    (void)state;
    const char *path = constructed_file();
    im_field *child = NULL, *here = NULL;
    surface_stated through_child, in_process;
    assert_int_equal(hdf5_read_raw(path, NULL, &child, &through_child), IM_OK);
    assert_int_equal(child->nx, NX);
    assert_int_equal(child->ny, NY);
    for (int y = 0; y < NY; ++y)
        for (int x = 0; x < NX; ++x)
            assert_true(child->data[y * NX + x] == 10.0 * x + y); /* rows of y, x the first index */
    assert_int_equal(hdf5_read_in_process(path, NULL, &here, &in_process), IM_OK);
    assert_memory_equal(child->data, here->data, sizeof(double) * NX * NY);
    assert_string_equal(through_child.conversion, in_process.conversion);
    assert_string_equal(through_child.spacing_keys, in_process.spacing_keys);
    assert_string_equal(through_child.lateral_key, in_process.lateral_key);
    assert_string_equal(through_child.height_key, in_process.height_key);
    assert_memory_equal(&through_child.units, &in_process.units, sizeof in_process.units);
    im_field_free(child);
    im_field_free(here);
}

/* A refusal made in the child reads as the same refusal made here. */
static void the_child_refuses_as_the_reader_does(void **state)
{
    (void)state;
    const char *path = constructed_file();
    im_surface_read_options options = {.channel = "9"};
    im_field *field = NULL;
    surface_stated stated;
    assert_int_equal(hdf5_read_in_process(path, &options, &field, &stated), IM_EFORMAT);
    char in_process[1024];
    snprintf(in_process, sizeof in_process, "%s", im_last_error());
    assert_non_null(
        strstr(in_process, "no channel has the index or name '9'; its 2-D data sets: 0 'heights' (150 x 3)"));
    assert_int_equal(hdf5_read_raw(path, &options, &field, &stated), IM_EFORMAT);
    assert_string_equal(im_last_error(), in_process);
    assert_null(field);
}

enum { NC_X = 6, NC_Y = 4 };

/* Heights 10 x + y (nm) on a 3 x 2 µm grid in SurfaceTopography's NetCDF layout, as NetCDF-4 (HDF5
 * underneath) or as classic (64-bit offset) NetCDF. */
static const char *netcdf_file(const char *name, int format)
{
    const char *path = test_path(name);
    double heights[NC_X][NC_Y], lengths[2] = {3.0, 2.0};
    for (int x = 0; x < NC_X; ++x)
        for (int y = 0; y < NC_Y; ++y)
            heights[x][y] = 10.0 * x + y;
    int ncid, dims[2], coordinates[2], var;
    assert_int_equal(nc_create(path, format | NC_CLOBBER, &ncid), NC_NOERR);
    nc_def_dim(ncid, "x", NC_X, &dims[0]);
    nc_def_dim(ncid, "y", NC_Y, &dims[1]);
    nc_def_var(ncid, "heights", NC_DOUBLE, 2, dims, &var);
    nc_put_att_text(ncid, var, "unit", 2, "nm");
    for (int k = 0; k < 2; ++k) {
        nc_def_var(ncid, k ? "y" : "x", NC_DOUBLE, 1, &dims[k], &coordinates[k]);
        nc_put_att_double(ncid, coordinates[k], "length", NC_DOUBLE, 1, &lengths[k]);
        nc_put_att_text(ncid, coordinates[k], "unit", strlen("µm"), "µm");
    }
    assert_int_equal(nc_enddef(ncid), NC_NOERR);
    assert_int_equal(nc_put_var_double(ncid, var, &heights[0][0]), NC_NOERR);
    assert_int_equal(nc_close(ncid), NC_NOERR);
    return path;
}

/* A NetCDF-4 file is read in the program (libhdf5 parses it), which must be there, and gives what the same
 * file written as classic NetCDF, read in this process, gives. */
static void netcdf4_is_read_in_the_child(void **state)
{
    (void)state;
    im_field *four = NULL, *classic = NULL;
    im_surface_read_info four_info, classic_info;
    assert_int_equal(im_surface_read_with(netcdf_file("four.nc", NC_NETCDF4), NULL, &four, &four_info), IM_OK);
    assert_int_equal(im_surface_read_with(netcdf_file("classic.nc", NC_64BIT_OFFSET), NULL, &classic, &classic_info),
                     IM_OK);
    assert_int_equal(four->nx, NC_X);
    assert_int_equal(four->ny, NC_Y);
    assert_close(four->delta, 0.5, 0.0);
    assert_close(four->data[2 * NC_X + 5], (10.0 * 5 + 2) * 1e-3, 1e-15); /* x = 5, y = 2, nm in µm */
    assert_memory_equal(four->data, classic->data, sizeof(double) * NC_X * NC_Y);
    assert_string_equal(four->unit, classic->unit);
    assert_memory_equal(&four_info.file, &classic_info.file, sizeof four_info.file);
    im_field_free(four);
    im_field_free(classic);
    setenv("INDENTMAP_HDF5_READER", test_path("four.nc"), 1); /* not executable: no program */
    im_field *field = NULL;
    assert_int_equal(im_surface_read(test_path("four.nc"), &field), IM_EFORMAT);
    assert_non_null(strstr(im_last_error(), "four.nc: NetCDF-4 (HDF5) files are read by indentmap-hdf5-read"));
    unsetenv("INDENTMAP_HDF5_READER");
}

/* The same NetCDF-4 file named .h5 (a plain HDF5 file by its name) states its units in NetCDF's layout:
 * read as NetCDF reads it, not as a bare matrix of its fill values and unit-less numbers; --unit does not
 * relabel it, as it does not the classic file. */
static void netcdf4_named_h5_is_read_with_its_units(void **state)
{
    (void)state;
    test_copy_file(netcdf_file("four.nc", NC_NETCDF4), test_path("four.h5"));
    im_field *four = NULL, *classic = NULL;
    im_surface_read_info four_info, classic_info;
    assert_int_equal(im_surface_read_with(test_path("four.h5"), NULL, &four, &four_info), IM_OK);
    assert_int_equal(im_surface_read_with(netcdf_file("classic.nc", NC_64BIT_OFFSET), NULL, &classic, &classic_info),
                     IM_OK);
    assert_close(four->delta, 0.5, 0.0);
    assert_memory_equal(four->data, classic->data, sizeof(double) * NC_X * NC_Y);
    assert_memory_equal(&four_info.file, &classic_info.file, sizeof four_info.file);
    im_field_free(four);
    im_field_free(classic);
    im_surface_read_options relabel = {.set = {.lateral = "nm"}};
    int status = im_surface_read_with(test_path("classic.nc"), &relabel, &classic, NULL);
    char classic_says[1024];
    snprintf(classic_says, sizeof classic_says, "%s", status == IM_OK ? "" : strchr(im_last_error(), ':'));
    assert_int_equal(im_surface_read_with(test_path("four.h5"), &relabel, &four, NULL), status);
    if (status == IM_OK) {
        assert_memory_equal(four->data, classic->data, sizeof(double) * NC_X * NC_Y);
        assert_true(four->delta == classic->delta && strcmp(four->unit, classic->unit) == 0);
    } else {
        assert_string_equal(strchr(im_last_error(), ':'), classic_says);
    }
    im_field_free(four);
    im_field_free(classic);
    im_surface_read_options channel = {.channel = "heights"};
    assert_int_equal(im_surface_read_with(test_path("four.h5"), &channel, &four, NULL), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "four.h5: channel 'heights' asked of a NetCDF-4 file"));
}

/* A stand-in for the program: a script that writes what `body` says. */
static void fake_reader(const char *name, const char *body)
{
    const char *path = test_path(name);
    char script[8192];
    snprintf(script, sizeof script, "#!/bin/sh\n%s\n", body);
    test_write_bytes(path, script, strlen(script));
    chmod(path, 0700);
    setenv("INDENTMAP_HDF5_READER", path, 1);
}

static void expect_refused(const char *phrase)
{
    im_field *field = NULL;
    int status = im_surface_read(test_path("constructed.h5"), &field);
    if (status != IM_EFORMAT || !strstr(im_last_error(), phrase))
        fail_msg("status %d, '%s' (expected '%s')", status, im_last_error(), phrase);
    assert_null(field);
}

/* A stream of a 2 x 1 field: the header, `slab` (a slab line), `values` doubles of 0, then `tail`. */
static const char *stream_file(const char *name, const char *slab, int values, const char *tail)
{
    char bytes[512] = {0};
    int length = snprintf(bytes, 400,
                          "indentmap-hdf5-read 1\nfield 2 1\nunits 0 0\nlateral \nheight \n"
                          "keys --delta\t--unit\t--height-unit\nconversion HDF5 data set 'h', channel 0 of 1, "
                          "indexed [x, y]\n%s",
                          slab);
    length += (int)sizeof(double) * values;
    length += snprintf(bytes + length, sizeof bytes - (size_t)length, "%s", tail);
    const char *path = test_path(name);
    test_write_bytes(path, bytes, (size_t)length);
    return path;
}

static void fake_reader_of(const char *name, const char *stream)
{
    char body[4200];
    snprintf(body, sizeof body, "cat '%s'", stream);
    fake_reader(name, body);
}

/* What the program says is checked: a crash or a hang is a refusal naming the file; a stream that is
 * short, long or not the program's is refused saying so. */
static void what_comes_from_the_child_is_checked(void **state)
{
    (void)state;
    constructed_file();
    fake_reader("crash.sh", "printf 'indentmap-hdf5-read 1\\n'; kill -SEGV $$");
    expect_refused("constructed.h5: the HDF5 library (libhdf5) crashed reading it (signal 11): the file is damaged "
                   "or hostile");
    fake_reader("hang.sh", "kill -ALRM $$"); /* what the program's own alarm does to a read that hangs */
    expect_refused("constructed.h5: the HDF5 library (libhdf5) ran out of time reading it");
    fake_reader("loader.sh", "echo 'libhdf5_serial.so.103: cannot open shared object file' >&2; exit 127");
    expect_refused("the HDF5 reader (indentmap-hdf5-read) ended with status 127: libhdf5_serial.so.103: cannot "
                   "open shared object file");
    fake_reader_of("short.sh", stream_file("short.bin", "slab 0 2\n", 1, ""));
    expect_refused("ended inside x-rows 0 to 1");
    fake_reader_of("long.sh", stream_file("long.bin", "slab 0 2\n", 2, "x"));
    expect_refused("wrote more than the field");
    fake_reader_of("cut.sh", stream_file("cut.bin", "slab 0 1\n", 1, ""));
    expect_refused("ended before x-row 1 of 2");
    fake_reader_of("order.sh", stream_file("order.bin", "slab 1 1\n", 1, ""));
    expect_refused("wrote 'slab 1 1': expected 'slab 0 ROWS' with ROWS in [1, 2]");
    fake_reader_of("late.sh", stream_file("late.bin", "slab 0 1\n", 1, "error 3 late.h5: refused late\n"));
    expect_refused("late.h5: refused late");
    fake_reader_of("good.sh", stream_file("good.bin", "slab 0 2\n", 2, ""));
    im_field *field = NULL;
    assert_int_equal(im_surface_read(test_path("constructed.h5"), &field), IM_OK);
    assert_int_equal(field->nx, 2);
    im_field_free(field);
    fake_reader("unit.sh",
                "printf 'indentmap-hdf5-read 1\\nfield 2 1\\nunits 0.5 0.5\\nlateral micrometres of it\\n'");
    expect_refused("wrote 'lateral micrometres of it': expected 'lateral TEXT' of at most 15 bytes");
    fake_reader("status.sh", "printf 'indentmap-hdf5-read 1\\nerror 0 fine\\n'");
    expect_refused("wrote 'error 0 fine': expected a refusal 'error STATUS MESSAGE'");
    fake_reader("huge.sh", "printf 'indentmap-hdf5-read 1\\nfield 70000 1\\n'");
    expect_refused("expected 'field NX NY' with sides in [1, 65536]");
    fake_reader("other.sh", "echo hello");
    expect_refused("wrote 'hello': expected 'indentmap-hdf5-read 1' first");
    setenv("INDENTMAP_HDF5_READER", test_path("constructed.h5"), 1); /* not executable: no program */
    expect_refused("set INDENTMAP_HDF5_READER to its path");
    unsetenv("INDENTMAP_HDF5_READER");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_child_reads_what_was_written),
        cmocka_unit_test(the_child_refuses_as_the_reader_does),
        cmocka_unit_test(what_comes_from_the_child_is_checked),
        cmocka_unit_test(netcdf4_is_read_in_the_child),
        cmocka_unit_test(netcdf4_named_h5_is_read_with_its_units),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
