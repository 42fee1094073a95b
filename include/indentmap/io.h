/* indentmap/io.h: files in and out: surfaces (.npy, text matrix, Gwyddion .gsf), PNG images,
 * and the atomic-write discipline every writer follows.
 *
 * Entry points:
 *   im_surface_read, im_surface_read_with, im_surface_write   a surface, its format by name or content
 *   im_npy_*, im_text_*, im_gsf_*, im_sdf_*, im_netcdf_*, im_x3p_*   one format each (_read, _write)
 *   im_png_write, im_png_read                                 images
 *   im_atomic_open, im_atomic_commit, im_atomic_abort, im_write_file_atomic   atomic writes
 *   im_output_protect, im_output_check                        the inputs no write may replace
 *   im_folder_lock_acquire, im_folder_lock_release            an output folder's lock
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
 * Readers refuse, with IM_EFORMAT and a message naming the file (and the line for text), anything
 * they cannot read exactly: truncated data, extra data, unsupported types, NaN or Inf heights.
 * Sizes are checked against the memory available before allocating.
 *
 * Misuse (status.h): IM_EINVAL for a NULL path, buffer, stream or output and for an invalid field
 * view. For NULL, im_file_kind_of_bytes gives IM_KIND_NONE, im_atomic_is_temporary_name and
 * im_folder_remove_temporaries 0, im_length_unit_metres 0, im_path_utf8 "" (returns 0);
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
    IM_KIND_NPY, IM_KIND_PNG, IM_KIND_GIF, IM_KIND_PDF, IM_KIND_SVG, IM_KIND_MP4, IM_KIND_GSF,
    IM_KIND_WISDOM,   /* FFTW wisdom: "(fftw-" */
    IM_KIND_JSON,     /* starts with '{' */
    IM_KIND_INI,      /* text whose first line that is not blank or a comment is a [section] */
    IM_KIND_TEXT,     /* other text (CSV, text matrices, tables): no NUL byte in its head */
    IM_KIND_BINARY    /* anything else */
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
    FILE *stream;        /* write here */
    char path[4096];     /* final destination */
    char temp_path[4128];
    int slot;            /* internal: its entry in the list of temporary files (-1: none) */
} im_atomic_file;

/* Opens a new temporary file beside path for writing (created exclusively, mode 0666 less the
 * umask). IM_EINVAL when path is a registered input or its sidecar (im_output_check); IM_EIO when
 * the file cannot be created. */
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
    int fd;             /* -1 when not held */
    char path[4104];
    long stale_pid;     /* out: the pid of the dead process whose lock was taken over, 0 if none */
} im_folder_lock;
int im_folder_lock_acquire(const char *folder, const char *advice, im_folder_lock *lock);
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
    IM_READ_REGULAR = 0,   /* regular files only */
    IM_READ_OR_PIPE = 1    /* regular files and pipes (FIFOs, process substitution, stdin) */
};

/* Opens path with fopen mode ("r", "rb") after checking what it is. Returns IM_OK and sets *stream
 * (close with fclose) and, when size is not NULL, *size to the file's size in bytes (-1 for a
 * pipe); IM_EIO when it cannot be opened, IM_EINVAL for a directory or a file of a kind `source`
 * does not accept; every message names path. The open never blocks: a pipe with no writer yet is
 * waited for while polling im_stop_requested (IM_EINTERRUPTED once a stop is requested). */
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

/* NumPy .npy, version 1.0, little-endian, C order, 2-D shape (ny, nx) (rows are y). A .npy states
 * no units: its sidecar PATH.json does, when present ("delta", "unit" and, for fields other than
 * heights, "value_unit": written by `surface --out` and im_field_sidecar_write), and im_npy_read takes
 * them from it (IM_EFORMAT naming the sidecar when it is not a JSON object of those types, or larger
 * than 1 MiB). A sidecar's "order": "xy" says that the array is indexed [x, y] (enum im_npy_order):
 * it is read transposed, rows along y; "yx" (and none) is the layout above. */
int im_npy_write(const char *path, const im_field *field, enum im_npy_dtype dtype);

/* Writes PATH.json beside the .npy at path: program, version, quantity (e.g. "force per patch"),
 * the grid, delta, unit and value_unit of field, atomically. */
int im_field_sidecar_write(const char *path, const im_field *field, const char *quantity);
/* Reads versions 1.0 to 3.0, 2-D, C or Fortran order, floats of 4 or 8 bytes and integers of 1, 2, 4
 * or 8 bytes (signed or not) in either byte order, each converted to double (int64 and uint64 beyond
 * 2^53 rounded); im_surface_read_with records the conversion in its info. */
int im_npy_read(const char *path, im_field **out);

/* Plain text: one grid row per line (row 0 first), values separated by blanks, tabs, commas or
 * semicolons ("1,5 2,25" with blanks or semicolons between values and no '.' is read with decimal
 * commas: 1.5 and 2.25); lines starting with '#' are header lines. What the numbers are:
 * - three columns (and no header stating a matrix): x y z points, in any order; when each (x, y) of a
 *   regular grid appears once, the heights on that grid, spaced by the steps of x and y; otherwise
 *   refused (scattered points, repeats, uneven steps);
 * - fewer than three columns or rows: a line scan (a 1-D profile), refused with that reason;
 * - otherwise a matrix.
 * Gwyddion's "# Width: 5.12 um" and "# Height:" headers ("# Breite:" and "# Höhe:" from a German
 * Gwyddion; Height in another length unit is converted into Width's) set the spacing (Width /
 * columns, Height / rows; one alone states square pixels) and lateral unit, and "# Value units: m"
 * the unit of the heights (converted as im_surface_read_with says). Wyko/Vision ASCII headers before
 * the numbers, "h=ROWS w=COLUMNS", "pixel size=3.7e-007 m", "data unit=rad" and "height conversion
 * factor (-> m)=2.9e-008", set the grid, the spacing and heights in metres (value times the factor);
 * a data unit that is not a length with no factor, or another key=value line, is refused. A header
 * stating the grid (Vision's, or "# ... C columns x R rows ..." as written here) must match the data:
 * a file with rows missing or added is refused (IM_EFORMAT, naming that line, the header's grid and
 * the data's). Gwyddion's Width and Height are extents, not counts, and are not checked against the
 * data. Writing uses %.17g, so a round trip is exact. */
int im_text_write(const char *path, const im_field *field);
int im_text_read(const char *path, im_field **out);

/* Gwyddion Simple Field (.gsf): a text header ("Gwyddion Simple Field 1.0", then KEY = VALUE
 * lines with XRes, YRes and optionally XReal, YReal, XYUnits, ZUnits), NUL padding to a multiple
 * of 4 bytes, then XRes * YRes little-endian float32 values, row by row. XRes and YRes must be
 * decimal integers (no "16abc", no "1.6e1"), XReal and YReal finite numbers > 0; a value that is
 * not is refused naming its key. As the GSF specification says, an absent XReal or YReal is 1.0 (each
 * on its own: a spacing of 1.0 / XRes, 1.0 / YRes in XYUnits), and XYUnits and ZUnits have no default:
 * without ZUnits the heights' unit is unknown, not XYUnits', and such a file is refused (IM_EFORMAT
 * naming ZUnits) when the spacing has a unit, unless the heights' unit is set (options->set.height);
 * without either unit it is read bare. Units as for im_surface_read_with.
 * Writing is in base SI units, as Gwyddion writes and reads them (it keeps no prefix: "XYUnits = um"
 * would read as metres): a field in a known length unit is written with XReal, YReal and the heights
 * in metres and XYUnits = ZUnits = m; a field without a unit with no units; another unit is refused
 * (IM_EINVAL, nothing written). */
int im_gsf_write(const char *path, const im_field *field);
int im_gsf_read(const char *path, im_field **out);

/* ISO 25178-71 surface data file (.sdf): ASCII ("aISO-1.0" or "aBCR-1.0") or binary ("bISO-1.0",
 * "bBCR-1.0"; an 81-byte little-endian header, then the values), and Gwyddion's "aBCR-0.0" and
 * "bBCR-0.0". NumPoints columns by NumProfiles rows; Xscale, Yscale (spacings) and Zscale (the height
 * of one unit of a value) in metres, each checked to be a finite number > 0; DataType 0-7
 * (uint8/16/32, float, int8/16/32, double); Compression must be 0; Gwyddion's NumDataSet, when
 * present, must be 1 and NanPresent 0 or 1; "BAD" (ASCII) or NaN marks a missing point. Values after the data other
 * than a '*' trailer are refused. Writing is binary, DataType double, in metres (the field needs a
 * length unit; IM_EINVAL otherwise). */
int im_sdf_write(const char *path, const im_field *field);
int im_sdf_read(const char *path, im_field **out);

/* NetCDF (.nc) in the layout of ContactMechanics/SurfaceTopography and contact.engineering:
 * dimensions x and y, heights(x, y) (first index x; (y, x) is read too), and optional coordinate
 * variables x and y whose attributes `length` (physical size) and `unit` (today's name; `length_unit`
 * in older files) state the spacing (length / points) and the lateral unit; heights:unit the unit of
 * the heights (else the lateral one). Any numeric type is read as double;
 * values equal to the fill value (heights:_FillValue, else netCDF's default for the type, which is
 * also what netCDF returns for values past the end of a truncated file) are missing points. Refused with IM_EFORMAT naming the file and
 * the dimension, variable or attribute at fault. Writing uses the classic 64-bit offset format (as
 * SurfaceTopography does), with the unit in ASCII ("um" for µm) and periodic = 0, built in
 * memory and written atomically; the unit is written as x:unit, y:unit and heights:unit and, for older
 * readers, x:length_unit and y:length_unit. */
int im_netcdf_write(const char *path, const im_field *field);
int im_netcdf_read(const char *path, im_field **out);

/* ISO 25178-72 .x3p: a zip archive (libzip) holding main.xml (ISO 5436-2, parsed with libxml2
 * without network access or entity expansion) and the binary data it links. Read: Record1 Axes CX,
 * CY of AxisType I with Increment (the spacings, metres), CZ of AxisType A with DataType I (int16),
 * L (int32), F (float32) or D (float64), heights Offset + Increment x value in metres; Record3
 * MatrixDimension SizeX, SizeY, SizeZ = 1 and DataLink/PointDataLink, whose entry must hold exactly
 * SizeX x SizeY values (x fastest). NaN marks a missing point, and so does a point that
 * DataLink/ValidPointsLink marks invalid: that entry, when linked, must hold a bit per point in the
 * same order, least significant bit first, 1 valid (ISO 5436-2), (SizeX x SizeY + 7) / 8 bytes, and
 * match its MD5ChecksumValidPoints when one is stated. Inline DataList data are not read.
 * Stated checksums must match: the data's MD5ChecksumPointData, and each line of md5checksum.hex
 * ("<md5> *<entry>", as md5sum writes it) that of the entry it names, main.xml when it names none
 * (SurfaceTopography names bindata/data.bin); every entry is read to its end so that libzip checks its
 * CRC-32. Refused with IM_EFORMAT naming the file and the element or entry. Written: DataType D in
 * metres (the field needs a length unit; IM_EINVAL otherwise), with MD5ChecksumPointData and
 * md5checksum.hex naming main.xml. */
int im_x3p_write(const char *path, const im_field *field);
int im_x3p_read(const char *path, im_field **out);

/* ---- units of a surface ----
 * A surface's lateral spacing and its heights are lengths. Files state them (GSF XReal/YReal/
 * XYUnits/ZUnits, Gwyddion text "# Width:", "# Height:", "# Value units:"), the user may set or
 * override them (.npy files state none), and a surface read into an im_field always has its heights
 * in the unit of its spacing (field->unit), converted when the file gives them in another one, so
 * that slopes such as h'rms are dimensionless and right. Known length units: "m", "cm", "mm", "µm"
 * (also "um", "μm", "micron"), "nm", "pm", "Å" (also "A", "angstrom"). */
typedef struct im_surface_units {
    double delta_x, delta_y; /* pixel spacing along x (columns) and y (rows), in `lateral`; 0: not stated */
    char lateral[16];        /* unit of the spacing; "" when not stated */
    char height[16];         /* unit of the heights; "" when not stated (then: the lateral unit; for a
                                .gsf, whose heights are then in no known unit, refused when the spacing
                                has one) */
} im_surface_units;

/* Metres per unit of a length unit's name (1e-6 for "µm"), and its canonical spelling in
 * *canonical (may be NULL); 0 when the name is not a known length unit. */
double im_length_unit_metres(const char *name, const char **canonical);

/* Pixels whose x and y spacings differ by at most this, relative to their mean, are square: read
 * with the mean spacing, the difference recorded (im_surface_read_info.spacing_difference). 2^-16,
 * 1.5e-5, because spacings reach a reader rounded: stored as float32 (a 24-bit significand: 6e-8
 * relative each), and printed in headers with 6 or 7 significant digits (%g: up to 5e-6 relative
 * each, 5e-7 with 7). x and y are rounded apart (on a grid that is not square XReal and YReal are
 * different numbers), so one square pixel can come out as 6-digit spacings 1e-5 apart: a 512 x 256
 * grid of 1.23456789e-8 m pixels, printed "6.32099e-06" and "3.16049e-06", differs by 1.6e-6; 2^-20
 * (1e-6) would refuse it. Taking the mean misplaces a point by at most 2^-17 spacings per spacing
 * from the first: half a pixel across the largest grid (IM_FIELD_MAX_SIDE), 0.03 across 4096.
 * Beyond it the pixels are refused unless resample_square is set. */
#define IM_SQUARE_PIXEL_TOLERANCE (1.0 / 65536.0) /* 2^-16 */

/* Which index of a .npy array is x. indentmap writes and reads arrays of shape (ny, nx), rows along y
 * (the first index is y, as NumPy images are); SurfaceTopography's heights() are indexed [x, y], shape
 * (nx, ny). The order is of the array's indices, whatever its memory order (C or Fortran). */
enum im_npy_order {
    IM_NPY_ORDER_SIDECAR = 0, /* as the sidecar PATH.json states ("order": "yx" or "xy"), else yx */
    IM_NPY_ORDER_YX = 1,      /* the first index is y: rows are y */
    IM_NPY_ORDER_XY = 2       /* the first index is x: the array is transposed on reading */
};

/* How a surface file is read. Zero-initialised means: as the file states. */
typedef struct im_surface_read_options {
    im_surface_units set;    /* each stated member (non-zero, non-empty) overrides the file's; a
                                delta_x without delta_y sets both */
    int fill;                /* 1: fill missing points (NaN) with im_surface_fill_missing (surface.h);
                                0: refuse them, naming the first one's (x, y) */
    char express_in[16];     /* a length unit ("m" for SI): spacing and heights are converted into it
                                from the surface's unit, which must then be known; "": kept */
    int field_values;        /* 1: the file holds a field to draw (forces, gaps, displacements), not
                                heights to solve on: NaN and Inf are kept (a flat punch's gap is +Inf
                                where it can never touch); fill is then ignored */
    char channel[64];        /* of a multi-channel instrument file read through Gwyddion: an index or
                                a title (case ignored); "": the first channel holding lengths */
    int resample_square;     /* 1: pixels whose spacings differ beyond IM_SQUARE_PIXEL_TOLERANCE are
                                resampled onto square pixels of the finer spacing after the heights are
                                converted and their missing points refused or filled
                                (im_surface_resample_square, surface.h: bilinear, within the stored
                                extent); 0: they are refused */
    enum im_npy_order npy_order; /* of a .npy: overrides its sidecar's "order" (IM_NPY_ORDER_SIDECAR: keeps
                                it); other formats' layouts are their own, and ignore it */
} im_surface_read_options;

/* What the reader found and did, for reports and run records. */
typedef struct im_surface_read_info {
    im_surface_units file;   /* as the file stated them (zeros and "" where it stated nothing) */
    im_surface_units used;   /* after overrides (delta_y = delta_x when only delta_x is set), in the unit
                                of the field read (used.lateral: after express_in); field->delta is
                                delta_x when they are equal, their mean when they differ within
                                IM_SQUARE_PIXEL_TOLERANCE, the finer when the grid was resampled */
    double height_factor;    /* the heights were multiplied by this to bring them into `used.lateral` */
    long filled;             /* missing points filled (options->fill) */
    char conversion[96];     /* how the stored values were converted, e.g. "'>i2' (int16) converted to
                                float64; Fortran order transposed to C order"; "" when none */
    double spacing_difference; /* |used.delta_x - used.delta_y| / their mean: 0 for square pixels */
    char resampled[16];      /* how the grid was brought to square pixels: "bilinear" (resample_square,
                                spacing_difference beyond IM_SQUARE_PIXEL_TOLERANCE), or "" when it
                                was not resampled */
    double resampled_delta;  /* the square pixels' spacing when resampled (field->delta, in its unit);
                                0 otherwise */
    int stored_nx, stored_ny; /* the grid as the file stores it (before resampling) */
} im_surface_read_info;

/* Reads a surface by extension (.npy, .gsf, .sdf, .nc, .x3p), else as text (see im_text_read) when the
 * file is text whose first data line starts with a number, else through Gwyddion's file modules when
 * this build has them (im_gwyddion_reader): Bruker Nanoscope, Asylum .ibw, Park TIFF, Zygo MetroPro,
 * Wyko .opd, Sensofar .plu, Alicona .al3d, Digital Surf .sur, FRT, Nanosurf .nid, Molecular Imaging
 * .mi, WSxM .stp, BCR and more (`indentmap formats` lists them). From such a file the channel
 * options->channel names is read, by default the first whose values are lengths (a file of one
 * channel without a unit is read as a bare matrix); masked (invalid) points become missing points;
 * info->conversion names the module and channel. Then its units are applied: field->delta
 * is the spacing (1 when none is stated), field->unit the canonical lateral unit, heights converted
 * into it. Refused with IM_EFORMAT, naming the file and the header field (or option): pixels that
 * are not square (x and y spacings differing by more than IM_SQUARE_PIXEL_TOLERANCE of their mean;
 * the message names both spacings, their difference, the tolerance and the option that resamples)
 * unless options->resample_square, a unit that is not a length, heights in a unit without a lateral
 * unit to convert them to, Inf heights, and NaN heights (missing points) unless options->fill. A .npy
 * indexed [x, y] (options->npy_order, else its sidecar's "order") is transposed first, and
 * info->conversion says "indexed [x, y]". options and info may be NULL; IM_EINVAL for an npy_order
 * outside the enumeration. */
int im_surface_read_with(const char *path, const im_surface_read_options *options, im_field **out,
                         im_surface_read_info *info);

/* im_surface_read_with(path, NULL, out, NULL). */
int im_surface_read(const char *path, im_field **out);

/* The path of indentmap-gwyddion-read, the program that runs Gwyddion's file modules (GPL-2.0+, kept
 * out of this library: see README's License), or NULL when this build has none. The environment
 * variable INDENTMAP_GWYDDION_READER chooses another; otherwise the one beside the running executable,
 * then the one beside the shared object holding this library (a build tree's, or the Python extension,
 * beside which the build copies it), then the installed one. HDF5 and NetCDF-4 files are read the same
 * way by indentmap-hdf5-read (INDENTMAP_HDF5_READER). */
const char *im_gwyddion_reader(void);
/* Writes a surface by extension: .npy (float64), .gsf, .sdf (binary, metres), .nc, .x3p, else a text
 * matrix. A NaN or Inf height is refused before anything is written (IM_EINVAL naming the path and
 * the point), here and by each format's writer: no reader takes such a file back. */
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

/* im_png_write: options may be NULL (no texts, no pHYs, zlib level 6). IM_EINVAL for a
 * size, channel count, stride or text it cannot write, the errors of an atomic write (IM_EIO,
 * nothing left at path). */
int im_png_write(const char *path, const uint8_t *pixels, int width, int height, int channels,
                 size_t stride, const im_png_options *options);

/* Reads an 8-bit RGB or RGBA PNG (for tests and figure assembly); *pixels is malloc'ed, rows top
 * first, stride width * channels. */
int im_png_read(const char *path, uint8_t **pixels, int *width, int *height, int *channels);

#ifdef __cplusplus
}
#endif

#endif
