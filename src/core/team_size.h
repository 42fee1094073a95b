/* Internal: the OpenMP team of a solve, sized to the cores other processes leave free (issue 33). */
#ifndef INDENTMAP_CORE_TEAM_SIZE_H
#define INDENTMAP_CORE_TEAM_SIZE_H

/* The runnable tasks of a /proc/loadavg line ("0.06 1.33 2.10 2/93 23158": 2); -1 if it is not one. */
int team_parse_loadavg(const char *line);

/* Whether a /proc/PID/task/TID/stat line says that task is running (state R): 1 or 0; -1 if it is not
 * one. The command name, in parentheses, may hold spaces and parentheses. */
int team_parse_task_running(const char *line);

/* The threads of a team: the requested count, cut to the online cpus that the other runnable tasks
 * (others, machine-wide) leave free, and never below one; the requested count when this process may
 * use fewer cpus than are online (taskset, a cpuset): the machine-wide count cannot say whether its
 * own are free. */
int team_size_rule(int requested, int online, int usable, int others);

/* Sets the OpenMP thread count of the calling thread for a solve to team_size_rule's, from a look at
 * /proc (the last one, when this thread looked less than a tenth of a second ago), and returns it. Leaves the count as it is when the user chose (OMP_NUM_THREADS or
 * OMP_WAIT_POLICY set), inside a parallel region, inside another choice on this thread (a coarse level's
 * solve), or when one thread is requested. Each call is paired with team_restore. */
int team_choose(void);

/* Looks again when the last look is older than a tenth of a second, so that a long solve follows a
 * neighbour that starts or ends. */
void team_refresh(void);

/* Gives the caller back its thread count. */
void team_restore(void);

#endif
