/* bench_session: one offscreen run of a scene in an existing GL context, for
 * `meadow compare`, `meadow bench` and the stability suite: world, frames,
 * timings, last frame, accuracy metrics (measure_metrics.c), and optional
 * per-frame hooks (bench_local.h). */
#include "measure/measure_session.h"

#include <string.h>

#include "platform/plat.h"

int measure_session_world(const measure_session_desc_t *d, world_t **out)
{
        world_t *w;
    *out = NULL;
    int rc = world_load(&d->world, &w);
    if (rc) return rc;
    world_setup_t setup = {.mode = d->mode, .mode_set = d->mode_set, .msaa = d->msaa,
                           .reference = d->reference, .tuning = d->tuning, .tweak = d->tweak, .user = d->user};
    if (!world_setup(w, &setup)) {
        world_destroy(w);
        return 1;
    }
    if (!world_make_gpu(w)) {
        core_log_error("session: cannot build the renderer for %s", world_info(w).scene_path);
        rc = world_info(w).input_error ? 2 : 1;
        world_destroy(w);
        return rc;
    }
    *out = w;
    return 0;
}

/* A session's hooks inside world_frame: the frame's number beside them. */
typedef struct session_frame_t {
    const measure_session_hooks_t *h;
    int frame;
} session_frame_t;

static int session_spheres(world_t *w, collide_sphere_t *out, int max, void *user)
{
    const session_frame_t *sf = user;
    return sf->h->blade_spheres(w, out, max, sf->h->user);
}

/* A step with the hooks' blade spheres (world_update_spheres). */
static void session_step(world_t *w, float t, float dt, void *user)
{
    world_update_spheres(w, t, dt, session_spheres, user);
}

static void session_updated(world_t *w, float t, void *user)
{
    const session_frame_t *sf = user;
    if (sf->h->frame) sf->h->frame(w, sf->frame, t, sf->h->user);
}

static void session_drawn(world_t *w, const grass_view_t *v, gfx_target_t *target, void *user)
{
    (void)w;
    (void)v;
    const session_frame_t *sf = user;
    if (sf->h->drawn) sf->h->drawn(target, sf->frame, sf->h->user);
}

int measure_session_run_hooks(const measure_session_desc_t *d, const measure_session_hooks_t *h, core_image_t *last,
                            measure_metrics_t *m)
{
    static const measure_session_hooks_t none = {0};
    if (!h) h = &none;
    world_t *w;
    int rc = measure_session_world(d, &w);
    if (rc) return rc;
    const scene_desc_t *s = world_info(w).scene;
    int frames = d->frames > 0 ? d->frames : 60;
    int warmup = d->warmup > 0 ? d->warmup : frames / 4;
    gfx_target_t target = {.w = s->size[0], .h = s->size[1]};
    if (!world_fit_target(w, &target, "session")) {
        core_log_error("session: cannot make the %dx%d target for %s", s->size[0], s->size[1],
                       world_info(w).scene_path);
        world_destroy(w);
        return 1;
    }
    bool own_update = h->blade_spheres && world_info(w).blades && !world_info(w).billboards &&
                      !world_info(w).characters;
    cam_t cam;
    scene_camera_init(s, &cam);
    /* A session draws a named path: the hardware one unless the options ask
     * for a path, or for auto (`--raster auto`: measured here). The scene's
     * default, auto, would make a session's images depend on timing (CI's
     * test_eval_image under ASan measured its noise floor on compute). */
    if (d->world.raster == 1 + SCENE_RASTER_AUTO) {
        double ms[2];
        world_raster_auto(w, &cam, &target, ms, NULL);
    }
    session_frame_t sf = {.h = h};
    double cpu0 = 0, t_acc = 0;
    bool ran = true; /* false: the target could not be made, or the GPU hung */
    for (int f = 0; f < frames; f++) {
        if (f == warmup) {
            gfx_timer_reset_stats();
            glFinish();
            cpu0 = plat_time();
        }
        float dt = h->step_dt ? h->step_dt(f, s->dt, h->user) : s->dt;
        t_acc += dt;
        sf.frame = f;
        world_frame_desc_t fd = {.target = &target, .label = "session", .cam = &cam, .follow_path = true,
                               .t = t_acc, .dt = dt, .steps = 1, .step = own_update ? session_step : NULL,
                               .updated = session_updated, .update_only = h->draw_last_only && f + 1 < frames,
                               .drawn = session_drawn, .user = &sf};
        world_frame_result_t r = world_frame(w, &fd);
        if (r == WORLD_FRAME_GPU_LOST)
            core_log_error("session: %s: the GPU did not finish frame %d", world_info(w).scene_path, f);
        if (r == WORLD_FRAME_NO_TARGET || r == WORLD_FRAME_GPU_LOST) {
            ran = false;
            break;
        }
    }
    if (!ran) {
        gfx_target_destroy(&target);
        world_destroy(w);
        return 1;
    }
    glFinish();
    double cpu = plat_time() - cpu0;
    gfx_timer_flush();
    if (m) {
        memset(m, 0, sizeof *m);
        m->cpu_ms = cpu * 1000.0 / (frames - warmup > 0 ? frames - warmup : 1);
        m->raster_compute = world_info(w).raster_compute;
        m->gpu_mb = (double)gfx_memory_bytes() / (1024.0 * 1024.0);
        m->pass_count = gfx_timer_count();
        for (int i = 0; i < m->pass_count; i++) {
            m->pass_ms[i] = gfx_timer_median_ms(i);
            snprintf(m->pass_name[i], sizeof m->pass_name[i], "%s", gfx_timer_name(i));
            m->frame_ms += m->pass_ms[i];
        }
        measure_metrics(w, m, h->ext);
    }
    bool ok = !last || gfx_target_read(&target, last);
    gfx_target_destroy(&target);
    world_destroy(w);
    return ok ? 0 : 1;
}

int measure_session_run(const measure_session_desc_t *d, core_image_t *last, measure_metrics_t *m)
{
    return measure_session_run_hooks(d, NULL, last, m);
}
