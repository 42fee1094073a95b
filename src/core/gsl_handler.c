#include "core/gsl_handler.h"

#include <gsl/gsl_errno.h>
#include <pthread.h>

/* GSL's error handler is one process-wide pointer; its default aborts the program, and the library
 * must return statuses instead. So it is switched off while any GSL call of the library runs and
 * the application's handler, whatever it was, is put back when the last one ends: a count, under a
 * lock, since quadratures run on several threads at once. */
static pthread_mutex_t gsl_handler_lock = PTHREAD_MUTEX_INITIALIZER;
static int gsl_handler_users;
static gsl_error_handler_t *application_gsl_handler;

void core_gsl_handler_off(void)
{
    pthread_mutex_lock(&gsl_handler_lock);
    if (gsl_handler_users++ == 0)
        application_gsl_handler = gsl_set_error_handler_off();
    pthread_mutex_unlock(&gsl_handler_lock);
}

void core_gsl_handler_restore(void)
{
    pthread_mutex_lock(&gsl_handler_lock);
    if (--gsl_handler_users == 0)
        gsl_set_error_handler(application_gsl_handler);
    pthread_mutex_unlock(&gsl_handler_lock);
}
