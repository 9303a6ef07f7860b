/* app_seam: the hybrid seam measure of a drawn frame (docs/METRICS.md,
 * "Hybrid seam"). A frame read back from the target gives, per pixel, the
 * distance from the camera to the nearest surface it shows (its nearest
 * depth sample, gfx_target_read_depth_nearest: the hardware path stores
 * grass depth per sample, the compute rasterizer's composite per pixel, so
 * one sample's depth put the same grass pixel at different distances on
 * the two paths). The
 * background, the same view drawn with no grass, says which pixels count:
 * those where it shows the terrain (not the sky, colliders or characters);
 * of those, a pixel is grass where the frame differs from the background by
 * more than APP_SEAM_GRASS_THRESHOLD in a channel (eval_image's coverage
 * rule), ground otherwise. The reference is the same view drawn again with
 * billboards only (no switch; the hybrid world's own billboards at the same
 * time), and eval_image_seam compares the steps of both across the switch
 * band [switch_distance - APP_SWITCH_FADE, + APP_SWITCH_FADE]. */
#include "app/app_world.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A background pixel shows the terrain when its surface lies less than this
 * (m) above terrain_height_at: the depth is an MSAA sample's, off the pixel
 * centre, which puts grazing ground a few centimetres high;
 * colliders and characters stand far higher. */
#define APP_SEAM_GROUND_EPS 0.15f
/* Levels (of 255) a channel must differ from the background for grass
 * (eval_image_desc_t.grass_threshold's default). */
#define APP_SEAM_GRASS_THRESHOLD 8
/* A window of the band with fewer counted pixels than this (in the frame
 * or the reference) leaves the seam unmeasured. */
#define APP_SEAM_MIN_PIXELS 100
/* The floor's placements: the world's placement seed xor this times 1, 2,
 * ... APP_SEAM_FLOOR_PLACEMENTS. */
#define APP_SEAM_FLOOR_SEED 0x9e3779b9u

void app_seam_frame_free(app_seam_frame_t *f)
{
    core_image_free(&f->img);
    free(f->dist);
    free(f->cls);
    memset(f, 0, sizeof *f);
}

bool app_seam_frame_read(const app_world_t *w, const app_view_t *v, const gfx_target_t *t, app_seam_frame_t *f)
{
    memset(f, 0, sizeof *f);
    size_t n = (size_t)t->w * (size_t)t->h;
    f->dist = malloc(sizeof(float) * n);
    f->cls = malloc(n);
    if (!f->dist || !f->cls || !gfx_target_read(t, &f->img) || !gfx_target_read_depth_nearest(t, f->dist)) {
        app_seam_frame_free(f);
        return false;
    }
    for (int y = 0; y < t->h; y++)
        for (int x = 0; x < t->w; x++) {
            size_t i = (size_t)y * (size_t)t->w + (size_t)x;
            float depth = f->dist[i];
            f->cls[i] = EVAL_SEAM_SKIP;
            if (depth >= 1.0f) continue;
            vec4 ndc = {((float)x + 0.5f) / (float)t->w * 2.0f - 1.0f, 1.0f - ((float)y + 0.5f) / (float)t->h * 2.0f,
                        depth * 2.0f - 1.0f, 1.0f};
            vec4 p;
            glm_mat4_mulv((vec4 *)v->inv_viewproj, ndc, p);
            glm_vec3_scale(p, 1.0f / p[3], p);
            f->dist[i] = glm_vec3_distance(p, (float *)v->camera);
            if (p[1] - terrain_height_at(&w->terrain_mesh, p[0], p[2], NULL) < APP_SEAM_GROUND_EPS)
                f->cls[i] = EVAL_SEAM_GROUND;
        }
    return true;
}

void app_seam_frame_classify(app_seam_frame_t *f, const app_seam_frame_t *background)
{
    size_t n = (size_t)f->img.w * (size_t)f->img.h;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *a = f->img.px + i * 4, *b = background->img.px + i * 4;
        bool grass = false;
        for (int c = 0; c < 3; c++) grass = grass || abs((int)a[c] - (int)b[c]) > APP_SEAM_GRASS_THRESHOLD;
        f->cls[i] = background->cls[i] != EVAL_SEAM_GROUND ? EVAL_SEAM_SKIP
                                                          : (grass ? EVAL_SEAM_GRASS : EVAL_SEAM_GROUND);
    }
}

bool app_seam_frame_draw(app_world_t *w, const app_view_t *v, const gfx_target_t *t, scene_mode_t mode, bool grass,
                         app_seam_frame_t *f)
{
    scene_mode_t keep = w->mode;
    bb_field_t *bb = w->bb;
    bool blades = w->have_blades, tiles = w->have_tiles;
    w->mode = mode;
    if (!grass) {
        w->bb = NULL;
        w->have_blades = w->have_tiles = false;
    }
    gfx_target_bind(t);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    app_world_draw(w, v, t, false);
    w->mode = keep;
    w->bb = bb;
    w->have_blades = blades;
    w->have_tiles = tiles;
    return app_seam_frame_read(w, v, t, f);
}

eval_seam_desc_t app_seam_desc(const app_world_t *w)
{
    return (eval_seam_desc_t){.switch_distance = w->scene.grass.switch_distance, .fade = APP_SWITCH_FADE};
}

/* eval_image_seam of frame against ref, both classified against bg, at
 * the band of d. */
static bool seam_at(app_seam_frame_t *frame, app_seam_frame_t *ref, const app_seam_frame_t *bg,
                    const eval_seam_desc_t *d, eval_seam_t *out)
{
    app_seam_frame_classify(frame, bg);
    app_seam_frame_classify(ref, bg);
    return eval_image_seam(&(eval_seam_frame_t){&frame->img, frame->dist, frame->cls},
                           &(eval_seam_frame_t){&ref->img, ref->dist, ref->cls}, d, out);
}

static bool seam_of(const app_world_t *w, app_seam_frame_t *frame, app_seam_frame_t *ref, const app_seam_frame_t *bg,
                    eval_seam_t *out)
{
    eval_seam_desc_t d = app_seam_desc(w);
    return seam_at(frame, ref, bg, &d, out);
}

/* The last frame against it drawn with billboards only, at band d. */
static bool world_seam(app_world_t *w, const app_view_t *v, const gfx_target_t *t, const eval_seam_desc_t *d,
                       eval_seam_t *out)
{
    memset(out, 0, sizeof *out);
    if (w->mode != SCENE_MODE_HYBRID || !w->bb) return false;
    app_seam_frame_t frame = {0}, ref = {0}, bg = {0};
    bool ok = app_seam_frame_read(w, v, t, &frame) && app_seam_frame_draw(w, v, t, SCENE_MODE_BILLBOARD, true, &ref) &&
              app_seam_frame_draw(w, v, t, w->mode, false, &bg);
    if (ok) {
        ok = seam_at(&frame, &ref, &bg, d, out);
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) ok = ok && out->pixels[i][j] >= APP_SEAM_MIN_PIXELS;
    }
    app_seam_frame_free(&frame);
    app_seam_frame_free(&ref);
    app_seam_frame_free(&bg);
    return ok;
}

bool app_world_seam(app_world_t *w, const app_view_t *v, const gfx_target_t *t, eval_seam_t *out)
{
    eval_seam_desc_t d = app_seam_desc(w);
    return world_seam(w, v, t, &d, out);
}

bool app_world_canopy_seam(app_world_t *w, const app_view_t *v, const gfx_target_t *t, eval_seam_t *out)
{
    memset(out, 0, sizeof *out);
    if (!w->have_tiles || w->terrain.canopy.rows < 2) return false;
    eval_seam_desc_t d = {.switch_distance = w->scene.grass.canopy_distance, .fade = APP_CANOPY_FADE};
    return world_seam(w, v, t, &d, out);
}

bool app_world_seam_floor(app_world_t *w, const app_view_t *v, const gfx_target_t *t, app_seam_floor_t *out)
{
    memset(out, 0, sizeof *out);
    if (w->mode != SCENE_MODE_HYBRID || !w->bb) return false;
    app_seam_frame_t ref = {0}, bg = {0};
    bool ok = app_seam_frame_draw(w, v, t, SCENE_MODE_BILLBOARD, true, &ref) &&
              app_seam_frame_draw(w, v, t, w->mode, false, &bg);
    bb_field_t *keep = w->bb;
    uint32_t seed = w->tuning.placement_seed ? w->tuning.placement_seed : w->scene.seed;
    for (int k = 0; ok && k < APP_SEAM_FLOOR_PLACEMENTS; k++) {
        app_seam_frame_t other = {0};
        eval_seam_t e;
        ok = app_world_make_billboards(w, seed ^ (APP_SEAM_FLOOR_SEED * (uint32_t)(k + 1)));
        if (ok) {
            ok = app_seam_frame_draw(w, v, t, SCENE_MODE_BILLBOARD, true, &other);
            bb_field_destroy(w->bb);
        }
        /* seam_of classifies ref again against the same background: the
         * same classes every time. */
        if (ok) ok = seam_of(w, &other, &ref, &bg, &e);
        app_seam_frame_free(&other);
        if (!ok) break;
        out->score[k] = e.score;
        out->mean.score += e.score / APP_SEAM_FLOOR_PLACEMENTS;
        out->mean.delta_e += e.delta_e / APP_SEAM_FLOOR_PLACEMENTS;
        out->mean.delta_l += e.delta_l / APP_SEAM_FLOOR_PLACEMENTS;
        out->mean.coverage += e.coverage / APP_SEAM_FLOOR_PLACEMENTS;
    }
    w->bb = keep;
    app_seam_frame_free(&ref);
    app_seam_frame_free(&bg);
    if (!ok) memset(out, 0, sizeof *out);
    return ok;
}
