/* app_signal: Ctrl-C (SIGINT) and SIGTERM stop long runs cleanly. The first
 * signal sets a flag that the main loop and `meadow bench` check between
 * frames and configurations, so the results so far are still written; the
 * third falls back to the default action. Not the second: `timeout` (GNU
 * coreutils) signals the program and then its whole process group, so one
 * timeout delivers the signal twice, and a second-signal rule had killed
 * `bench` runs before they wrote what they had. */
#include "app/app.h"

#include <signal.h>
#include <string.h>

static volatile sig_atomic_t g_interrupted;

static void on_signal(int sig)
{
    if (g_interrupted < 3) g_interrupted++;
    if (g_interrupted < 3) return;
    signal(sig, SIG_DFL);
    raise(sig);
}

void app_signal_install(void)
{
    g_interrupted = 0;
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
}

bool app_interrupted(void) { return g_interrupted != 0; }
