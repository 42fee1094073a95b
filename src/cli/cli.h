/* The command line: one function per subcommand, each parsing its own options. */
#ifndef INDENTMAP_CLI_H
#define INDENTMAP_CLI_H

#include "indentmap/history.h"
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/render.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <signal.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

struct option;

/* Subcommands: argv[0] is the subcommand's name. Return the process exit status. */
int cli_surface(int argc, char **argv);
int cli_info(int argc, char **argv);
int cli_formats(int argc, char **argv);
int cli_render(int argc, char **argv);
int cli_render_view3d(int argc, char **argv); /* render view3d (render_view3d.c) */
int cli_indent(int argc, char **argv);
int cli_theory(int argc, char **argv);
/* theory --fit-k HISTORY (theory_fit_k.c): k of eq. (2) over a periodic history, as a line or (csv) a CSV row. */
int cli_theory_fit_k(const char *history, int csv);
int cli_run(int argc, char **argv);
/* One grid over MPI ranks (mpi_indent.c); exists only where IM_HAVE_MPI (indentmap/mpi.h). */
int cli_mpi_indent(int argc, char **argv);

/* SIGINT/SIGTERM/SIGHUP (interrupt.c): cli_interrupt_install makes them store their number in
 * cli_stop_signal (a second one removes the temporary files being written and ends the process);
 * cli_interrupt_report prints the interrupted work's message (im_last_error) when reporting (rank 0, or a
 * single process) and returns the exit status, 128 + it. cli_interrupt_install_cleanup makes the first one remove
 * the temporary files and end the process (for commands with nothing to keep). cli_interrupt_install_unrestarted
 * is cli_interrupt_install without SA_RESTART: a write blocked on a pipe fails with EINTR (mpi-indent under a
 * signalled mpirun). 0, or -1 if sigaction failed. */
extern volatile sig_atomic_t cli_stop_signal;
int cli_interrupt_install(void);
int cli_interrupt_install_unrestarted(void);
int cli_interrupt_install_cleanup(void);
int cli_interrupt_report(int reporting);

/* Unless OMP_WAIT_POLICY or GOMP_SPINCOUNT is set, re-executes the program (argv as given) once
 * with GOMP_SPINCOUNT=CLI_SPIN_COUNT, so that idle OpenMP threads spin only briefly before they
 * sleep, instead of holding for long cores that others need (wait_policy.c). Returns only if that is
 * not wanted or the re-execution failed. */
#define CLI_SPIN_COUNT "3000"
void cli_prefer_short_spinning(char **argv);

/* The library's messages on stderr (log.c), as callbacks of status.h: cli_log prints
 * "indentmap: MESSAGE"; cli_progress draws "[####....] done/total surfaces" in place, only when
 * stderr is a terminal (user unused). cli_warn_stale_lock prints the notice of a lock taken over
 * (io.h: im_folder_lock's stale_pid), if any. */
void cli_log(void *user, im_log_level level, const char *message);
void cli_progress(void *user, const char *stage, int done, int total);
struct im_folder_lock;
void cli_warn_stale_lock(const struct im_folder_lock *lock);

/* The environment's settings of the library (environment.c). cli_apply_memory_limit sets
 * im_memory_set_limit from IM_MEMORY_LIMIT_MIB (MiB; unset or empty: none): 0, or -1 after
 * printing what was expected. cli_render_backend turns IM_RENDER_AUTO into IM_RENDER_BACKEND's
 * backend when it is set (an explicit --backend wins): IM_EINVAL naming the variable for a bad
 * value. cli_render_open is im_render_open after cli_render_backend. cli_space_check_off: 1 when
 * IM_NO_SPACE_CHECK is set to anything but "" or "0" (run's im_scene_run_options.no_space_check). */
int cli_apply_memory_limit(void);
int cli_space_check_off(void);
int cli_render_backend(im_render_backend *backend);
int cli_render_open(im_render_backend backend, im_render_context **out);

/* The FFTW wisdom file of a run (wisdom.c; the library reads no environment): --wisdom FILE (given),
 * else $IM_FFTW_WISDOM (set but empty: none), else, when use_cache is CLI_WISDOM_CACHE (a run long enough
 * for measured plans to pay: docs/solver.md, "FFTW wisdom"), the user's cache, $XDG_CACHE_HOME/indentmap/
 * fftw-wisdom or ~/.cache/indentmap/fftw-wisdom (its folder is created); CLI_WISDOM_CACHE_LOOK (run
 * --check): that cache's path, the file and its folder neither made nor cleaned (a damaged file is told
 * as the run would remove it, and none is used); none with --no-wisdom (off). Sets
 * solver->wisdom_path (NULL for none; it may point into buffer, which must outlive the run). A damaged
 * wisdom file gets a notice on stderr and the run goes on (a damaged cache file is removed first); a
 * named file that may not be replaced (a surface, an input, a device) is an error (status.h), its
 * message naming where the path came from. IM_OK otherwise. */
struct im_solver_options;
enum { CLI_WISDOM_NO_CACHE = 0, CLI_WISDOM_CACHE = 1, CLI_WISDOM_CACHE_LOOK = 2 };
int cli_wisdom_resolve(const char *given, int off, int use_cache, struct im_solver_options *solver, char *buffer,
                       size_t size);

/* Exit statuses: 0 success, 1 a failure while running, 2 bad usage or input. */
enum { CLI_EXIT_OK = 0, CLI_EXIT_FAILURE = 1, CLI_EXIT_USAGE = 2 };

/* Option parsing that names the option in its error: "--n: 'abc' is not an integer". Each
 * returns 0 on success and prints the message to stderr otherwise. */
int cli_parse_int(const char *option, const char *text, long min, long max, int *out);
int cli_parse_u64(const char *option, const char *text, uint64_t *out);
int cli_parse_double(const char *option, const char *text, double min, double max, double *out);

/* --adhesion-law maugis-dugdale|exponential (solver.h: im_adhesion_law_parse): 0, or -1 after the message. */
int cli_parse_adhesion_law(const char *text, int *law);

/* A length unit for --unit or --height-unit (formats.h: m, mm, µm or um, nm, ...), copied into out
 * (16 bytes) in its canonical spelling ("um" becomes "µm"); 0, or -1 after naming the option and the known units. */
int cli_parse_length_unit(const char *option, const char *text, char *out);

/* --channel of an instrument file (formats.h: an index or a title, read through Gwyddion): 1 to 63 bytes,
 * copied into out (64 bytes); 0, or -1 after saying what was expected. */
int cli_parse_channel(const char *text, char *out);

/* --npy-order yx|xy: which index of a .npy array is x (formats.h: enum im_npy_order). 0, or -1 after saying
 * what was expected. */
int cli_parse_npy_order(const char *text, enum im_npy_order *out);

/* A path given to an option (--out, --psd, --frames, --wisdom): any text but the empty one, which names
 * no file (it failed later as "indentmap: : cannot create directory"). 0, or -1 after saying so. */
int cli_parse_path(const char *option, const char *text, const char **out);

/* A unit's name (e.g. --e-star-unit Pa): 1 to size - 1 bytes without blanks or quotes. */
int cli_parse_name(const char *option, const char *text, char *out, size_t size);

/* Preparation of a measured surface (prepare.c): crop (sides 0: none), then plane or curvature
 * removal. --fill is the reader's (im_surface_read_options.fill). */
typedef struct cli_preparation {
    int crop[4]; /* X0, Y0, NX, NY */
    enum im_detrend detrend;
    enum im_row_alignment align; /* scan lines, before the detrending */
    im_taper taper;              /* for spectral estimates only */
} cli_preparation;

/* --crop X0,Y0,NX,NY; --detrend none|plane|curvature; --window none|hann|tukey[:ALPHA]. Each returns
 * 0, or -1 after printing what was expected. */
int cli_parse_crop(const char *text, int crop[4]);
int cli_parse_detrend(const char *text, enum im_detrend *out);
/* --align none|median|mean|line (surface.h: im_surface_align_rows) */
int cli_parse_align(const char *text, enum im_row_alignment *out);
int cli_parse_taper(const char *text, im_taper *out);
/* --device cpu|gpu|auto (solver.h: IM_DEVICE_*) */
int cli_parse_device(const char *text, int *device);

/* The options that read and prepare a surface file, which `indent` and `surface` both take (one table
 * of them): their getopt codes (above every subcommand's own), CLI_SURFACE_FILE_OPTIONS (their
 * entries, for a subcommand's struct option table) and cli_apply_surface_file_option, which applies
 * code's option to read and preparation: 0, or -1 after printing its error or for a code that is not
 * one of them. *prepared (prepared not NULL) is set for those that change the heights read (all but
 * the units and the channel). */
enum {
    CLI_OPT_UNIT = 1000,
    CLI_OPT_HEIGHT_UNIT,
    CLI_OPT_CHANNEL,
    CLI_OPT_FILL,
    CLI_OPT_RESAMPLE,
    CLI_OPT_CROP,
    CLI_OPT_NPY_ORDER,
    CLI_OPT_DETREND,
    CLI_OPT_ALIGN
};
/* The surface formats every command that reads one names in its help (formats.h: im_surface_read's readers by
 * extension and signature, src/formats/surface_file.c; instrument files too through Gwyddion, `indentmap
 * formats`), and those `surface --out` writes: one list each, so that no help names fewer than it reads
 * (DA11). */
#define CLI_SURFACE_FORMATS ".npy, .gsf, .sdf, .nc, .x3p, .tmd, .h5, contact.engineering .zip or text"
#define CLI_SURFACE_WRITE_FORMATS ".npy, .gsf, .sdf, .nc, .x3p or text"

/* clang-format off */
#define CLI_SURFACE_FILE_OPTIONS                                    \
    {"unit", required_argument, 0, CLI_OPT_UNIT},                   \
    {"height-unit", required_argument, 0, CLI_OPT_HEIGHT_UNIT},     \
    {"channel", required_argument, 0, CLI_OPT_CHANNEL},             \
    {"fill", no_argument, 0, CLI_OPT_FILL},                         \
    {"resample-square", no_argument, 0, CLI_OPT_RESAMPLE},          \
    {"crop", required_argument, 0, CLI_OPT_CROP},                   \
    {"npy-order", required_argument, 0, CLI_OPT_NPY_ORDER},         \
    {"detrend", required_argument, 0, CLI_OPT_DETREND},             \
    {"align", required_argument, 0, CLI_OPT_ALIGN}
/* clang-format on */
int cli_apply_surface_file_option(int code, const char *arg, im_surface_read_options *read,
                                  cli_preparation *preparation, int *prepared);

/* Crops *surface (replacing it) and detrends it; a status naming the option on failure. */
int cli_prepare_surface(const cli_preparation *preparation, im_field **surface);

/* The warnings of reading the surface file path (of `points` points): --fill invented more than 5% of it,
 * so that statistics and contact on it are partly the fill's (finding D17: 30% of a profilometer scan
 * filled without a word); the reader took a unit the file does not state (finding D8b). */
void cli_warn_about_reading(const char *path, const im_surface_read_info *info, size_t points);

/* "plane removed, cropped to 256 x 256 at (0, 0), 3 missing points filled" */
void cli_describe_preparation(const cli_preparation *preparation, long filled, char *text, size_t size);

/* Parses a subcommand's options with getopt_long: apply(code, optarg, state) for each, which
 * returns 0 or prints its error and returns -1; usage(stdout) for -h or the option whose code is
 * help_code. Returns 1 after help, 0 when every option was applied, -1 after an error. optind is
 * left at the first operand. */
int cli_parse_options(int argc, char **argv, const struct option *options, int help_code, void (*usage)(FILE *),
                      int (*apply)(int code, const char *arg, void *state), void *state);

/* Outputs never overwrite inputs (io.h: the output guard). cli_protect_inputs registers
 * inputs[0..count) (NULLs skipped) as inputs of the process: no write may replace them or their
 * sidecars; 0, or -1 after printing why not.
 * cli_check_output_file: 0 when the file `output` (of option `option`; NULL: nothing) is none of
 * the registered inputs nor their sidecars; otherwise prints "indentmap: OPTION OUTPUT would
 * overwrite the input file INPUT (REALPATH); ..." and returns -1 (exit CLI_EXIT_USAGE). An output
 * folder's inputs: front/run_folder.h. */
int cli_protect_inputs(const char *const *inputs, int count);
int cli_check_output_file(const char *option, const char *output);

/* Prints "indentmap: MESSAGE" for the status's last error and returns the exit status that fits
 * it (2 for invalid input, 1 otherwise). */
int cli_report(int status);

#endif
