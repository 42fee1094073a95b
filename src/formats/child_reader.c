/* A file read by a program of indentmap's own in a child process: finding it, starting it, its end. */
#define _GNU_SOURCE /* pipe2, secure_getenv, dladdr */
#include "formats/child_reader.h"

#include "indentmap/status.h"

#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* name in the folder of file (an absolute path), when it is an executable there. */
static const char *beside(const char *file, const char *name)
{
    static __thread char path[4096];
    const char *slash = strrchr(file, '/');
    if (file[0] != '/' || !slash || (size_t)(slash - file) + strlen(name) + 2 > sizeof path)
        return NULL;
    snprintf(path, sizeof path, "%.*s/%s", (int)(slash - file), file, name);
    return access(path, X_OK) == 0 ? path : NULL;
}

/* The program beside the running executable (a build tree's, or bin/ beside libexec/ when installed so). */
static const char *beside_this_program(const char *name)
{
    char executable[4096];
    ssize_t length = readlink("/proc/self/exe", executable, sizeof executable - 1);
    if (length <= 0)
        return NULL;
    executable[length] = '\0';
    return beside(executable, name);
}

/* The program beside the shared object that holds this code, when that is not the executable: a build
 * tree's libindentmap.so, or the Python package's extension module, beside which the build copies the
 * programs (python3 is not beside them). A relative name (as the loader was given it) is not trusted. */
static const char *beside_this_code(const char *name)
{
    Dl_info object;
    if (!dladdr((void *)beside_this_code, &object) || !object.dli_fname)
        return NULL;
    return beside(object.dli_fname, name);
}

const char *child_program_path(const child_program *program)
{
    const char *chosen = secure_getenv(program->environment);
    if (chosen && chosen[0])
        return access(chosen, X_OK) == 0 ? chosen : NULL;
    const char *found = beside_this_program(program->name);
    if (!found)
        found = beside_this_code(program->name);
    if (found)
        return found;
    if (program->installed && access(program->installed, X_OK) == 0)
        return program->installed;
    return NULL;
}

int child_stream_line(FILE *stream, char *line)
{
    if (!fgets(line, CHILD_STREAM_LINE, stream)) {
        line[0] = '\0';
        return 0;
    }
    size_t length = strcspn(line, "\n");
    if (line[length] != '\n')
        for (int c = fgetc(stream); c != EOF && c != '\n'; c = fgetc(stream))
            ; /* a longer line is cut */
    line[length] = '\0';
    for (char *at = line; *at; ++at)
        if ((unsigned char)*at < 0x20 && *at != '\t')
            *at = '?';
    return 1;
}

void child_stream_put_line(FILE *stream, const char *prefix, const char *text)
{
    fputs(prefix, stream);
    for (const char *at = text; *at; ++at)
        fputc((unsigned char)*at < 0x20 && *at != '\t' ? '?' : *at, stream);
    fputc('\n', stream);
}

/* The program's environment for one read: a pipe for its stream, a temporary file for its errors. */
typedef struct child_process {
    pid_t child;
    FILE *from, *errors;
    int started;
    int answered;
} child_process;

/* Spawn attributes: no signal blocked and the default actions for those a caller may have changed
 * (Python ignores SIGPIPE; the alarm that bounds a read must end it). */
static void default_signals(posix_spawnattr_t *attributes)
{
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    int reset[] = {SIGPIPE, SIGINT, SIGTERM, SIGALRM, SIGCHLD};
    for (size_t k = 0; k < sizeof reset / sizeof *reset; ++k)
        sigaddset(&defaults, reset[k]);
    posix_spawnattr_init(attributes);
    posix_spawnattr_setsigmask(attributes, &none);
    posix_spawnattr_setsigdefault(attributes, &defaults);
    posix_spawnattr_setflags(attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
}

/* Starts the program on path (after "--": a file may be named like an option), its stream on a pipe,
 * its errors (a library's warnings, a loader's message) into a temporary file quoted on failure. */
static int start_child(const child_program *program, const char *executable, const char *path, const char *channel,
                       child_process *process)
{
    int ends[2];
    process->errors = tmpfile();
    if (!process->errors || pipe2(ends, O_CLOEXEC) != 0)
        return im_fail(IM_EIO, "%s: cannot start %s: %s", path, program->reader, strerror(errno));
    fcntl(ends[0], F_SETPIPE_SZ,
          1 << 20); /* fewer, larger hand-overs of the values; the default is kept if refused */
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, ends[1], 1);
    posix_spawn_file_actions_adddup2(&actions, fileno(process->errors), 2);
    posix_spawnattr_t attributes;
    default_signals(&attributes);
    char *arguments[6] = {(char *)executable}, **next = arguments + 1;
    if (program->mode)
        *next++ = (char *)program->mode;
    *next++ = "--";
    *next++ = (char *)path;
    *next = channel[0] ? (char *)channel : NULL;
    int failed = posix_spawn(&process->child, executable, &actions, &attributes, arguments, environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    close(ends[1]);
    if (failed) {
        close(ends[0]);
        return im_fail(IM_EIO, "%s: cannot start %s %s: %s", path, program->reader, executable, strerror(failed));
    }
    process->started = 1;
    process->from = fdopen(ends[0], "rb");
    if (process->from)
        return IM_OK;
    close(ends[0]); /* the program's next write fails and ends it */
    return im_fail(IM_ENOMEM, "%s: cannot read %s: %s", path, program->reader, strerror(errno));
}

/* The last line the program wrote on its standard error, or "". */
static void last_error_line(FILE *errors, char *line, size_t size)
{
    char text[CHILD_STREAM_LINE];
    line[0] = '\0';
    rewind(errors);
    while (fgets(text, sizeof text, errors))
        if (text[strspn(text, " \t\r\n")])
            snprintf(line, size, "%.*s", (int)strcspn(text, "\r\n"), text);
}

/* The program's end: a crash or a hang in its parser is a refusal of the file, not of the caller. When
 * another part of the process reaps children (SIGCHLD ignored, a watcher), the status is gone: the
 * stream alone then decides. */
static int finish_child(const child_program *program, const char *path, const child_process *process, int parsed)
{
    int how = 0;
    pid_t ended;
    while ((ended = waitpid(process->child, &how, 0)) < 0 && errno == EINTR)
        ;
    if (ended < 0)
        return parsed;
    char said[200];
    last_error_line(process->errors, said, sizeof said);
    if (WIFSIGNALED(how) && WTERMSIG(how) == SIGALRM)
        return im_fail(IM_EFORMAT, "%s: %s ran out of time reading it (%s)", path, program->parser, program->damage);
    if (WIFSIGNALED(how) && WTERMSIG(how) != SIGPIPE)
        return im_fail(IM_EFORMAT, "%s: %s crashed reading it (signal %d): %s%s%s", path, program->parser,
                       WTERMSIG(how), program->damage, said[0] ? " It said: " : "", said);
    if (parsed != IM_OK && !process->answered && WIFEXITED(how) && WEXITSTATUS(how) != 0)
        return im_fail(IM_EFORMAT, "%s: %s ended with status %d%s%s", path, program->reader, WEXITSTATUS(how),
                       said[0] ? ": " : "", said);
    return parsed;
}

int child_read(const child_program *program, const char *executable, const char *path, const char *channel,
               child_stream_parser parse, void *result)
{
    child_process process = {0};
    int status = start_child(program, executable, path, channel, &process);
    if (status == IM_OK)
        status = parse(process.from, path, result, &process.answered);
    if (process.from)
        fclose(process.from); /* before the wait: a program still writing ends on the closed pipe */
    if (process.started)
        status = finish_child(program, path, &process, status);
    if (process.errors)
        fclose(process.errors);
    return status;
}
