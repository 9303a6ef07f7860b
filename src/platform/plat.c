/* plat: back-end selection, GL debug-output callback, shared state. */
#include "platform/plat_local.h"

#include "core/core.h"

#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

plat_state_t plat_state;

plat_desc_t plat_desc_defaults(const plat_desc_t *desc)
{
    plat_desc_t d = desc ? *desc : (plat_desc_t){0};
    if (d.width <= 0) d.width = 1280;
    if (d.height <= 0) d.height = 720;
    if (!d.title) d.title = "meadow";
#ifndef NDEBUG
    d.debug = true;
#endif
    const char *env = getenv("MEADOW_GL_DEBUG");
    if (env && env[0] == '1') d.debug = true;
    if (d.no_debug) d.debug = false;
    return d;
}

static bool have_display(void)
{
    const char *x = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
    return (x && *x) || (wl && *wl);
}

bool plat_init(const plat_desc_t *desc_in, char *err, size_t err_size)
{
    plat_desc_t desc = plat_desc_defaults(desc_in);
    memset(&plat_state, 0, sizeof plat_state);
    plat_backend_t be = desc.backend;
    if (be == PLAT_BACKEND_AUTO) be = have_display() ? PLAT_BACKEND_WINDOW : PLAT_BACKEND_EGL;
    bool ok = be == PLAT_BACKEND_WINDOW ? plat_glfw_init(&desc, err, err_size)
                                        : plat_egl_init(&desc, err, err_size);
    if (!ok) {
        /* Under a small `ulimit -v` the driver cannot map itself, and EGL
         * says only that it failed: name the limit. */
        size_t n = strlen(err);
        while (n > 0 && (err[n - 1] == ' ' || err[n - 1] == ';')) err[--n] = 0;
        struct rlimit rl;
        if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && n < err_size)
            snprintf(err + n, err_size - n, "; the address space is limited to %.0f MiB (ulimit -v): that limit may "
                     "be the cause", (double)rl.rlim_cur / (1024.0 * 1024.0));
        return false;
    }
    if (epoxy_gl_version() < 45) {
        snprintf(err, err_size, "OpenGL 4.5 core is required, %s offers %d.%d (%s)", plat_state.backend_name,
                 epoxy_gl_version() / 10, epoxy_gl_version() % 10, (const char *)glGetString(GL_RENDERER));
        plat_shutdown();
        return false;
    }
    if (desc.debug) plat_install_debug_callback();
    core_log_info("GL_RENDERER: %s | GL_VERSION: %s | platform: %s", (const char *)glGetString(GL_RENDERER),
                  (const char *)glGetString(GL_VERSION), plat_state.backend_name);
    return true;
}

void plat_shutdown(void)
{
    if (plat_state.window)
        plat_glfw_shutdown();
    else
        plat_egl_shutdown();
}

bool plat_is_headless(void) { return plat_state.window == NULL; }
const char *plat_backend_name(void) { return plat_state.backend_name; }
int plat_gl_error_count(void) { return plat_state.gl_errors; }

double plat_time(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

double plat_thread_time(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

double plat_peak_rss_mb(void)
{
    struct rusage u;
    if (getrusage(RUSAGE_SELF, &u) != 0) return 0.0;
    return (double)u.ru_maxrss / 1024.0; /* KiB on Linux */
}

static void GLAPIENTRY debug_cb(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                const GLchar *message, const void *user)
{
    (void)id, (void)length, (void)user;
    /* Compile errors are reported by gfx with the shader's file and line. */
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) return;
    if (type == GL_DEBUG_TYPE_ERROR) {
        plat_state.gl_errors++;
        core_log_error("GL: %s", message);
    } else if (severity == GL_DEBUG_SEVERITY_HIGH) {
        core_log_warn("GL: %s", message);
    }
}

void plat_install_debug_callback(void)
{
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_cb, NULL);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, NULL, GL_FALSE);
}
