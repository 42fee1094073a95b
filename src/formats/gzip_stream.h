/* formats/gzip_stream.h: gzip-compressed text surfaces (matrix.txt.gz) read as the text they hold. */
#ifndef INDENTMAP_FORMATS_GZIP_STREAM_H
#define INDENTMAP_FORMATS_GZIP_STREAM_H

#include <stdio.h>

/* When the regular file behind *stream starts with gzip's magic bytes (1f 8b), replaces *stream by a
 * stream of the decompressed bytes (zlib, through a glibc cookie stream) and closes the original;
 * *compressed says so. Otherwise the stream is rewound and kept (a pipe is kept as it is: it cannot
 * be looked at twice). IM_EIO or IM_ENOMEM naming path; the original is then closed and *stream NULL. */
int formats_gunzip_if_compressed(FILE **stream, const char *path, int *compressed);

#endif
