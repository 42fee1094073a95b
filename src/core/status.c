#include "indentmap/status.h"
#include "core/args.h"
#include "core/error_keep.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

enum { MESSAGE_CAPACITY = 1024 };
static _Thread_local char last_message[MESSAGE_CAPACITY];

const char *im_strstatus(int status)
{
    switch (status) {
    case IM_OK: return "success";
    case IM_EINVAL: return "invalid argument";
    case IM_EIO: return "input/output error";
    case IM_EFORMAT: return "malformed file";
    case IM_ENOMEM: return "not enough memory";
    case IM_ENUMERIC: return "numerical error";
    case IM_ENOCONV: return "no convergence";
    case IM_EEDGE: return "contact reached the surface edge";
    case IM_EUNSUPPORTED: return "not supported here";
    case IM_EINTERRUPTED: return "interrupted";
    default: return "unknown status";
    }
}

const char *im_last_error(void) { return last_message; }

int im_fail(int status, const char *fmt, ...)
{
    ARG_REQUIRE(fmt, "fmt");
    va_list args;
    va_start(args, fmt);
    vsnprintf(last_message, sizeof last_message, fmt, args);
    va_end(args);
    return status;
}

int im_fail_context(int status, const char *fmt, ...)
{
    ARG_REQUIRE(fmt, "fmt");
    char previous[MESSAGE_CAPACITY];
    memcpy(previous, last_message, sizeof previous);
    va_list args;
    va_start(args, fmt);
    int used = vsnprintf(last_message, sizeof last_message, fmt, args);
    va_end(args);
    if (used >= 0 && (size_t)used < sizeof last_message && previous[0] != '\0')
        snprintf(last_message + used, sizeof last_message - (size_t)used, ": %s", previous);
    return status;
}

_Static_assert(sizeof(((kept_error *)0)->message) == MESSAGE_CAPACITY, "a kept message holds any message");

void error_keep(kept_error *kept) { memcpy(kept->message, last_message, sizeof kept->message); }

int error_restore(const kept_error *kept, int status) { return im_fail(status, "%s", kept->message); }

static volatile sig_atomic_t *stop_flag;

void im_set_stop_flag(volatile sig_atomic_t *flag) { stop_flag = flag; }

int im_stop_requested(void) { return stop_flag ? (int)*stop_flag : 0; }
