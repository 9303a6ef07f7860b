/* plat_glfw: an interactive GLFW window with an OpenGL 4.5 core context,
 * keyboard state and buffer swaps. */
#include "platform/plat_local.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <stdio.h>
#include <string.h>

static char g_glfw_err[512];

static void on_error(int code, const char *msg)
{
    snprintf(g_glfw_err, sizeof g_glfw_err, "GLFW error 0x%x: %s", (unsigned)code, msg);
}

static const int key_map[PLAT_KEY_COUNT] = {
    [PLAT_KEY_W] = GLFW_KEY_W,         [PLAT_KEY_A] = GLFW_KEY_A,       [PLAT_KEY_S] = GLFW_KEY_S,
    [PLAT_KEY_D] = GLFW_KEY_D,         [PLAT_KEY_Q] = GLFW_KEY_Q,       [PLAT_KEY_E] = GLFW_KEY_E,
    [PLAT_KEY_UP] = GLFW_KEY_UP,       [PLAT_KEY_DOWN] = GLFW_KEY_DOWN, [PLAT_KEY_LEFT] = GLFW_KEY_LEFT,
    [PLAT_KEY_RIGHT] = GLFW_KEY_RIGHT, [PLAT_KEY_SPACE] = GLFW_KEY_SPACE, [PLAT_KEY_N] = GLFW_KEY_N,
    [PLAT_KEY_P] = GLFW_KEY_P,         [PLAT_KEY_F] = GLFW_KEY_F,       [PLAT_KEY_C] = GLFW_KEY_C,
    [PLAT_KEY_H] = GLFW_KEY_H,         [PLAT_KEY_1] = GLFW_KEY_1,       [PLAT_KEY_2] = GLFW_KEY_2,
    [PLAT_KEY_3] = GLFW_KEY_3,         [PLAT_KEY_O] = GLFW_KEY_O,       [PLAT_KEY_R] = GLFW_KEY_R,
    [PLAT_KEY_ESCAPE] = GLFW_KEY_ESCAPE, [PLAT_KEY_SHIFT] = GLFW_KEY_LEFT_SHIFT,
};

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)w, (void)scancode, (void)mods;
    for (int i = 0; i < PLAT_KEY_COUNT; i++) {
        if (key_map[i] != key) continue;
        if (action == GLFW_PRESS) {
            plat_state.keys[i] = true;
            plat_state.pressed[i] = true;
        } else if (action == GLFW_RELEASE) {
            plat_state.keys[i] = false;
        }
    }
}

bool plat_glfw_init(const plat_desc_t *desc, char *err, size_t err_size)
{
    glfwSetErrorCallback(on_error);
    if (!glfwInit()) {
        snprintf(err, err_size, "glfw: init failed: %s", g_glfw_err);
        return false;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, desc->debug ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow *win = glfwCreateWindow(desc->width, desc->height, desc->title, NULL, NULL);
    if (!win) {
        snprintf(err, err_size, "glfw: no OpenGL 4.5 core window: %s", g_glfw_err);
        glfwTerminate();
        return false;
    }
    glfwMakeContextCurrent(win);
    glfwSwapInterval(1);
    glfwSetKeyCallback(win, on_key);
    plat_state.window = win;
    plat_state.backend_name = "glfw";
    return true;
}

void plat_glfw_shutdown(void)
{
    glfwDestroyWindow(plat_state.window);
    plat_state.window = NULL;
    glfwTerminate();
}

bool plat_should_close(void) { return plat_state.window && glfwWindowShouldClose(plat_state.window); }

void plat_request_close(void)
{
    if (plat_state.window) glfwSetWindowShouldClose(plat_state.window, GLFW_TRUE);
}

void plat_poll_events(void)
{
    memset(plat_state.pressed, 0, sizeof plat_state.pressed);
    if (plat_state.window) glfwPollEvents();
}

void plat_swap(void)
{
    if (plat_state.window) glfwSwapBuffers(plat_state.window);
}

void plat_framebuffer_size(int *w, int *h)
{
    if (plat_state.window) {
        glfwGetFramebufferSize(plat_state.window, w, h);
    } else {
        *w = plat_state.width;
        *h = plat_state.height;
    }
}

bool plat_key_down(plat_key_t key) { return plat_state.keys[key]; }
bool plat_key_pressed(plat_key_t key) { return plat_state.pressed[key]; }
