/* plat_egl: headless OpenGL 4.5 core through EGL, with no surface. Tries
 * EGL_EXT_platform_device (NVIDIA, no X server) first, then
 * EGL_MESA_platform_surfaceless (Mesa llvmpipe). Rendering goes to FBOs. */
#include "platform/plat_local.h"

#include "core/core.h"

#include <epoxy/egl.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static void append(char *err, size_t err_size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

static void append(char *err, size_t err_size, const char *fmt, ...)
{
    size_t n = strlen(err);
    if (n + 1 >= err_size) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err + n, err_size - n, fmt, ap);
    va_end(ap);
}

static bool try_display(EGLDisplay dpy, const char *name, char *err, size_t err_size)
{
    EGLint major = 0, minor = 0;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
        append(err, err_size, "%s: eglInitialize failed (0x%x); ", name, (unsigned)eglGetError());
        return false;
    }
    if (!epoxy_has_egl_extension(dpy, "EGL_KHR_surfaceless_context")) {
        append(err, err_size, "%s: no EGL_KHR_surfaceless_context; ", name);
        eglTerminate(dpy);
        return false;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        append(err, err_size, "%s: eglBindAPI(EGL_OPENGL_API) failed (0x%x); ", name, (unsigned)eglGetError());
        eglTerminate(dpy);
        return false;
    }
    /* No surface is ever made, but some drivers (NVIDIA) still want a
     * config: the first OpenGL-renderable one, else EGL_NO_CONFIG_KHR. */
    static const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig cfg = NULL;
    EGLint ncfg = 0;
    if (!eglChooseConfig(dpy, cfg_attr, &cfg, 1, &ncfg) || ncfg == 0) cfg = EGL_NO_CONFIG_KHR;
    EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (ctx == EGL_NO_CONTEXT) {
        append(err, err_size, "%s: no OpenGL 4.5 core context (0x%x); ", name, (unsigned)eglGetError());
        eglTerminate(dpy);
        return false;
    }
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        append(err, err_size, "%s: eglMakeCurrent failed (0x%x); ", name, (unsigned)eglGetError());
        eglDestroyContext(dpy, ctx);
        eglTerminate(dpy);
        return false;
    }
    plat_state.egl_display = dpy;
    plat_state.egl_context = ctx;
    plat_state.backend_name = name;
    return true;
}

bool plat_egl_init(const plat_desc_t *desc, char *err, size_t err_size)
{
    err[0] = 0;
    plat_state.width = desc->width;
    plat_state.height = desc->height;
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base")) {
        append(err, err_size, "EGL: no EGL_EXT_platform_base (no EGL library?); ");
        return false;
    }
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device") &&
        (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") ||
         epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base"))) {
        EGLDeviceEXT devices[16];
        EGLint n = 0;
        if (eglQueryDevicesEXT(16, devices, &n) && n > 0) {
            for (EGLint i = 0; i < n; i++) {
                const char *exts = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
                /* Mesa lists a software device too; prefer it only via surfaceless. */
                if (exts && strstr(exts, "EGL_MESA_device_software")) continue;
                EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
                if (try_display(dpy, "egl-device", err, err_size)) return true;
            }
            append(err, err_size, "egl-device: %d device(s), none usable; ", (int)n);
        } else {
            append(err, err_size, "egl-device: eglQueryDevicesEXT found no device; ");
        }
    } else {
        append(err, err_size, "egl-device: EGL_EXT_platform_device not offered; ");
    }
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
        if (try_display(dpy, "egl-surfaceless", err, err_size)) {
            if (err[0]) core_log_info("EGL fell back to surfaceless: %s", err);
            return true;
        }
    } else {
        append(err, err_size, "egl-surfaceless: EGL_MESA_platform_surfaceless not offered; ");
    }
    return false;
}

void plat_egl_shutdown(void)
{
    if (!plat_state.egl_display) return;
    eglMakeCurrent(plat_state.egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(plat_state.egl_display, plat_state.egl_context);
    eglTerminate(plat_state.egl_display);
    plat_state.egl_display = NULL;
    plat_state.egl_context = NULL;
}
