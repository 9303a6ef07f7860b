/* app_signal: Ctrl-C (SIGINT) and SIGTERM stop long runs cleanly. The first
 * signal sets a flag that the main loop and `meadow bench` check between
 * frames and configurations, so the results so far are still written; a
 * second signal falls back to the default action. */
#include "app/app.h"

#include <signal.h>
#include <string.h>

static volatile sig_atomic_t g_interrupted;

static void on_signal(int sig)
{
    g_interrupted = 1;
    signal(sig, SIG_DFL);
}

void app_signal_install(void)
{
    g_interrupted = 0;
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
}

bool app_interrupted(void) { return g_interrupted != 0; }
