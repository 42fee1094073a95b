/* indentmap/io.h: files in and out: surfaces (.npy, text matrix, Gwyddion .gsf), PNG images,
 * and the atomic-write discipline every writer follows.
 *
 * Atomic writes: every file is written to "PATH.tmp.PID" beside its destination and renamed over
 * it only when complete, so an interrupted run never leaves a half-written file and an existing
 * file is replaced whole or not at all.
 *
 * Readers refuse, with IM_EFORMAT and a message naming the file (and the line for text), anything
 * they cannot read exactly: truncated data, extra data, unsupported types, NaN or Inf heights.
 * Sizes are checked against the memory available before allocating.
 */
#ifndef INDENTMAP_IO_H
#define INDENTMAP_IO_H

#include "indentmap/field.h"

#include <stdint.h>
#include <stdio.h>

/* ---- atomic files ---- */
typedef struct im_atomic_file {
    FILE *stream;        /* write here */
    char path[4096];     /* final destination */
    char temp_path[4128];
} im_atomic_file;

/* Opens a temporary file beside path for writing ("wb"). */
int im_atomic_open(im_atomic_file *file, const char *path);
/* Flushes, syncs, closes and renames into place; on failure removes the temporary file. */
int im_atomic_commit(im_atomic_file *file);
/* Closes and removes the temporary file; the destination is untouched. Accepts a closed file. */
void im_atomic_abort(im_atomic_file *file);

/* Writes a whole text (or binary) buffer atomically. */
int im_write_file_atomic(const char *path, const void *data, size_t size);

/* Creates a directory and its parents (mkdir -p); IM_OK if it already exists. */
int im_make_directories(const char *path);

/* ---- bounded reading ----
 * Every reader opens its input through im_read_open, so that no input can make it read without
 * end or without limit: a directory is refused, and so is anything but a regular file or a pipe (a
 * device such as /dev/zero, a socket), whose reading may never end. Pipes are accepted only by
 * readers that bound what they read as they go (text lines, below). Reads poll im_stop_requested
 * (status.h), so that SIGINT/SIGTERM end even a read of a long pipe promptly. */
enum im_read_source {
    IM_READ_REGULAR = 0,   /* regular files only */
    IM_READ_OR_PIPE = 1    /* regular files and pipes (FIFOs, process substitution, stdin) */
};

/* Opens path with fopen mode ("r", "rb") after checking what it is. Returns IM_OK and sets *stream
 * (close with fclose) and, when size is not NULL, *size to the file's size in bytes (-1 for a
 * pipe); IM_EIO when it cannot be opened, IM_EINVAL for a directory or a file of a kind `source`
 * does not accept; every message names path. */
int im_read_open(const char *path, const char *mode, enum im_read_source source, FILE **stream, long long *size);

/* One line of text as im_read_line reads it. */
typedef struct im_text_line {
    char *text;        /* the line without its newline, NUL-terminated; owned: free() it */
    size_t length;     /* bytes in text */
    size_t capacity;   /* bytes allocated */
    long number;       /* 1-based number of the line last read */
} im_text_line;

/* Reads the next line of stream into line (zero-initialise it before the first call). Returns
 * IM_OK with *end = 0 for a line, IM_OK with *end = 1 at the end of the file (nothing read), or an
 * error whose message names path and the line: a NUL byte (IM_EFORMAT: not a text file), a line
 * longer than max_length bytes (IM_EFORMAT), a line that would not fit in the memory available
 * (IM_ENOMEM), a read error (IM_EIO with the system's reason; never taken for the end of the file),
 * or a stop request (IM_EINTERRUPTED). */
int im_read_line(FILE *stream, const char *path, size_t max_length, im_text_line *line, int *end);

/* Reads a whole regular text file of at most max_bytes bytes (and within the memory available)
 * into *text, NUL-terminated, its length in *size when size is not NULL; the caller frees *text.
 * Errors name path: IM_EIO (open or read), IM_EINVAL (not a regular file, or larger than
 * max_bytes), IM_ENOMEM, IM_EFORMAT (a NUL byte inside: not text). */
int im_read_text_file(const char *path, size_t max_bytes, char **text, size_t *size);

/* ---- surfaces ---- */
enum im_npy_dtype { IM_NPY_FLOAT64 = 0, IM_NPY_FLOAT32 = 1 };

/* NumPy .npy, version 1.0, little-endian, C order, 2-D shape (ny, nx) (rows are y). */
int im_npy_write(const char *path, const im_field *field, enum im_npy_dtype dtype);
/* Reads '<f8' or '<f4', C order, 2-D, versions 1.0 to 3.0. */
int im_npy_read(const char *path, im_field **out);

/* Plain text matrix: one grid row per line (row 0 first), values separated by blanks, tabs or
 * commas; lines starting with '#' are header lines. Gwyddion's "# Width: 5.12 um" and
 * "# Height:" headers, when present, set the spacing (Width / columns) and unit. A header line
 * stating the grid, "# ... C columns x R rows ..." (as written here), must match the data: a file
 * with rows missing or added is refused (IM_EFORMAT, naming that line, the header's grid and the
 * data's). Gwyddion's Width and Height are extents, not counts, and are not checked against the
 * data. Writing uses %.17g, so a round trip is exact. */
int im_text_write(const char *path, const im_field *field);
int im_text_read(const char *path, im_field **out);

/* Gwyddion Simple Field (.gsf): a text header ("Gwyddion Simple Field 1.0", then KEY = VALUE
 * lines with XRes, YRes and optionally XReal, YReal, XYUnits, ZUnits), NUL padding to a multiple
 * of 4 bytes, then XRes * YRes little-endian float32 values, row by row. Writing is provided for
 * round trips and tests. */
int im_gsf_write(const char *path, const im_field *field);
int im_gsf_read(const char *path, im_field **out);

/* Reads a surface by extension: .npy, .gsf, else a text matrix. */
int im_surface_read(const char *path, im_field **out);
/* Writes a surface by extension: .npy (float64), .gsf, else a text matrix. */
int im_surface_write(const char *path, const im_field *field);

/* ---- PNG ---- */
typedef struct im_png_text {
    const char *key, *value;
} im_png_text;

/* Writes an 8-bit RGB (channels 3) or RGBA (4) image with libpng, atomically. Row 0 of pixels is
 * the top row of the image; stride is the distance between rows in bytes. texts (may be NULL)
 * become tEXt chunks; dots_per_metre > 0 writes a pHYs chunk. compression is zlib's level 0-9. */
typedef struct im_png_options {
    const im_png_text *texts;
    int text_count;
    double dots_per_metre;
    int compression;
} im_png_options;

int im_png_write(const char *path, const uint8_t *pixels, int width, int height, int channels,
                 size_t stride, const im_png_options *options);

/* Reads an 8-bit RGB or RGBA PNG (for tests and figure assembly); *pixels is malloc'ed, rows top
 * first, stride width * channels. */
int im_png_read(const char *path, uint8_t **pixels, int *width, int *height, int *channels);

#endif
