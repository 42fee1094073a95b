/* Internal: a failure's message kept across the cleanup after it. Writing a run's record, removing
 * stale files or drawing frames after a failed step may record messages of their own (status.h: one
 * message per thread); the run's error must stay the one reported:
 *
 *     kept_error kept;
 *     error_keep(&kept);
 *     ... cleanup that may fail ...
 *     return error_restore(&kept, status);
 */
#ifndef INDENTMAP_CORE_ERROR_KEEP_H
#define INDENTMAP_CORE_ERROR_KEEP_H

typedef struct kept_error {
    char message[1024]; /* status.c's capacity: a kept message is never cut */
} kept_error;

/* Copies this thread's current message (im_last_error) into kept. */
void error_keep(kept_error *kept);

/* Records the kept message again as this thread's message and returns status (as im_fail). */
int error_restore(const kept_error *kept, int status);

#endif
