/* world_frame: one frame of the world, the sequence the program (app_run.c)
 * and every offscreen bench session (src/measure/measure_session.c) run: the
 * simulation steps, the camera on its path, the view, the target fitted,
 * cleared and drawn into, then the frame paced at the GPU. Also the scene's
 * `raster: auto` measure at start-up, for both. */
#include "world/world_local.h"

#include "platform/plat.h"

#include <string.h>

world_frame_result_t world_frame(world_t *w, const world_frame_desc_t *d)
{
    const scene_desc_t *s = &w->scene;
    double scratch[WORLD_FRAME_MARKS], *mark = d->marks ? d->marks : scratch;
    mark[0] = plat_time();
    memset(w->update_ms, 0, sizeof w->update_ms);
    gfx_timer_frame_begin();
    mark[1] = plat_time();
    for (int i = d->steps - 1; i >= 0; i--) {
        float t = (float)(d->t - i * d->dt);
        if (d->step) d->step(w, t, d->dt, d->user);
        else world_update(w, t, d->dt);
    }
    float t = (float)d->t;
    if (d->updated) d->updated(w, t, d->user);
    mark[2] = plat_time();
    if (d->update_only) return WORLD_FRAME_UPDATED;
    if (d->follow_path && s->camera.path.count) cam_path_eval(&s->camera.path, t, d->cam);
    grass_view_t view;
    world_view_make(&view, d->cam, d->target->w, d->target->h, t, s->dt);
    view.overlay = d->overlay;
    view.wireframe = d->wireframe;
    if (!world_fit_target(w, d->target, d->label)) return WORLD_FRAME_NO_TARGET;
    gfx_target_bind(d->target);
    /* Colour is cleared only for a wireframe frame: otherwise the ground
     * pass covers every pixel (the terrain, then the sky wherever the depth
     * is still clear). Clearing it took 0.59 ms of a 1080p frame with 4x
     * MSAA on the H200 (0.15 ms single-sampled), as long as the depth's. */
    glClearColor(0, 0, 0, 1);
    gfx_timer_begin(GFX_PASS_TARGET_CLEAR);
    glClear(GL_DEPTH_BUFFER_BIT | (view.wireframe ? GL_COLOR_BUFFER_BIT : 0));
    gfx_timer_end();
    glEnable(GL_DEPTH_TEST);
    mark[3] = plat_time();
    world_draw(w, &view, d->target);
    mark[4] = plat_time();
    if (d->drawn) d->drawn(w, &view, d->target, d->user);
    mark[5] = plat_time();
    if (gfx_frame_end(d->in_flight > 0 ? d->in_flight : WORLD_FRAMES_IN_FLIGHT) < 0.0) return WORLD_FRAME_GPU_LOST;
    return WORLD_FRAME_DRAWN;
}

/* Draws `view` with each rasterizer into a target of `target`'s size and
 * that path's samples: one warm-up draw, then the least of 5, GL timestamps
 * around the whole draw. */
static bool calibrate_raster(world_t *w, const grass_view_t *view, const gfx_target_t *target, double ms[2])
{
    /* Each path draws into the target it would use (world_fit_target). */
    gfx_target_t tg[2] = {{.w = target->w, .h = target->h}, {.w = target->w, .h = target->h}};
    for (int c = 0; c < 2; c++) {
        world_set_raster(w, c == 1);
        if (!world_fit_target(w, &tg[c], c ? "raster.calibrate.compute" : "raster.calibrate.hw")) {
            gfx_target_destroy(&tg[0]);
            gfx_target_destroy(&tg[1]);
            world_set_raster(w, false);
            ms[0] = ms[1] = 0.0;
            return false;
        }
    }
    GLuint q[2] = {gfx_query_make(GL_TIMESTAMP, "raster.calibrate.begin"),
                   gfx_query_make(GL_TIMESTAMP, "raster.calibrate.end")};
    double best[2] = {1e30, 1e30};
    for (int rep = 0; rep < 6; rep++) {
        for (int c = 0; c < 2; c++) {
            world_set_raster(w, c == 1);
            gfx_timer_frame_begin();
            gfx_target_bind(&tg[c]);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glEnable(GL_DEPTH_TEST);
            glQueryCounter(q[0], GL_TIMESTAMP);
            world_draw(w, view, &tg[c]);
            glQueryCounter(q[1], GL_TIMESTAMP);
            GLuint64 t0 = 0, t1 = 0;
            glGetQueryObjectui64v(q[0], GL_QUERY_RESULT, &t0);
            glGetQueryObjectui64v(q[1], GL_QUERY_RESULT, &t1);
            if (rep > 0 && (double)(t1 - t0) * 1e-6 < best[c]) best[c] = (double)(t1 - t0) * 1e-6;
        }
    }
    gfx_query_destroy(&q[0]);
    gfx_query_destroy(&q[1]);
    gfx_target_destroy(&tg[0]);
    gfx_target_destroy(&tg[1]);
    /* A path that fell back (no compute rasterizer) cannot be chosen. */
    bool compute = best[1] < best[0] && grass_stats(w->grass).compute;
    world_set_raster(w, compute);
    ms[0] = best[0];
    ms[1] = best[1];
    gfx_timer_reset_stats();
    core_log_info("raster auto: a frame takes %.3f ms with the hardware path, %.3f ms with compute: %s", best[0],
                  best[1], compute ? "compute" : "hw");
    return compute;
}

bool world_raster_auto(world_t *w, const cam_t *cam, const gfx_target_t *target, double ms[2],
                           double *wall_ms)
{
    grass_view_t view;
    world_view_make(&view, cam, target->w, target->h, 0.0f, w->scene.dt);
    double t0 = plat_time();
    bool compute = calibrate_raster(w, &view, target, ms);
    if (wall_ms) *wall_ms = (plat_time() - t0) * 1e3;
    return compute;
}
