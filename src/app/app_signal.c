/* app_signal: Ctrl-C (SIGINT), SIGTERM and SIGHUP (the terminal closed)
 * stop long runs cleanly. The first signal sets a flag that the main loop
 * and `meadow bench` check between
 * frames and configurations, so the results so far are still written; a
 * signal a second or more after it falls back to the default action (Ctrl-C
 * again kills a run that does not stop). Signals within that second count
 * as the first: GNU `timeout` signals the program, its process group and,
 * receiving its own, the program again, so one timeout delivers three or
 * four, and a count of signals had killed runs before they wrote what they
 * had. The handler is installed with sigaction and stays: signal() under
 * _POSIX_C_SOURCE has System V semantics, a handler reset to the default on
 * entry, so a second signal sent right after the first killed the run. */
#include "app/app.h"

#include <signal.h>
#include <string.h>
#include <time.h>

static volatile sig_atomic_t g_interrupted;
static struct timespec g_first; /* when the first signal came */

static void on_signal(int sig)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now); /* async-signal-safe (POSIX) */
    if (!g_interrupted) {
        g_first = now;
        g_interrupted = 1;
        return;
    }
    double since = (double)(now.tv_sec - g_first.tv_sec) + 1e-9 * (double)(now.tv_nsec - g_first.tv_nsec);
    if (since < 1.0) return;
    signal(sig, SIG_DFL);
    raise(sig);
}

void app_signal_install(void)
{
    g_interrupted = 0;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sa.sa_flags = SA_RESTART;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
}

bool app_interrupted(void) { return g_interrupted != 0; }
