/* core_log: one-line diagnostics on stderr (or a host's sink), with
 * counters for tests. */
#include "core.h"

#include <stdarg.h>
#include <stdio.h>

static bool g_quiet;
static int g_warns, g_errors;
static core_log_sink_fn g_sink;
static void *g_sink_user;

static void log_line(int severity, const char *level, const char *fmt, va_list ap)
{
    char buf[2048];
    vsnprintf(buf, sizeof buf, fmt, ap);
    if (g_sink) g_sink(severity, buf, g_sink_user);
    else fprintf(stderr, "meadow: %s%s\n", level, buf);
}

void core_log_set_quiet(bool quiet) { g_quiet = quiet; }
void core_log_set_sink(core_log_sink_fn sink, void *user)
{
    g_sink = sink;
    g_sink_user = user;
}
int core_log_warn_count(void) { return g_warns; }
int core_log_error_count(void) { return g_errors; }

void core_log_info(const char *fmt, ...)
{
    if (g_quiet) return;
    va_list ap;
    va_start(ap, fmt);
    log_line(0, "", fmt, ap);
    va_end(ap);
}

void core_log_warn(const char *fmt, ...)
{
    g_warns++;
    va_list ap;
    va_start(ap, fmt);
    log_line(1, "warning: ", fmt, ap);
    va_end(ap);
}

void core_log_error(const char *fmt, ...)
{
    g_errors++;
    va_list ap;
    va_start(ap, fmt);
    log_line(2, "error: ", fmt, ap);
    va_end(ap);
}
