/* core_log: one-line diagnostics on stderr, with counters for tests. */
#include "core.h"

#include <stdarg.h>
#include <stdio.h>

static bool g_quiet;
static int g_warns, g_errors;

static void log_line(const char *level, const char *fmt, va_list ap)
{
    char buf[2048];
    vsnprintf(buf, sizeof buf, fmt, ap);
    fprintf(stderr, "meadow: %s%s\n", level, buf);
}

void core_log_set_quiet(bool quiet) { g_quiet = quiet; }
int core_log_warn_count(void) { return g_warns; }
int core_log_error_count(void) { return g_errors; }

void core_log_info(const char *fmt, ...)
{
    if (g_quiet) return;
    va_list ap;
    va_start(ap, fmt);
    log_line("", fmt, ap);
    va_end(ap);
}

void core_log_warn(const char *fmt, ...)
{
    g_warns++;
    va_list ap;
    va_start(ap, fmt);
    log_line("warning: ", fmt, ap);
    va_end(ap);
}

void core_log_error(const char *fmt, ...)
{
    g_errors++;
    va_list ap;
    va_start(ap, fmt);
    log_line("error: ", fmt, ap);
    va_end(ap);
}
