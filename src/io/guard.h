/* Internal to the io module: the output guard's check at commit (guard.c). */
#ifndef INDENTMAP_IO_GUARD_H
#define INDENTMAP_IO_GUARD_H

/* IM_OK when the complete new contents of path, readable from the open descriptor written_fd, may
 * replace what path holds now: nothing, an empty file, something not a regular file (rename
 * replaces a symlink itself), or a file of the same kind. Otherwise IM_EINVAL naming both kinds. */
int output_check_replace(const char *path, int written_fd);

#endif
