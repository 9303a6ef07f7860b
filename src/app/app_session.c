/* app_session: one offscreen run of a scene in an existing GL context, for
 * `meadow compare` and `meadow bench`: world, frames, timings, last frame. */
#include "app/app_world.h"

#include <string.h>

#include "platform/plat.h"

int app_session_run(const app_session_desc_t *d, core_image_t *last, app_metrics_t *m)
{
    app_world_t *w = calloc(1, sizeof *w);
    if (!w) return 1;
    int rc = app_world_load(w, d->opts);
    if (rc) {
        app_world_destroy(w);
        free(w);
        return rc;
    }
    scene_desc_t *s = &w->scene;
    if (d->mode_set) app_world_set_mode(w, d->mode);
    if (d->msaa) s->msaa = d->msaa;
    w->reference = d->reference;
    w->tuning = d->tuning;
    if (d->tweak) d->tweak(s, d->user);
    int frames = d->frames > 0 ? d->frames : 60;
    int warmup = d->warmup > 0 ? d->warmup : frames / 4;
    gfx_target_t target = gfx_target_make(&(gfx_target_desc_t){.w = s->size[0], .h = s->size[1],
                                                               .samples = s->msaa, .label = "session"});
    if (!target.fbo || !app_world_make_gpu(w)) {
        core_log_error("session: cannot build the renderer for %s", w->scene_path);
        gfx_target_destroy(&target);
        app_world_destroy(w);
        free(w);
        return 1;
    }
    cam_t cam;
    scene_camera_init(s, &cam);
    double cpu0 = 0;
    for (int f = 0; f < frames; f++) {
        if (f == warmup) {
            gfx_timer_reset_stats();
            glFinish();
            cpu0 = plat_time();
        }
        gfx_timer_frame_begin();
        float t = (float)((f + 1) * s->dt);
        app_world_update(w, t, s->dt);
        if (s->camera.path.count) cam_path_eval(&s->camera.path, t, &cam);
        app_view_t view;
        app_view_make(&view, &cam, target.w, target.h, t, s->dt);
        gfx_target_bind(&target);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        app_world_draw(w, &view, &target, false);
    }
    glFinish();
    double cpu = plat_time() - cpu0;
    gfx_timer_flush();
    if (m) {
        memset(m, 0, sizeof *m);
        m->penetration_fraction = m->penetration_max = m->blade_length_error = m->spring_error = -1;
        m->cpu_ms = cpu * 1000.0 / (frames - warmup > 0 ? frames - warmup : 1);
        m->pass_count = gfx_timer_count();
        for (int i = 0; i < m->pass_count; i++) {
            m->pass_ms[i] = gfx_timer_median_ms(i);
            snprintf(m->pass_name[i], sizeof m->pass_name[i], "%s", gfx_timer_name(i));
            m->frame_ms += m->pass_ms[i];
        }
        app_world_metrics(w, m);
    }
    bool ok = !last || gfx_target_read(&target, last);
    gfx_target_destroy(&target);
    app_world_destroy(w);
    free(w);
    return ok ? 0 : 1;
}
