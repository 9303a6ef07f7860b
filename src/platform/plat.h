/* plat: one API over two back ends that create an OpenGL 4.5 core context:
 * a GLFW window for interactive use (plat_glfw.c) and headless EGL
 * (plat_egl.c: EGL_EXT_platform_device first, then
 * EGL_MESA_platform_surfaceless). Headless rendering goes into gfx FBOs. */
#ifndef MEADOW_PLAT_H
#define MEADOW_PLAT_H

#include <stdbool.h>
#include <stddef.h>

typedef enum plat_backend_t {
    PLAT_BACKEND_AUTO = 0, /* window if a display exists, else EGL */
    PLAT_BACKEND_WINDOW,
    PLAT_BACKEND_EGL,
} plat_backend_t;

typedef struct plat_desc_t {
    plat_backend_t backend; /* default AUTO */
    int width, height;      /* window size; default 1280x720 */
    const char *title;      /* default "meadow" */
    bool debug;             /* GL debug context + callback; default: on in
                               debug builds (NDEBUG undefined) or when the
                               environment has MEADOW_GL_DEBUG=1 */
    bool no_debug;          /* force the debug callback off */
    bool visible;           /* unused for EGL */
} plat_desc_t;

plat_desc_t plat_desc_defaults(const plat_desc_t *desc);

/* Creates the context and makes it current. On failure writes every platform
 * tried and why it failed into err (and, under a finite RLIMIT_AS, that
 * the limit may be the cause) and returns false. */
bool plat_init(const plat_desc_t *desc, char *err, size_t err_size);
void plat_shutdown(void);

bool plat_is_headless(void);
const char *plat_backend_name(void); /* "glfw", "egl-device", "egl-surfaceless" */

/* Window only (no-ops headless). */
bool plat_should_close(void);
void plat_request_close(void);
void plat_poll_events(void);
void plat_swap(void);
void plat_framebuffer_size(int *w, int *h);
double plat_time(void); /* seconds, monotonic */
double plat_thread_time(void); /* seconds of CPU time of the calling thread */
double plat_peak_rss_mb(void); /* the process's peak resident memory (MiB), 0 if unknown */

/* Keys, window only. Edge-triggered "pressed" is true once per press. */
typedef enum plat_key_t {
    PLAT_KEY_W, PLAT_KEY_A, PLAT_KEY_S, PLAT_KEY_D, PLAT_KEY_Q, PLAT_KEY_E,
    PLAT_KEY_UP, PLAT_KEY_DOWN, PLAT_KEY_LEFT, PLAT_KEY_RIGHT,
    PLAT_KEY_SPACE, PLAT_KEY_N, PLAT_KEY_P, PLAT_KEY_F, PLAT_KEY_C, PLAT_KEY_H,
    PLAT_KEY_1, PLAT_KEY_2, PLAT_KEY_3, PLAT_KEY_O, PLAT_KEY_R,
    PLAT_KEY_ESCAPE, PLAT_KEY_SHIFT,
    PLAT_KEY_COUNT
} plat_key_t;
bool plat_key_down(plat_key_t key);
bool plat_key_pressed(plat_key_t key);

/* GL debug output. Errors reported by the driver are counted and logged with
 * their message; tests assert plat_gl_error_count() == 0. */
int plat_gl_error_count(void);
void plat_install_debug_callback(void);

/* Back-end entry points (internal). */
bool plat_egl_init(const plat_desc_t *desc, char *err, size_t err_size);
void plat_egl_shutdown(void);
bool plat_glfw_init(const plat_desc_t *desc, char *err, size_t err_size);
void plat_glfw_shutdown(void);

#endif
