/* indentmap/status.h: status codes and error messages shared by every module.
 *
 * Entry points:
 *   im_last_error, im_strstatus        the last failure's message on this thread; a status's name
 *   im_fail, im_fail_context           record a failure (returns its status)
 *   im_set_stop_flag, im_stop_requested  the flag that interrupts long reads
 *
 * Every fallible function returns an int status (IM_OK on success), GSL style. On failure the
 * function also records a message naming the file, line or parameter and what was expected;
 * im_last_error() returns it. The message is per thread, so OpenMP workers do not clobber each
 * other's messages.
 *
 * Misuse (issue 32, SQLite's rule: a misuse is reported, not undefined): every public function
 * checks its handles, output pointers and field views at entry. A NULL where a pointer is required,
 * or a field view that breaks field.h's invariants (im_field_check_view), gives IM_EINVAL with a
 * message naming the function and the argument ("im_surface_psd: out is NULL: expected a pointer"),
 * never a crash. Functions returning void or a value record the same message and do nothing or
 * return their safe result (NULL for a pointer, NaN for a number, 0 for a count or flag; each
 * header says which); *_free, *_release, *_close and *_abort accept NULL silently.
 * tests/test_api_misuse.c holds every public function to this.
 *
 * Threads: the message is per thread (each thread reads its own failures only); every function here
 * is thread-safe, but im_set_stop_flag sets one process-wide pointer: set it before work starts.
 */
#ifndef INDENTMAP_STATUS_H
#define INDENTMAP_STATUS_H

#include <signal.h>

#ifdef __cplusplus
extern "C" {
#endif

enum im_status {
    IM_OK = 0,
    IM_EINVAL,       /* a parameter is out of range or malformed */
    IM_EIO,          /* a file could not be opened, read or written */
    IM_EFORMAT,      /* a file's contents do not follow its format */
    IM_ENOMEM,       /* an allocation failed, or would exceed the memory available */
    IM_ENUMERIC,     /* NaN or Inf where finite numbers are required, or a numeric failure */
    IM_ENOCONV,      /* an iteration did not converge within its cap */
    IM_EEDGE,        /* contact reached the edge of the modelled surface */
    IM_EUNSUPPORTED, /* a feature is not available on this machine (e.g. no GL context) */
    IM_EINTERRUPTED  /* the run was interrupted by a signal */
};

/* Short fixed description of a status code ("invalid argument", ...). Never NULL. */
const char *im_strstatus(int status);

/* The last detailed message recorded on this thread, or "" if none. */
const char *im_last_error(void);

/* Records a printf-style message for this thread and returns status, so that callers can write
 * `return im_fail(IM_EINVAL, "n = %d: expected n >= 2", n);`. Messages longer than 1023 bytes are
 * cut. A NULL fmt is a misuse: IM_EINVAL naming it. */
int im_fail(int status, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Prefixes the current message with context ("reading s.npy: ...") and returns status; a NULL fmt
 * as im_fail's. */
int im_fail_context(int status, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Interruption of long operations that take no stop flag of their own (file reads): the program
 * registers the flag its SIGINT/SIGTERM handler sets (NULL, the default, disables the check), and
 * such operations end with IM_EINTERRUPTED once it is non-zero. The flag stays owned by the caller
 * and must outlive every read. im_stop_requested returns the flag's value (the signal number), 0
 * when none is registered or none has arrived. */
void im_set_stop_flag(volatile sig_atomic_t *flag);
int im_stop_requested(void);

/* Messages of long operations (scene runs), handed to the caller instead of being printed: the
 * library never writes to stdout or stderr. A log callback, like SQLite's log hook, receives each
 * message as one line of text without a prefix or newline (valid only during the call); user is
 * the pointer given beside the callback. Where no callback is given (NULL), messages are dropped.
 * The indentmap program prints them on stderr as "indentmap: MESSAGE". */
typedef enum im_log_level {
    IM_LOG_INFO = 0,   /* progress of a stage ("table: 51 surfaces: 51 solved, ...") */
    IM_LOG_WARNING = 1 /* a notice the user should see even when quiet: a kept result is stale
                           or damaged and solved again, a stale lock was taken over */
} im_log_level;
typedef void (*im_log_fn)(void *user, im_log_level level, const char *message);

/* Progress of a stage that works through `total` items (surfaces of an ensemble): called with
 * done = 1, ..., total as each item finishes, in order of finishing. stage names the stage as its
 * log lines do ("table", "histories"). */
typedef void (*im_progress_fn)(void *user, const char *stage, int done, int total);

#ifdef __cplusplus
}
#endif

#endif
