/* The team size of a solve (core/team_size.h): the /proc readers on lines of the kernel's format, the
 * rule, who decides (the user's environment, a parallel region, a nested solve), and a busy process of
 * our own making that the choice must leave a core to. */
#include "support.h"

#include "core/team_size.h"

#include <omp.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static void test_loadavg_lines(void **state)
{
    (void)state;
    assert_int_equal(team_parse_loadavg("0.06 1.33 2.10 2/93 23158\n"), 2);
    assert_int_equal(team_parse_loadavg("12.50 9.01 7.33 17/1204 99999"), 17);
    assert_int_equal(team_parse_loadavg(""), -1);
    assert_int_equal(team_parse_loadavg("0.06 1.33 2.10"), -1);
    assert_int_equal(team_parse_loadavg("0.06 1.33 2.10 2/93"), -1);        /* no last pid */
    assert_int_equal(team_parse_loadavg("0.06 1.33 2.10 94/93 23158"), -1); /* more running than tasks */
    assert_int_equal(team_parse_loadavg("0.06 1.33 2.10 -1/93 23158"), -1);
    assert_int_equal(team_parse_loadavg("a b c 2/93 23158"), -1);
}

static void test_task_stat_lines(void **state)
{
    (void)state;
    assert_int_equal(team_parse_task_running("4242 (indentmap) R 4200 4242 4200 0 -1 4194304 90 0 0 0\n"), 1);
    assert_int_equal(team_parse_task_running("4243 (indentmap) S 4200 4242 4200 0 -1 4194368 0 0 0 0\n"), 0);
    /* a command name may hold ") R " itself: the state follows the last ')' */
    assert_int_equal(team_parse_task_running("4244 (a) R (b) S 1 4244 4244 0 -1 0 0 0 0 0\n"), 0);
    assert_int_equal(team_parse_task_running("4245 (x y) R 1 4245 4245 0 -1 0 0 0 0 0\n"), 1);
    assert_int_equal(team_parse_task_running(""), -1);
    assert_int_equal(team_parse_task_running("4246 indentmap R 1"), -1);
    assert_int_equal(team_parse_task_running("4247 (indentmap)R 1"), -1);
    assert_int_equal(team_parse_task_running("4248 (indentmap) "), -1);
}

static void test_rule(void **state)
{
    (void)state;
    assert_int_equal(team_size_rule(2, 2, 2, 0), 2); /* a quiet machine: all */
    assert_int_equal(team_size_rule(2, 2, 2, 1), 1); /* one busy neighbour on 2 cores */
    assert_int_equal(team_size_rule(2, 2, 2, 9), 1); /* never none */
    assert_int_equal(team_size_rule(8, 16, 16, 4), 8);
    assert_int_equal(team_size_rule(8, 16, 16, 11), 5);
    assert_int_equal(team_size_rule(4, 2, 2, 0), 2); /* no more than the cpus */
    assert_int_equal(team_size_rule(1, 4, 4, 0), 1);
    assert_int_equal(team_size_rule(2, 16, 2, 15), 2); /* bound to 2 of 16: cannot tell, as asked */
}

static void clear_users_choice(void)
{
    unsetenv("OMP_NUM_THREADS");
    unsetenv("OMP_WAIT_POLICY");
}

static void test_the_caller_gets_its_count_back(void **state)
{
    (void)state;
    clear_users_choice();
    const int saved = omp_get_max_threads();
    omp_set_num_threads(2);
    const int team = team_choose();
    assert_true(team == 1 || team == 2);
    assert_int_equal(omp_get_max_threads(), team);
    assert_int_equal(team_choose(), team); /* a coarse level's solve inside: no second look */
    team_refresh();
    team_restore();
    assert_int_equal(omp_get_max_threads(), team);
    team_restore();
    assert_int_equal(omp_get_max_threads(), 2);
    omp_set_num_threads(saved);
}

/* The caller's count as it is: requested */
static void assert_untouched(int requested)
{
    assert_int_equal(team_choose(), requested);
    assert_int_equal(omp_get_max_threads(), requested);
    team_restore();
    assert_int_equal(omp_get_max_threads(), requested);
}

static void test_the_users_choice_wins(void **state)
{
    (void)state;
    const int saved = omp_get_max_threads();
    const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    omp_set_num_threads((int)cpus + 3); /* more than any rule would keep */
    clear_users_choice();
    setenv("OMP_NUM_THREADS", "7", 1);
    assert_untouched((int)cpus + 3);
    clear_users_choice();
    setenv("OMP_WAIT_POLICY", "active", 1);
    assert_untouched((int)cpus + 3);
    clear_users_choice();
#pragma omp parallel num_threads(2)
    {
        omp_set_num_threads(5); /* this thread's count inside the region */
        assert_untouched(5);
    }
    omp_set_num_threads(saved);
}

/* A child process that spins until it is killed. */
static pid_t start_busy_process(void)
{
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0)
        for (volatile unsigned long spin = 0;; ++spin)
            ;
    nanosleep(&(struct timespec){0, 150000000}, NULL); /* until it runs, and any look is older than 0.1 s */
    return child;
}

static void test_a_busy_process_keeps_a_core(void **state)
{
    (void)state;
    const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    if (cpus < 2 || omp_get_num_procs() < cpus) /* bound to some cpus: the rule keeps the count */
        skip();
    clear_users_choice();
    const int saved = omp_get_max_threads();
    omp_set_num_threads((int)cpus);
    pid_t busy = start_busy_process();
    const int team = team_choose();
    team_restore();
    kill(busy, SIGKILL);
    waitpid(busy, NULL, 0);
    omp_set_num_threads(saved);
    assert_true(team >= 1 && team <= cpus - 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_loadavg_lines),
        cmocka_unit_test(test_task_stat_lines),
        cmocka_unit_test(test_rule),
        cmocka_unit_test(test_the_caller_gets_its_count_back),
        cmocka_unit_test(test_the_users_choice_wins),
        cmocka_unit_test(test_a_busy_process_keeps_a_core),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
