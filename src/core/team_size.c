/* The OpenMP team of a solve (see team_size.h).
 *
 * libgomp spins 300000 times at every barrier before it sleeps, and reads its spin count only when it
 * loads, which a library cannot precede. With one busy process on 2 cores, a 2-thread solve spends its
 * barriers waiting for a thread that shares its core with the neighbour: through the library a 512^2
 * solve took 3-10x its 1-thread time (docs/benchmarks.md, "Threads for library users"). A team no larger
 * than the free cores has no such wait, whatever the spin. OpenMP's own dynamic adjustment
 * (OMP_DYNAMIC) does not help: libgomp sizes it from the 15-minute load average, which lags by minutes
 * and counts our own threads. /proc/loadavg's fourth field is the number of tasks runnable now; our
 * own running threads (the caller, and workers still spinning after the last region) are taken off.
 *
 * The plans' FFTW threads are not touched: a plan made for two threads runs its two halves one after
 * the other on a team of one (FFTW's OpenMP loops take the team in force), the same arithmetic. */
#include "core/team_size.h"

#include <dirent.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

enum { LOOKS = 3 };                  /* the fewest others seen over these (a task that only woke) */
static const long LOOK_GAP_NS = 1e5; /* between looks */
static const double RELOOK_S = 0.1;  /* team_refresh's period */

int team_parse_loadavg(const char *line)
{
    double one, five, fifteen;
    int runnable, total, end = 0;
    if (sscanf(line, "%lf %lf %lf %d/%d %*d%n", &one, &five, &fifteen, &runnable, &total, &end) != 5 || end == 0 ||
        runnable < 0 || total < runnable)
        return -1;
    return runnable;
}

int team_parse_task_running(const char *line)
{
    const char *name_end = strrchr(line, ')');
    if (!name_end || !strchr(line, '(') || name_end[1] != ' ' || name_end[2] == '\0' || name_end[3] != ' ')
        return -1;
    return name_end[2] == 'R';
}

int team_size_rule(int requested, int online, int usable, int others)
{
    if (usable < online)
        return requested;
    const int free_cpus = online - others;
    const int team = free_cpus < requested ? free_cpus : requested;
    return team > 1 ? team : 1;
}

/* The first line of a file, or "" when it cannot be read. */
static void read_line(const char *path, char *line, int size)
{
    FILE *f = fopen(path, "r");
    line[0] = '\0';
    if (f && !fgets(line, size, f))
        line[0] = '\0';
    if (f)
        fclose(f);
}

static int own_running_threads(void)
{
    DIR *tasks = opendir("/proc/self/task");
    if (!tasks)
        return 0;
    int running = 0;
    for (struct dirent *task; (task = readdir(tasks));) {
        char path[64], line[256];
        if (task->d_name[0] == '.')
            continue;
        snprintf(path, sizeof path, "/proc/self/task/%.20s/stat", task->d_name);
        read_line(path, line, sizeof line);
        running += team_parse_task_running(line) == 1;
    }
    closedir(tasks);
    return running;
}

/* The fewest runnable tasks of other processes over a few looks; 0 where /proc cannot tell. */
static int other_runnable_tasks(void)
{
    int fewest = -1;
    for (int look = 0; look < LOOKS; ++look) {
        char line[128];
        if (look > 0)
            nanosleep(&(struct timespec){0, LOOK_GAP_NS}, NULL);
        read_line("/proc/loadavg", line, sizeof line);
        const int runnable = team_parse_loadavg(line);
        if (runnable < 0)
            return 0;
        const int others = runnable - own_running_threads();
        if (fewest < 0 || others < fewest)
            fewest = others;
    }
    return fewest > 0 ? fewest : 0;
}

/* This thread's open choice: the caller's thread count (0: not ours to change), and the last look,
 * kept between solves so that a run of small solves looks at most every RELOOK_S. */
static _Thread_local struct {
    int depth; /* team_choose calls not yet restored */
    int requested;
    int team, looked_for; /* the last look's team, and the count it was cut from */
    double looked;
} open_choice;

static int looked_lately(void)
{
    return open_choice.looked_for == open_choice.requested && omp_get_wtime() - open_choice.looked < RELOOK_S;
}

static int set_team(void)
{
    if (!looked_lately()) {
        const int online = (int)sysconf(_SC_NPROCESSORS_ONLN), usable = omp_get_num_procs();
        open_choice.team = team_size_rule(open_choice.requested, online, usable, other_runnable_tasks());
        open_choice.looked_for = open_choice.requested;
        open_choice.looked = omp_get_wtime();
    }
    omp_set_num_threads(open_choice.team);
    return open_choice.team;
}

/* Set and not empty (libgomp ignores an empty one: its defaults hold). */
static int is_set(const char *name)
{
    const char *value = getenv(name);
    return value && value[0];
}

static int users_choice(void) { return is_set("OMP_NUM_THREADS") || is_set("OMP_WAIT_POLICY"); }

int team_choose(void)
{
    const int requested = omp_get_max_threads();
    if (open_choice.depth++ > 0)
        return requested;
    open_choice.requested = requested > 1 && !omp_in_parallel() && !users_choice() ? requested : 0;
    return open_choice.requested ? set_team() : requested;
}

void team_refresh(void)
{
    if (open_choice.requested && !looked_lately())
        set_team();
}

void team_restore(void)
{
    if (--open_choice.depth == 0 && open_choice.requested) {
        omp_set_num_threads(open_choice.requested);
        open_choice.requested = 0;
    }
}
