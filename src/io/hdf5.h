/* io/hdf5.h: plain HDF5 files, read with libhdf5 in this process (hdf5.c) by indentmap-hdf5-read, which
 * hands them to the library over a stream (hdf5_child.c; the library's reader is hdf5_read_raw, readers.h). */
#ifndef INDENTMAP_IO_HDF5_H
#define INDENTMAP_IO_HDF5_H

#include "io/readers.h"

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

/* Copies rows x-rows of field->ny values each ([x][y]), the first of them x0, into field's rows of y. */
void hdf5_scatter_slab(im_field *field, const double *values, int x0, int rows);

/* hdf5_read_raw's read in this process: what the program runs through hdf5_read_into, and what the fuzz
 * harness feeds. */
int hdf5_read_in_process(const char *path, const im_surface_read_options *options, im_field **out,
                         surface_stated *stated);

/* The program's side: reads path in this process and writes the stream hdf5_read_raw parses on stream;
 * 0 when it wrote the field, 2 when it wrote a refusal, 1 when the stream could not be written. */
int hdf5_child_write(FILE *stream, const char *path, const char *channel);

#endif
