/* measure_seam: the hybrid seam measure of a drawn frame (docs/METRICS.md,
 * "Hybrid seam"). A frame read back from the target gives, per pixel, the
 * distance from the camera to the nearest surface it shows (its nearest
 * depth sample, gfx_target_read_depth_nearest: the hardware path stores
 * grass depth per sample, the compute rasterizer's composite per pixel, so
 * one sample's depth put the same grass pixel at different distances on
 * the two paths). The
 * background, the same view drawn with no grass, says which pixels count:
 * those where it shows the terrain (not the sky, colliders or characters);
 * of those, a pixel is grass where the frame differs from the background by
 * more than MEASURE_SEAM_GRASS_THRESHOLD in a channel (eval_image's coverage
 * rule), ground otherwise. The reference is the same view drawn again with
 * billboards only (no switch; the hybrid world's own billboards at the same
 * time), and eval_image_seam compares the steps of both across the switch
 * band [switch_distance - GRASS_SWITCH_FADE, + GRASS_SWITCH_FADE]. */
#include "measure/measure.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A background pixel shows the terrain when its surface lies less than this
 * (m) above terrain_height_at: the depth is an MSAA sample's, off the pixel
 * centre, which puts grazing ground a few centimetres high;
 * colliders and characters stand far higher. */
#define MEASURE_SEAM_GROUND_EPS 0.15f
/* Levels (of 255) a channel must differ from the background for grass
 * (eval_image_desc_t.grass_threshold's default). */
#define MEASURE_SEAM_GRASS_THRESHOLD 8
/* A window of the band with fewer counted pixels than this (in the frame
 * or the reference) leaves the seam unmeasured. */
#define MEASURE_SEAM_MIN_PIXELS 100
/* The floor's placements: the world's placement seed xor this times 1, 2,
 * ... MEASURE_SEAM_FLOOR_PLACEMENTS. */
#define MEASURE_SEAM_FLOOR_SEED 0x9e3779b9u

void measure_seam_frame_free(measure_seam_frame_t *f)
{
    core_image_free(&f->img);
    free(f->dist);
    free(f->cls);
    memset(f, 0, sizeof *f);
}

bool measure_seam_frame_read(world_t *w, const grass_view_t *v, const gfx_target_t *t, measure_seam_frame_t *f)
{
    memset(f, 0, sizeof *f);
    size_t n = (size_t)t->w * (size_t)t->h;
    f->dist = malloc(sizeof(float) * n);
    f->cls = malloc(n);
    if (!f->dist || !f->cls || !gfx_target_read(t, &f->img) || !gfx_target_read_depth_nearest(t, f->dist)) {
        measure_seam_frame_free(f);
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
            if (p[1] - terrain_height_at(world_info(w).terrain, p[0], p[2], NULL) < MEASURE_SEAM_GROUND_EPS)
                f->cls[i] = EVAL_SEAM_GROUND;
        }
    return true;
}

void measure_seam_frame_classify(measure_seam_frame_t *f, const measure_seam_frame_t *background)
{
    size_t n = (size_t)f->img.w * (size_t)f->img.h;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *a = f->img.px + i * 4, *b = background->img.px + i * 4;
        bool grass = false;
        for (int c = 0; c < 3; c++) grass = grass || abs((int)a[c] - (int)b[c]) > MEASURE_SEAM_GRASS_THRESHOLD;
        f->cls[i] = background->cls[i] != EVAL_SEAM_GROUND ? EVAL_SEAM_SKIP
                                                          : (grass ? EVAL_SEAM_GRASS : EVAL_SEAM_GROUND);
    }
}

bool measure_seam_frame_draw(world_t *w, const grass_view_t *v, const gfx_target_t *t, scene_mode_t mode, bool grass,
                             measure_seam_frame_t *f)
{
    world_draw_as(w, v, t, mode, grass);
    return measure_seam_frame_read(w, v, t, f);
}

eval_seam_desc_t measure_seam_desc(world_t *w)
{
    return (eval_seam_desc_t){.switch_distance = world_info(w).scene->grass.switch_distance, .fade = GRASS_SWITCH_FADE};
}

/* eval_image_seam of frame against ref, both classified against bg, at
 * the band of d. ground_windows: both frames' pixels fall in the windows by
 * bg's distance (the terrain's along the pixel), not by their own nearest
 * surface's: the canopy lies on the ground while cards stand up, so by
 * their own distances the two windows would hold different pixels. */
static bool seam_at(measure_seam_frame_t *frame, measure_seam_frame_t *ref, const measure_seam_frame_t *bg,
                    const eval_seam_desc_t *d, bool ground_windows, eval_seam_t *out)
{
    measure_seam_frame_classify(frame, bg);
    measure_seam_frame_classify(ref, bg);
    return eval_image_seam(&(eval_seam_frame_t){&frame->img, ground_windows ? bg->dist : frame->dist, frame->cls},
                           &(eval_seam_frame_t){&ref->img, ground_windows ? bg->dist : ref->dist, ref->cls}, d, out);
}

static bool seam_of(world_t *w, measure_seam_frame_t *frame, measure_seam_frame_t *ref, const measure_seam_frame_t *bg,
                    eval_seam_t *out)
{
    eval_seam_desc_t d = measure_seam_desc(w);
    return seam_at(frame, ref, bg, &d, false, out);
}

/* seam_at of three frames read (drawn: all three were), false unless each
 * window counts MEASURE_SEAM_MIN_PIXELS in both; the frames are freed. */
static bool seam_counted(measure_seam_frame_t *frame, measure_seam_frame_t *ref, measure_seam_frame_t *bg, bool drawn,
                         const eval_seam_desc_t *d, bool ground_windows, eval_seam_t *out)
{
    bool ok = drawn && seam_at(frame, ref, bg, d, ground_windows, out);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) ok = ok && out->pixels[i][j] >= MEASURE_SEAM_MIN_PIXELS;
    measure_seam_frame_free(frame);
    measure_seam_frame_free(ref);
    measure_seam_frame_free(bg);
    return ok;
}

/* The last frame against it drawn with billboards only, at band d. */
static bool world_seam(world_t *w, const grass_view_t *v, const gfx_target_t *t, const eval_seam_desc_t *d,
                       bool ground_windows, eval_seam_t *out)
{
    memset(out, 0, sizeof *out);
    world_info_t wi = world_info(w);
    if (wi.mode != SCENE_MODE_HYBRID || !wi.billboards) return false;
    measure_seam_frame_t frame = {0}, ref = {0}, bg = {0};
    /* drawn again: the frame's own target may lack the grass's depth */
    bool ok = measure_seam_frame_draw(w, v, t, wi.mode, true, &frame) &&
              measure_seam_frame_draw(w, v, t, SCENE_MODE_BILLBOARD, true, &ref) &&
              measure_seam_frame_draw(w, v, t, wi.mode, false, &bg);
    return seam_counted(&frame, &ref, &bg, ok, d, ground_windows, out);
}

bool measure_seam(world_t *w, const grass_view_t *v, const gfx_target_t *t, eval_seam_t *out)
{
    eval_seam_desc_t d = measure_seam_desc(w);
    return world_seam(w, v, t, &d, false, out);
}

float measure_canopy_seam_reach(float switch_distance)
{
    eval_seam_desc_t d =
        eval_seam_desc_defaults(&(eval_seam_desc_t){.switch_distance = switch_distance, .fade = GRASS_SWITCH_FADE});
    return d.switch_distance + d.fade + d.window + MEASURE_SEAM_REACH;
}

/* Where the blades end in the canopy (the hybrid without billboards): the
 * last frame against what the eye would see without the switch, blades
 * across the band (world_draw_tiles_to, out to MEASURE_SEAM_REACH beyond
 * its far window). Nearer than the band's centre the reference is the
 * frame itself: the tiles made for it are all idle, and the frame's near
 * blades are what both sides share (a trail there would otherwise count). */
static bool blades_canopy_seam(world_t *w, const grass_view_t *v, const gfx_target_t *t, eval_seam_t *out)
{
    world_info_t wi = world_info(w);
    eval_seam_desc_t d = measure_seam_desc(w);
    measure_seam_frame_t frame = {0}, ref = {0}, bg = {0};
    bool ok = measure_seam_frame_draw(w, v, t, wi.mode, true, &frame) &&
              world_draw_tiles_to(w, v, t, measure_canopy_seam_reach(d.switch_distance)) &&
              measure_seam_frame_read(w, v, t, &ref) && measure_seam_frame_draw(w, v, t, wi.mode, false, &bg);
    for (size_t i = 0, n = (size_t)t->w * (size_t)t->h; ok && i < n; i++)
        if (bg.dist[i] < d.switch_distance) memcpy(ref.img.px + i * 4, frame.img.px + i * 4, 4);
    return seam_counted(&frame, &ref, &bg, ok, &d, true, out);
}

bool measure_canopy_seam(world_t *w, const grass_view_t *v, const gfx_target_t *t, eval_seam_t *out)
{
    memset(out, 0, sizeof *out);
    world_info_t wi = world_info(w);
    if (!wi.tiles || !wi.canopy) return false;
    if (!wi.billboards) return blades_canopy_seam(w, v, t, out);
    eval_seam_desc_t d = {.switch_distance = wi.scene->grass.canopy_distance, .fade = GRASS_CANOPY_FADE};
    return world_seam(w, v, t, &d, true, out);
}

bool measure_seam_floor(world_t *w, const grass_view_t *v, const gfx_target_t *t, measure_seam_floor_t *out)
{
    memset(out, 0, sizeof *out);
    world_info_t wi = world_info(w);
    if (wi.mode != SCENE_MODE_HYBRID || !wi.billboards) return false;
    measure_seam_frame_t ref = {0}, bg = {0};
    bool ok = measure_seam_frame_draw(w, v, t, SCENE_MODE_BILLBOARD, true, &ref) &&
              measure_seam_frame_draw(w, v, t, wi.mode, false, &bg);
    uint32_t seed = world_placement_seed(w);
    for (int k = 0; ok && k < MEASURE_SEAM_FLOOR_PLACEMENTS; k++) {
        measure_seam_frame_t other = {0};
        eval_seam_t e;
        bb_field_t *field = world_build_billboards(w, seed ^ (MEASURE_SEAM_FLOOR_SEED * (uint32_t)(k + 1)));
        ok = field != NULL;
        if (ok) {
            bb_field_t *keep = world_swap_billboards(w, field);
            ok = measure_seam_frame_draw(w, v, t, SCENE_MODE_BILLBOARD, true, &other);
            world_swap_billboards(w, keep);
            bb_field_destroy(field);
        }
        /* seam_of classifies ref again against the same background: the
         * same classes every time. */
        if (ok) ok = seam_of(w, &other, &ref, &bg, &e);
        measure_seam_frame_free(&other);
        if (!ok) break;
        out->score[k] = e.score;
        out->mean.score += e.score / MEASURE_SEAM_FLOOR_PLACEMENTS;
        out->mean.delta_e += e.delta_e / MEASURE_SEAM_FLOOR_PLACEMENTS;
        out->mean.delta_l += e.delta_l / MEASURE_SEAM_FLOOR_PLACEMENTS;
        out->mean.coverage += e.coverage / MEASURE_SEAM_FLOOR_PLACEMENTS;
    }
    measure_seam_frame_free(&ref);
    measure_seam_frame_free(&bg);
    if (!ok) memset(out, 0, sizeof *out);
    return ok;
}
