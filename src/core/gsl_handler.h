/* core/gsl_handler.h: GSL's error handler switched off (its default aborts; the library returns
 * statuses) for the length of a GSL call, and the application's put back once no such call of the
 * library runs (a count under a lock: callers on several threads at once). Every off is paired with
 * a restore. Shared by the theory's quadratures and the indenter's profile splines. */
#ifndef INDENTMAP_CORE_GSL_HANDLER_H
#define INDENTMAP_CORE_GSL_HANDLER_H

void core_gsl_handler_off(void);
void core_gsl_handler_restore(void);

#endif
