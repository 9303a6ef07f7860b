/* plat_local: state shared by the platform back ends (private). */
#ifndef MEADOW_PLAT_LOCAL_H
#define MEADOW_PLAT_LOCAL_H

#include "platform/plat.h"

typedef struct plat_state_t {
    void *window; /* GLFWwindow*, NULL when headless */
    const char *backend_name;
    int gl_errors;
    int width, height;
    bool keys[PLAT_KEY_COUNT];
    bool pressed[PLAT_KEY_COUNT];
    /* EGL */
    void *egl_display;
    void *egl_context;
} plat_state_t;

extern plat_state_t plat_state;

#endif
