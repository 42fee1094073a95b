/* Internal: the SHA-256 of a file's bytes (checksum.c), as sha256sum prints it, for the run records'
 * inputs (docs/scenes.md, "Provenance"). */
#ifndef INDENTMAP_IO_CHECKSUM_H
#define INDENTMAP_IO_CHECKSUM_H

enum { IM_SHA256_HEX = 64 };

/* The SHA-256 of the file at path as 64 lower-case hex digits. im_read_open's errors (naming the
 * path), IM_EIO naming it when a read fails. */
int im_file_sha256(const char *path, char hex[IM_SHA256_HEX + 1]);

#endif
