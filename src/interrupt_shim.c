/* Stopping a run on SIGINT or SIGTERM, for vemcontact_interrupt.
 *
 * The handler only records the signal in a sig_atomic_t (the one thing an
 * asynchronous signal handler may safely do besides a few system calls); the
 * program looks at it at safe points (between steps and between contact
 * iterations) and ends the run there through its error object, so that the
 * results of the completed steps are written and closed normally.  The handler
 * is installed with SA_RESETHAND: a second SIGINT or SIGTERM, sent when the
 * first takes too long to reach a safe point (a long factorization), ends the
 * process at once with the default action.  SA_RESTART keeps interrupted reads
 * and writes going.
 */
#define _GNU_SOURCE
#include <signal.h>
#include <string.h>

static volatile sig_atomic_t vc_stop_signal = 0;

static void vc_on_stop_signal(int signo) {
    vc_stop_signal = signo;
}

/* Install the handler for SIGINT and SIGTERM; 0 or -1 when sigaction failed. */
int vc_interrupt_install(void) {
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = vc_on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND | SA_RESTART;
    if (sigaction(SIGINT, &sa, NULL) != 0) return -1;
    if (sigaction(SIGTERM, &sa, NULL) != 0) return -1;
    return 0;
}

/* The signal received (SIGINT or SIGTERM), 0 if none. */
int vc_interrupt_signal(void) {
    return (int)vc_stop_signal;
}

/* The numbers of SIGINT and SIGTERM on this system. */
int vc_interrupt_sigint(void) { return SIGINT; }
int vc_interrupt_sigterm(void) { return SIGTERM; }
