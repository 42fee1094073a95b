/* indentmap/io.h: the file layer: the atomic-write discipline every writer follows, the output
 * guard, folder locks, bounded reading, paths and PNG images. It depends on field.h and status.h
 * only; the surface and profile formats are formats.h's.
 *
 * Entry points:
 *   im_surface_read, im_surface_read_with, im_surface_write   a surface, its format by name or content
 *   im_npy_*, im_text_*, im_gsf_*, im_sdf_*, im_netcdf_*, im_x3p_*   one format each (_read, _write)
 *   im_png_write, im_png_read                                 images
 *   im_atomic_open, im_atomic_commit, im_atomic_abort, im_write_file_atomic   atomic writes
 *   im_output_protect, im_output_check                        the inputs no write may replace
 *   im_folder_lock_acquire, im_folder_lock_release            an output folder's lock
 *   im_folder_lock_probe                                       whether it is free, nothing written
 *   im_read_open, im_read_line, im_read_text_file             bounded reading
 *   im_path_join, im_path_absolute, im_make_directories       paths
 *
 * Atomic writes: every file is written to a temporary file with a short unique name beside its
 * destination, ".im.tmp.PID.N" (N counts the files this process opened, across threads), and
 * renamed over it only when complete, so an interrupted run never leaves a half-written file and
 * an existing file is replaced whole or not at all. A final name of up to NAME_MAX (255) bytes
 * keeps working: the temporary name does not grow with it.
 *
 * The output guard: every atomic write is checked, when it is opened, against the inputs the
 * process registered (im_output_protect): an input, another name of it (symlink, hard link,
 * "..") or its sidecar PATH.json is never written (IM_EINVAL). When it is committed, an existing
 * file is replaced only by a file of the same kind (im_file_kind): a PNG never replaces a scene
 * file, FFTW wisdom never replaces a surface (IM_EINVAL; the existing file is left as it was).
 *
 * Misuse (status.h): IM_EINVAL for a NULL path, buffer, stream or output and for an invalid field
 * view. For NULL, im_file_kind_of_bytes gives IM_KIND_NONE, im_atomic_is_temporary_name and
 * im_folder_remove_temporaries 0, im_path_utf8 "" (returns 0);
 * im_atomic_abort and im_folder_lock_release accept NULL; im_pair_writers_lock(NULL) is -1.
 * Threads: thread-safe on distinct files and handles (an im_atomic_file or a stream is one
 * thread's; the temporary names' counter and the guard's list are shared under locks), with one
 * exception: libnetcdf is not thread-safe, so im_netcdf_read and im_netcdf_write (and
 * im_surface_read or _write of a NetCDF file) run in one thread at a time. Folder locks are
 * flock(2)s: two threads of one process asking for one folder's lock are refused as two processes.
 */
#ifndef INDENTMAP_IO_H
#define INDENTMAP_IO_H

#include "indentmap/field.h"

#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the output guard ---- */

/* Registers path as an input of this process: from now on no atomic write may replace it (by any
 * name that reaches it) or its sidecar path.json. A path that does not exist is registered by name.
 * IM_ENOMEM if the list cannot grow. Thread-safe. */
int im_output_protect(const char *path);
/* Forgets every registered input (for tests and long-lived embedders). */
void im_output_protect_reset(void);
/* IM_OK when path is none of the registered inputs and none of their sidecars; otherwise IM_EINVAL
 * with "PATH would overwrite the input file INPUT (RESOLVED); write it elsewhere" or the sidecar's
 * message. Cheap (a few stat calls per input): the command line calls it before any work. */
int im_output_check(const char *path);

/* The absolute form of path with every symlink of its existing leading part resolved; the part
 * that does not exist yet is appended as written. IM_EINVAL if it does not fit in size. */
int im_path_absolute(const char *path, char *out, size_t size);

/* Checked path building. im_path_join writes DIR/NAME and im_path_suffix PATH followed by SUFFIX
 * (e.g. a sidecar's ".json") into out (size bytes, terminated). IM_OK, or IM_EINVAL with
 * "path too long: L bytes where at most size - 1 fit: 'HEAD...TAIL'" (the path's first and last 60
 * bytes) when it does not fit, out then being the empty string: a cut path is never handed on. */
int im_path_join(char *out, size_t size, const char *dir, const char *name);
int im_path_suffix(char *out, size_t size, const char *path, const char *suffix);

/* What a file holds, recognised from its first bytes. */
enum im_file_kind {
    IM_KIND_NONE = 0, /* missing or empty */
    IM_KIND_NPY,
    IM_KIND_PNG,
    IM_KIND_GIF,
    IM_KIND_PDF,
    IM_KIND_SVG,
    IM_KIND_MP4,
    IM_KIND_GSF,
    IM_KIND_WISDOM, /* FFTW wisdom: "(fftw-" */
    IM_KIND_JSON,   /* starts with '{' */
    IM_KIND_INI,    /* text whose first line that is not blank or a comment is a [section] */
    IM_KIND_TEXT,   /* other text (CSV, text matrices, tables): no NUL byte in its head */
    IM_KIND_BINARY  /* anything else */
};
/* The kind of `length` first bytes of a file (512 are enough). */
enum im_file_kind im_file_kind_of_bytes(const void *bytes, size_t length);
/* The kind of the file at path (IM_KIND_NONE when missing, empty or unreadable); IM_EINVAL for a
 * path that is not a regular file (a folder, a device, a FIFO). */
int im_file_kind_of(const char *path, enum im_file_kind *kind);
/* "a PNG image", "FFTW wisdom", ... for messages. */
const char *im_file_kind_name(enum im_file_kind kind);

/* ---- atomic files ---- */
typedef struct im_atomic_file {
    FILE *stream;    /* write here */
    char path[4096]; /* final destination (a symbolic link's target) */
    char temp_path[4128];
    int slot; /* internal: its entry in the list of temporary files (-1: none) */
} im_atomic_file;

/* Opens a new temporary file beside path for writing (created exclusively, mode 0666 less the
 * umask). A path that is a symbolic link (or a chain of them) is written through: the temporary file
 * is made beside the link's target and replaces it, so the link stays and shows the new content (a
 * dangling link's target is created). IM_EINVAL when path is a registered input or its sidecar
 * (im_output_check) or a loop of links; IM_EIO when the file cannot be created. */
int im_atomic_open(im_atomic_file *file, const char *path);
/* The same with a temporary name ending in suffix (e.g. ".mp4", for a program that picks its
 * format from the name and writes file->temp_path itself). */
int im_atomic_open_suffixed(im_atomic_file *file, const char *path, const char *suffix);
/* Flushes, syncs, closes and renames into place. On failure removes the temporary file and leaves
 * path as it was: IM_EIO (write or rename failed: the message has errno's reason), IM_EINVAL (path
 * holds a file of another kind than the one written, see the output guard). */
int im_atomic_commit(im_atomic_file *file);
/* Closes and removes the temporary file; the destination is untouched. Accepts a closed file. */
void im_atomic_abort(im_atomic_file *file);
/* Removes every temporary file this process has open (async-signal-safe: for a handler of a
 * fatal signal, which then ends the process). */
void im_atomic_remove_temporaries(void);
/* Whether name (a file name without folder) is a temporary name of an atomic write: ".im.tmp.*",
 * or "NAME.tmp.PID" / "NAME.tmp.PID.mp4" as earlier versions named them. */
int im_atomic_is_temporary_name(const char *name);

/* Writes a whole text (or binary) buffer atomically (data may be NULL when size is 0). The errors of
 * im_atomic_open and im_atomic_commit, and IM_EIO when the write fails; nothing is left at path
 * on an error. */
int im_write_file_atomic(const char *path, const void *data, size_t size);

/* Creates a directory and its parents (mkdir -p); IM_OK if it already exists. IM_EIO naming the
 * folder that cannot be made or that exists as another kind of file; IM_EINVAL for a path of 4096
 * bytes or more. */
int im_make_directories(const char *path);

/* A path as UTF-8 text for records (JSON, PNG text chunks): itself when it is valid UTF-8 (returns
 * 0); otherwise (returns 1) each byte outside valid UTF-8 becomes \xHH and each backslash \\,
 * so that the bytes can be recovered. out is always terminated; a path that does not fit is cut
 * (size 4 * PATH_MAX + 1 always fits). */
int im_path_utf8(const char *path, char *out, size_t size);

/* ---- output folders ---- */

/* An output folder's lock, FOLDER/.lock (the folder must exist), held by `run` and `indent` while
 * they write there: flock(2) decides who holds it (the kernel drops it when its holder dies) and
 * the file holds the holder's pid. IM_EIO while another live process holds it, with "output folder
 * FOLDER is in use by another indentmap run (pid N, lock file F); wait for it to end or ADVICE";
 * a lock file no live process holds is taken over silently, and its pid reported in stale_pid for
 * the caller to tell the user (the indentmap program and scene runs do, as a warning). */
typedef struct im_folder_lock {
    int fd; /* -1 when not held */
    char path[4104];
    long stale_pid; /* out: the pid of the dead process whose lock was taken over, 0 if none */
} im_folder_lock;
int im_folder_lock_acquire(const char *folder, const char *advice, im_folder_lock *lock);
/* Whether im_folder_lock_acquire would find the lock free, creating and writing nothing: IM_OK when
 * FOLDER/.lock does not exist or no live process holds it, else its IM_EIO and message (advice as
 * there). A read-only look (run --check): the answer may change before a later acquire. */
int im_folder_lock_probe(const char *folder, const char *advice);
/* Removes the lock file and releases it; nothing if not held. */
void im_folder_lock_release(im_folder_lock *lock);

/* A file and its sidecar (FILE.npy and FILE.npy.json) are two renames: writers of one pair take
 * turns under an flock(2) on the folder holding path, waited for, so that the pair left behind is
 * one writer's whole (without it, racing writers left one's data beside another's sidecar). Returns
 * the lock's descriptor for im_pair_writers_unlock, or -1 with IM_EIO's message naming the folder. */
int im_pair_writers_lock(const char *path);
/* Releases it; nothing for -1. */
void im_pair_writers_unlock(int fd);

/* Removes the temporary files of atomic writes (im_atomic_is_temporary_name) that a killed run
 * left in folder and, for depth d > 0, in its subfolders d levels down (depth 0: folder only). Call
 * it only while holding the folder's lock: another live writer's temporary files would go too.
 * Returns how many were removed. */
int im_folder_remove_temporaries(const char *folder, int depth);

/* ---- bounded reading ----
 * Every reader opens its input through im_read_open, so that no input can make it read without
 * end or without limit: a directory is refused, and so is anything but a regular file or a pipe (a
 * device such as /dev/zero, a socket), whose reading may never end. Pipes are accepted only by
 * readers that bound what they read as they go (text lines, below). Reads poll im_stop_requested
 * (status.h), so that SIGINT/SIGTERM end even a read of a long pipe promptly. */
enum im_read_source {
    IM_READ_REGULAR = 0, /* regular files only */
    IM_READ_OR_PIPE = 1  /* regular files and pipes (FIFOs, process substitution, stdin) */
};

/* Opens path with fopen mode ("r", "rb") after checking what it is. Returns IM_OK and sets *stream
 * (close with fclose) and, when size is not NULL, *size to the file's size in bytes (-1 for a
 * pipe); IM_EIO when it cannot be opened, IM_EINVAL for a directory or a file of a kind `source`
 * does not accept; every message names path. The open never blocks: a pipe with no writer yet is
 * waited for while polling im_stop_requested (IM_EINTERRUPTED once a stop is requested). */
int im_read_open(const char *path, const char *mode, enum im_read_source source, FILE **stream, long long *size);

/* One line of text as im_read_line reads it. */
typedef struct im_text_line {
    char *text;      /* the line without its newline, NUL-terminated; owned: free() it */
    size_t length;   /* bytes in text */
    size_t capacity; /* bytes allocated */
    long number;     /* 1-based number of the line last read */
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

/* im_png_write: options may be NULL (no texts, no pHYs, zlib level 6). IM_EINVAL for a
 * size, channel count, stride or text it cannot write, the errors of an atomic write (IM_EIO,
 * nothing left at path). */
int im_png_write(const char *path, const uint8_t *pixels, int width, int height, int channels, size_t stride,
                 const im_png_options *options);

/* Reads an 8-bit RGB or RGBA PNG (for tests and figure assembly); *pixels is malloc'ed, rows top
 * first, stride width * channels. */
int im_png_read(const char *path, uint8_t **pixels, int *width, int *height, int *channels);

#ifdef __cplusplus
}
#endif

#endif
