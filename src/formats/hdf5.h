/* formats/hdf5.h: plain HDF5 files, read with libhdf5 in this process (hdf5.c) by indentmap-hdf5-read, which
 * hands them to the library over a stream (hdf5_child.c; the library's reader is hdf5_read_raw, readers.h). */
#ifndef INDENTMAP_FORMATS_HDF5_H
#define INDENTMAP_FORMATS_HDF5_H

#include "formats/readers.h"

#include <stdio.h>

/* The most x-rows read (and sent over the stream) at a time. */
enum { HDF5_SLAB_ROWS = 64 };

/* Where hdf5_read_into hands the chosen data set: its sides and what the file states, then its values
 * at most HDF5_SLAB_ROWS x-rows at a time, in the order HDF5 stores them ([x][y], y fastest). A status other
 * than IM_OK (set with im_fail) ends the read with it. */
typedef struct hdf5_sink {
    int (*begin)(void *context, const char *path, int nx, int ny, const surface_stated *stated);
    int (*slab)(void *context, const double *values, int x0, int rows);
    void *context;
} hdf5_sink;

/* Lists path's data sets, chooses options->channel's (options may be NULL) and hands it to sink; IM_EFORMAT
 * naming path for what hdf5_read_raw refuses. */
int hdf5_read_into(const char *path, const im_surface_read_options *options, const hdf5_sink *sink);

/* 1 when path is an HDF5 file that netCDF-4 wrote (its root has netCDF's _NCProperties attribute): the layout
 * and attributes of its variables are NetCDF's, which netcdf.c reads (units, fill values, dimension order). */
int hdf5_is_netcdf4(const char *path);

/* Copies rows x-rows of field->ny values each ([x][y]), the first of them x0, into field's rows of y. */
void hdf5_scatter_slab(im_field *field, const double *values, int x0, int rows);
/* The reverse: field's x-rows x0 to x0 + rows - 1 into values ([x][y]). */
void hdf5_gather_slab(const im_field *field, double *values, int x0, int rows);

/* hdf5_read_raw's read in this process: what the program runs through hdf5_read_into, and what the fuzz
 * harness feeds. */
int hdf5_read_in_process(const char *path, const im_surface_read_options *options, im_field **out,
                         surface_stated *stated);

/* The program's side: reads path in this process, as a plain HDF5 file (channel chooses the data set) or when
 * netcdf4 is 1 or the file is one (hdf5_is_netcdf4; a channel is then refused) as a NetCDF-4 file, and writes the stream that hdf5_read_raw and netcdf4_read_raw parse on
 * stream; 0 when it wrote the field, 2 when it wrote a refusal, 1 when the stream could not be written. */
int hdf5_child_write(FILE *stream, const char *path, const char *channel, int netcdf4);

/* A NetCDF-4 file (HDF5 underneath) read as netcdf_read_in_process reads it, in the program (readers.h's
 * netcdf_read_raw hands such files here). */
int netcdf4_read_raw(const char *path, im_field **out, surface_stated *stated);

#endif
