/* formats/payload.h: a check shared by the binary surface readers (.npy, .gsf). */
#ifndef INDENTMAP_FORMATS_PAYLOAD_H
#define INDENTMAP_FORMATS_PAYLOAD_H

#include "indentmap/field.h"

#include <stdint.h>
#include <stdio.h>

/* Runs after a binary reader has parsed a header claiming an nx x ny grid of item_size-byte values
 * (each side >= 1) and before it allocates the grid: refuses a grid that would not fit in memory
 * (IM_ENOMEM, as im_field_create would, with the estimate; nx and ny may be as large as a long, the
 * estimate is computed in double and anything past SIZE_MAX is refused), then a side larger than
 * IM_FIELD_MAX_SIDE (IM_EFORMAT), then a regular file whose bytes after the stream's position are not
 * exactly nx * ny * item_size (IM_EFORMAT, "truncated data" or "more data"; `claim` describes the
 * header in the message). Without it a header claiming a huge grid over a few bytes of data made
 * the reader allocate gigabytes before finding the data missing (found with fuzz/fuzz_npy). Other
 * streams (pipes) pass the size check; the readers' own end-of-data checks still apply. */
int formats_check_grid(FILE *stream, const char *path, long nx, long ny, unsigned item_size, const char *claim);

/* IM_EFORMAT naming path and the first NaN or Inf value with its (x, y), as formats.h promises for every
 * reader (im_field_check_finite alone would give IM_ENUMERIC, which the command line reports as a
 * failure while running, exit 1, rather than as bad input, exit 2). */
int formats_check_finite(const im_field *field, const char *path);

/* The writers' side: IM_EINVAL naming path and the first infinite value with its (x, y), before anything is
 * written. NaN, a missing point, is written: every format's reader takes it back as missing (.npy, .sdf,
 * .nc, .gsf and text as NaN, .x3p in its validity mask). */
int formats_check_heights_or_missing_writable(const im_field *field, const char *path);

#endif
