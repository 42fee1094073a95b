/* Ctrl-C during calls that run without the GIL. Python's own SIGINT handler only records the signal
 * for the interpreter, which acts on it once the call returns; for a long solve that would be many
 * seconds late. So, on the main thread (the only one Python delivers KeyboardInterrupt to), a call
 * arms a handler of its own for its duration: it sets the call's stop flag, which the library polls
 * (solver.h: im_solver_options.stop, scene.h: im_scene_run_options.stop), and then calls Python's
 * handler as before; when the call returns, Python's handler is put back and the signal is handed to
 * the interpreter (PyErr_CheckSignals), which raises KeyboardInterrupt, or runs the application's
 * own handler. Where SIGINT is ignored or not Python's (SIG_IGN, SIG_DFL) nothing is armed. */
#include "core.h"

#include <signal.h>
#include <string.h>

static unsigned long main_thread;
static struct sigaction python_handler; /* the handler a call replaced (valid while armed) */
static volatile sig_atomic_t *volatile armed_flag;

static void on_interrupt(int signal_number, siginfo_t *info, void *context)
{
    volatile sig_atomic_t *flag = armed_flag;
    if (flag)
        *flag = signal_number;
    if (python_handler.sa_flags & SA_SIGINFO)
        python_handler.sa_sigaction(signal_number, info, context);
    else if (python_handler.sa_handler != SIG_IGN && python_handler.sa_handler != SIG_DFL)
        python_handler.sa_handler(signal_number);
}

int py_interrupt_init(void)
{
    PyObject *threading = PyImport_ImportModule("threading");
    PyObject *thread = threading ? PyObject_CallMethod(threading, "main_thread", NULL) : NULL;
    PyObject *ident = thread ? PyObject_GetAttrString(thread, "ident") : NULL;
    main_thread = ident ? PyLong_AsUnsignedLong(ident) : 0;
    Py_XDECREF(ident);
    Py_XDECREF(thread);
    Py_XDECREF(threading);
    return PyErr_Occurred() ? -1 : 0;
}

void py_interrupt_arm(py_interrupt *call, volatile sig_atomic_t *flag)
{
    *flag = 0;
    call->armed = 0;
    call->outer_flag = NULL;
    if (PyThread_get_thread_ident() != main_thread)
        return;
    if (armed_flag) { /* nested: our handler is installed; saving it as Python's would loop */
        call->outer_flag = armed_flag;
        armed_flag = flag;
        return;
    }
    struct sigaction current;
    if (sigaction(SIGINT, NULL, &current) != 0 ||
        (!(current.sa_flags & SA_SIGINFO) && (current.sa_handler == SIG_IGN || current.sa_handler == SIG_DFL)))
        return;
    python_handler = current;
    armed_flag = flag;
    struct sigaction ours;
    memset(&ours, 0, sizeof ours);
    ours.sa_sigaction = on_interrupt;
    ours.sa_flags = SA_SIGINFO | (current.sa_flags & (SA_RESTART | SA_ONSTACK));
    sigemptyset(&ours.sa_mask);
    call->armed = sigaction(SIGINT, &ours, NULL) == 0;
}

int py_interrupt_disarm(py_interrupt *call, volatile sig_atomic_t *flag)
{
    if (call->outer_flag) {
        armed_flag = call->outer_flag;
        call->outer_flag = NULL;
    } else if (call->armed) {
        sigaction(SIGINT, &python_handler, NULL);
        armed_flag = NULL;
        call->armed = 0;
    }
    return *flag ? PyErr_CheckSignals() : 0;
}
