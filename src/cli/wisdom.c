/* The FFTW wisdom file of a run (see cli.h and docs/solver.md, "FFTW wisdom"). */
#include "cli/cli.h"

#include "indentmap/io.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* $XDG_CACHE_HOME/indentmap/fftw-wisdom, else ~/.cache/indentmap/fftw-wisdom (the XDG base directory
 * rules: a relative XDG_CACHE_HOME is ignored); its folder is created when `make`. 0 when there is none
 * (no HOME, a path too long, a folder that cannot be made). */
static int cache_path(char *path, size_t size, int make)
{
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    char folder[4096];
    int length;
    if (xdg && xdg[0] == '/')
        length = snprintf(folder, sizeof folder, "%s/indentmap", xdg);
    else if (home && home[0])
        length = snprintf(folder, sizeof folder, "%s/.cache/indentmap", home);
    else
        return 0;
    if (length < 0 || (size_t)length >= sizeof folder || (make && im_make_directories(folder) != IM_OK))
        return 0;
    length = snprintf(path, size, "%s/fftw-wisdom", folder);
    return length > 0 && (size_t)length < size;
}

/* The cache is ours: a file there that is not wisdom FFTW accepts is removed (with a notice) and
 * planning writes a new one; if it cannot be removed, this run keeps no wisdom. Without `remove`
 * (--check), the same judgement is told and nothing removed: no wisdom is planned with then. */
static void use_cache_file(const char *path, int remove, im_solver_options *solver)
{
    solver->wisdom_path = path;
    if (im_solver_wisdom_verify(solver) == IM_OK)
        return;
    fprintf(stderr, "indentmap: notice: %s; ", im_last_error());
    if (!remove) {
        fprintf(stderr, "the run would remove it and write it afresh\n");
        solver->wisdom_path = NULL;
        return;
    }
    if (unlink(path) == 0 || errno == ENOENT) {
        fprintf(stderr, "removed, it is written afresh\n");
        return;
    }
    fprintf(stderr, "it cannot be removed (%s): this run keeps no FFTW wisdom\n", strerror(errno));
    solver->wisdom_path = NULL;
}

int cli_wisdom_resolve(const char *given, int off, int use_cache, im_solver_options *solver, char *buffer,
                       size_t size)
{
    const char *env = getenv("IM_FFTW_WISDOM");
    const char *path = off ? NULL : given ? given : env;
    const char *source = given ? "--wisdom" : "IM_FFTW_WISDOM";
    solver->wisdom_path = NULL;
    if (off || (!given && env && !env[0])) /* --no-wisdom, or IM_FFTW_WISDOM set but empty */
        return IM_OK;
    if (!path) {
        /* --check looks at the cache as it is now (it may not exist yet), making and removing nothing */
        int look = use_cache == CLI_WISDOM_CACHE_LOOK;
        if (use_cache != CLI_WISDOM_NO_CACHE && cache_path(buffer, size, !look))
            use_cache_file(buffer, !look, solver);
        return IM_OK;
    }
    solver->wisdom_path = path;
    int status = im_solver_wisdom_verify(solver);
    if (status == IM_EFORMAT) { /* a damaged wisdom file the user named: planning replaces it */
        fprintf(stderr, "indentmap: notice: %s; it is planned afresh and replaced\n", im_last_error());
        return IM_OK;
    }
    return status == IM_OK ? IM_OK : im_fail_context(status, "%s %s", source, path);
}
