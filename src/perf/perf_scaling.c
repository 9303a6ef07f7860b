/* bench_scaling: `meadow bench --scaling`: what the tiled blade field's
 * simulation costs (Fan et al. 2015 tile activation over Jahrmann & Wimmer
 * 2017 blades, src/blade/blade_tiles.h) against
 *   field  the field size at a fixed active area: 4 resting balls on the 4
 *          tiles around the centre, terrain side 1, 2, 4 (and 8) x the base
 *          (1x, 4x, 16x, 64x area); the full-field blade mode beside it;
 *   active the number of active tiles at a fixed field size: N resting
 *          balls, each on its own tile, N = 1, 2, 4, 8, 16 (32); least
 *          squares line of physics time against N.
 * Scenes are built here (hybrid mode, a gentle heightfield; 4 m tiles of
 * 250 blades/m^2, the active sweep 8 m tiles of 1000 blades/m^2 outside
 * --quick).
 * Each run simulates every frame and draws the last; the measure is the
 * median of the "tiles.physics" (or "blade.physics") GPU timer over the
 * frames after warm-up, next to the slots and blades dispatched by the
 * latest update (blade_tiles_stats). Writes scaling.csv, scaling_field.dat,
 * scaling_active.dat and their gnuplot charts (PNG and SVG) into out. */
#include "perf/perf.h"

#include "eval/eval.h"

#include "measure/measure.h"
#include "measure/measure_session.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define BALL_R 0.3f

typedef struct scaling_run_t {
    float side;        /* terrain side, m */
    int balls;         /* resting balls, one per tile */
    float density;     /* blades per m^2 */
    float tile;        /* tile side, m */
    bool full;         /* the full-field blade mode instead of the tiles */
    perf_scaling_point_t *point;
} scaling_run_t;

/* Tile centres in rings around the centre: the 4 tiles at (+-2, +-2) first,
 * then outwards, so N balls always sit on N distinct tiles. */
static void tile_centre(int i, float tile, float out[2])
{
    static const int order[][2] = {{0, 0},  {-1, 0}, {0, -1}, {-1, -1}, {1, 0},  {1, -1}, {1, 1},   {0, 1},
                                   {-1, 1}, {-2, 1}, {-2, 0}, {-2, -1}, {-2, -2}, {-1, -2}, {0, -2}, {1, -2},
                                   {2, -2}, {2, -1}, {2, 0},  {2, 1},   {2, 2},   {1, 2},   {0, 2},  {-1, 2},
                                   {-2, 2}, {-3, 2}, {-3, 1}, {-3, 0},  {-3, -1}, {-3, -2}, {-3, -3}, {-2, -3}};
    out[0] = ((float)order[i][0] + 0.5f) * tile;
    out[1] = ((float)order[i][1] + 0.5f) * tile;
}

static void tweak(scene_desc_t *s, void *user)
{
    const scaling_run_t *r = user;
    s->terrain = terrain_desc_defaults(&(terrain_desc_t){
        .type = TERRAIN_HEIGHTFIELD, .size = r->side, .resolution = (int)fminf(256.0f, r->side), .height = 0.3f});
    s->grass.population.density = r->density;
    s->grass.billboard_density = 6;
    s->grass.tile_size = r->tile;
    s->grass.switch_distance = 12;
    s->dt = 1.0f / 60.0f;
    s->size[0] = 320;
    s->size[1] = 180;
    s->msaa = 1;
    s->camera.path.count = 0;
    glm_vec3_copy((vec3){0.0f, 6.0f, 14.0f}, s->camera.position);
    glm_vec3_zero(s->camera.target);
    s->character_count = 0;
    s->collider_count = r->balls;
    for (int i = 0; i < r->balls; i++) {
        float c[2];
        tile_centre(i, r->tile, c);
        s->colliders[i] = (scene_collider_t){.type = SCENE_COLLIDER_SPHERE, .radius = BALL_R};
        s->colliders[i].path.count = 1;
        glm_vec3_copy((vec3){c[0], BALL_R, c[1]}, s->colliders[i].path.keys[0].position);
    }
}

static void last_frame(world_t *w, int frame, float t, void *user)
{
    (void)t;
    scaling_run_t *r = user;
    if (frame + 1 < r->point->frames) return;
    measure_grass_t mg;
    measure_grass(w, r->full ? MEASURE_GRASS_SIZES : MEASURE_GRASS_TILES, true, &mg);
    if (r->full) {
        r->point->full_blades = mg.blades_total;
    } else if (world_info(w).tiles) {
        r->point->slots = mg.tile_slots_dispatched;
        r->point->blades = mg.tile_blades_dispatched;
    }
}

static double pass_median(const measure_metrics_t *m, const char *name)
{
    for (int p = 0; p < m->pass_count; p++)
        if (strcmp(m->pass_name[p], name) == 0) return m->pass_ms[p];
    return -1.0;
}

/* One session: hybrid (tiles) or, with r->full, the full-field blade mode. */
static int measure(const perf_session_desc_t *o, scaling_run_t *r)
{
    perf_scaling_point_t *p = r->point;
    measure_session_desc_t d = {.world = o->world,
                                .mode = r->full ? SCENE_MODE_BLADE : SCENE_MODE_HYBRID, .mode_set = true,
                              .frames = p->frames, .tweak = tweak, .user = r};
    measure_session_hooks_t h = {.frame = last_frame, .user = r, .draw_last_only = true};
    measure_metrics_t m;
    int rc = measure_session_run_hooks(&d, &h, NULL, &m);
    if (rc) return rc;
    if (r->full)
        p->full_ms = pass_median(&m, "blade.physics");
    else
        p->physics_ms = pass_median(&m, "tiles.physics");
    return 0;
}

static void write_chart(const char *out, const char *name, const char *title, const char *xlabel, const char *plot)
{
    char body[4096];
    snprintf(body, sizeof body,
             "set title '%s'\nset xlabel '%s'\nset ylabel 'physics GPU ms per frame (median)'\n"
             "set grid\nset key top left\nset yrange [0:*]\n%s",
             title, xlabel, plot);
    eval_gnuplot_chart(out, name, body);
}

int perf_scaling_run(const perf_session_desc_t *o, const char *out, bool quick, perf_scaling_t *res, core_buf_t *md)
{
    memset(res, 0, sizeof *res);
    snprintf(res->renderer, sizeof res->renderer, "%s", (const char *)glGetString(GL_RENDERER));
    static const int balls[] = {1, 2, 4, 8, 16, 32};
    float base = quick ? 16.0f : 32.0f; /* multiples of 2 tiles: tile centres at +-2 m */
    float density = quick ? 120.0f : 250.0f, tile = 4.0f;
    /* On a GPU a few tiles of 4 m cost only the dispatches (H100: 0.03-0.07 ms
     * flat from 4k to 131k blades): the active sweep uses 8 m tiles of
     * 1000 blades/m^2 (64k blades each, up to 2M) to leave that regime. */
    float active_density = quick ? density : 1000.0f, active_tile = quick ? tile : 8.0f;
    int frames = o->frames_set ? o->frames : (quick ? 24 : 120);
    res->field_count = quick ? 3 : 4;
    res->active_count = quick ? 5 : 6;
    int total = res->field_count * (quick ? 1 : 2) + res->active_count, done = 0;
    int rc = 0;
    for (int i = 0; i < res->field_count && rc == 0; i++) {
        perf_scaling_point_t *p = &res->field[i];
        *p = (perf_scaling_point_t){.side = base * (float)(1 << i), .balls = 4, .frames = frames, .full_ms = -1};
        scaling_run_t r = {.side = p->side, .balls = 4, .density = density, .tile = tile, .point = p};
        rc = measure(o, &r);
        fprintf(stderr, "\rscaling: %d/%d field %g m tiles %.4f ms   ", ++done, total, p->side, p->physics_ms);
        if (rc == 0 && !quick) {
            r.full = true;
            rc = measure(o, &r);
            fprintf(stderr, "\rscaling: %d/%d field %g m full %.4f ms   ", ++done, total, p->side, p->full_ms);
        }
        if (perf_interrupted(o)) rc = 1;
    }
    for (int i = 0; i < res->active_count && rc == 0; i++) {
        perf_scaling_point_t *p = &res->active[i];
        *p = (perf_scaling_point_t){.side = base * 2.0f, .balls = balls[i], .frames = frames, .full_ms = -1};
        scaling_run_t r = {.side = p->side, .balls = balls[i], .density = active_density, .tile = active_tile,
                           .point = p};
        rc = measure(o, &r);
        fprintf(stderr, "\rscaling: %d/%d active %d tiles %.4f ms   ", ++done, total, p->balls, p->physics_ms);
        if (perf_interrupted(o)) rc = 1;
    }
    fputc('\n', stderr);
    if (rc) return rc;

    /* Least squares physics_ms = intercept + slope * active tiles (slots). */
    double xs[PERF_SCALING_MAX], ys[PERF_SCALING_MAX];
    for (int i = 0; i < res->active_count; i++) {
        xs[i] = res->active[i].slots;
        ys[i] = res->active[i].physics_ms;
    }
    res->r2 = eval_linear_fit(xs, ys, res->active_count, &res->slope, &res->intercept);

    char path[1200];
    core_buf_t csv = {0}, fd = {0}, ad = {0};
    core_buf_printf(&csv, "sweep,field_m,area_x,balls,slots,blades_simulated,tiles_physics_ms,full_blades,"
                          "full_physics_ms\n");
    core_buf_printf(&fd, "# area_x field_m tiles_physics_ms full_physics_ms slots\n");
    core_buf_printf(&ad, "# slots tiles_physics_ms fit_ms balls\n");
    if (md)
        core_buf_printf(md,
                        "Renderer `%s`, %d frames per run (median of the frames after warm-up), r %.1f m balls "
                        "resting on tile centres; field sweep %.0f blades/m^2 in %g m tiles, active sweep %.0f "
                        "blades/m^2 in %g m tiles.\n\n"
                        "| sweep | field | area | balls | slots simulated | blades simulated | tiles.physics ms | "
                        "full-field blade.physics ms |\n| --- | --- | --- | --- | --- | --- | --- | --- |\n",
                        res->renderer, frames, BALL_R, density, tile, active_density, active_tile);
    for (int s = 0; s < 2; s++) {
        int cnt = s ? res->active_count : res->field_count;
        for (int i = 0; i < cnt; i++) {
            const perf_scaling_point_t *p = s ? &res->active[i] : &res->field[i];
            double area = (double)(p->side * p->side) / (double)(res->field[0].side * res->field[0].side);
            core_buf_printf(&csv, "%s,%g,%g,%d,%d,%ld,%.5f,%ld,%.5f\n", s ? "active" : "field", p->side, area,
                            p->balls, p->slots, p->blades, p->physics_ms, p->full_blades, p->full_ms);
            if (s)
                core_buf_printf(&ad, "%d %.5f %.5f %d\n", p->slots, p->physics_ms,
                                res->intercept + res->slope * p->slots, p->balls);
            else
                core_buf_printf(&fd, "%g %g %.5f %.5f %d\n", area, p->side, p->physics_ms, p->full_ms, p->slots);
            if (!md) continue;
            char full[32] = "-";
            if (p->full_ms >= 0) snprintf(full, sizeof full, "%.4f", p->full_ms);
            core_buf_printf(md, "| %s | %g m | %gx | %d | %d | %ld | %.4f | %s |\n", s ? "active" : "field",
                            p->side, area, p->balls, p->slots, p->blades, p->physics_ms, full);
        }
    }
    if (md)
        core_buf_printf(md, "\nLeast squares over the active sweep: %.4f ms + %.5f ms per active tile, R^2 = %.3f.\n",
                        res->intercept, res->slope, res->r2);
    const char *names[3] = {"scaling.csv", "scaling_field.dat", "scaling_active.dat"};
    core_buf_t *texts[3] = {&csv, &fd, &ad};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/%s", out, names[k]);
        if (!core_buf_write(texts[k], path)) rc = 1;
        core_buf_free(texts[k]);
    }
    if (rc) return rc;
    char plot[1600];
    snprintf(plot, sizeof plot,
             "set logscale x 2\nplot '%s/scaling_field.dat' using 1:3 with linespoints lw 2 pt 7 title 'tiles "
             "(hybrid, 4 active tiles)'%s",
             out, quick ? "" : ", '' using 1:4 with linespoints lw 2 pt 5 title 'full-field blade mode'");
    write_chart(out, "scaling_field", "simulation vs field size (fixed active area)", "field area (x base)", plot);
    snprintf(plot, sizeof plot,
             "plot '%s/scaling_active.dat' using 1:2 with points pt 7 ps 1.4 title 'measured', "
             "'' using 1:3 with lines lw 2 title 'least squares: %.4f + %.5f ms/tile (R^2 %.3f)'",
             out, res->intercept, res->slope, res->r2);
    write_chart(out, "scaling_active", "simulation vs active tiles (fixed field)", "active tiles (slots simulated)",
                plot);

    core_log_info("scaling: wrote %s/scaling.csv and charts (tiles.physics %.4f -> %.4f ms from 1x to %gx area; "
                  "%.5f ms per active tile, R^2 %.3f)",
                  out, res->field[0].physics_ms, res->field[res->field_count - 1].physics_ms,
                  (double)(1 << (2 * (res->field_count - 1))), res->slope, res->r2);
    return 0;
}
