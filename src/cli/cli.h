/* The command line: one function per subcommand, each parsing its own options. */
#ifndef INDENTMAP_CLI_H
#define INDENTMAP_CLI_H

#include <signal.h>
#include <stdint.h>
#include <stdio.h>

struct option;

/* Subcommands: argv[0] is the subcommand's name. Return the process exit status. */
int cli_surface(int argc, char **argv);
int cli_info(int argc, char **argv);
int cli_render(int argc, char **argv);
int cli_indent(int argc, char **argv);
int cli_theory(int argc, char **argv);
int cli_run(int argc, char **argv);
/* One grid over MPI ranks (mpi_indent.c); exists only where IM_HAVE_MPI (indentmap/mpi.h). */
int cli_mpi_indent(int argc, char **argv);

/* SIGINT/SIGTERM (interrupt.c): cli_interrupt_install makes them store their number in
 * cli_stop_signal (a second one ends the process); cli_interrupt_exit_status is 128 + it. */
extern volatile sig_atomic_t cli_stop_signal;
int cli_interrupt_install(void);
int cli_interrupt_exit_status(void);

/* Exit statuses: 0 success, 1 a failure while running, 2 bad usage or input. */
enum { CLI_EXIT_OK = 0, CLI_EXIT_FAILURE = 1, CLI_EXIT_USAGE = 2 };

/* Option parsing that names the option in its error: "--n: 'abc' is not an integer". Each
 * returns 0 on success and prints the message to stderr otherwise. */
int cli_parse_int(const char *option, const char *text, long min, long max, int *out);
int cli_parse_u64(const char *option, const char *text, uint64_t *out);
int cli_parse_double(const char *option, const char *text, double min, double max, double *out);

/* Parses a subcommand's options with getopt_long: apply(code, optarg, state) for each, which
 * returns 0 or prints its error and returns -1; usage(stdout) for -h or the option whose code is
 * help_code. Returns 1 after help, 0 when every option was applied, -1 after an error. optind is
 * left at the first operand. */
int cli_parse_options(int argc, char **argv, const struct option *options, int help_code, void (*usage)(FILE *),
                      int (*apply)(int code, const char *arg, void *state), void *state);

/* Outputs never overwrite inputs. Paths are compared by realpath (symlinks, "." and ".." resolved)
 * and, for a symlink given as an input, by the link's own name. inputs[0..count) may hold NULLs
 * (skipped); inputs that do not exist are skipped (their reader reports them).
 * cli_check_output_file: 0 when the file `output` (of option `option`) is none of the inputs;
 * otherwise prints "indentmap: OPTION OUTPUT would overwrite the input file INPUT (REALPATH); ..."
 * and returns -1 (exit CLI_EXIT_USAGE).
 * cli_check_output_folder: the same for a folder `dir` into which a command writes the files whose
 * names writes(name, state) accepts: -1, naming DIR/NAME and the input, when an input lies directly
 * in dir under such a name. */
int cli_check_output_file(const char *option, const char *output, const char *const *inputs, int count);
int cli_check_output_folder(const char *option, const char *dir, int (*writes)(const char *name, const void *state),
                            const void *state, const char *const *inputs, int count);

/* Prints "indentmap: MESSAGE" for the status's last error and returns the exit status that fits
 * it (2 for invalid input, 1 otherwise). */
int cli_report(int status);

#endif
