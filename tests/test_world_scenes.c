/* test_world_scenes: the open-world bench scenes (scenes/bench/world_1km,
 * world, world_4km; written by meadow_gen_world). One world: same seed,
 * generator and amplitude, sides 1, 2 and 4 km, hybrid mode, 16 humanoid
 * walkers whose looping paths stay inside the world and spread over it.
 * The camera path lasts at least 60 s, stays inside the world square, and
 * every key and the interpolated path at 0.1 s steps (cam_path_eval) is at
 * least 1 m above terrain_world_height; it walks (~1.5 m/s, eye ~1.7 m),
 * runs (~6 m/s), flies low (~10 m) and high (>= 80 m) for at least 4 s each,
 * and reaches both halves of the world. */
#include <stdio.h>
#include <string.h>

#include "scene/camera.h"
#include "scene/scene.h"
#include "terrain/terrain.h"
#include "test.h"

enum { WALK, RUN, LOW, HIGH, REGIMES };

static void check_camera(const scene_desc_t *s, const terrain_world_t *w)
{
    const cam_path_t *p = &s->camera.path;
    float half = w->size * 0.5f, end = p->keys[p->count - 1].t, worst = 1e9f;
    double regime[REGIMES] = {0};
    float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
    for (int k = 0; k < p->count; k++) {
        const float *q = p->keys[k].position;
        worst = fminf(worst, q[1] - terrain_world_height(w, q[0], q[2], NULL));
    }
    cam_t prev = {0};
    for (int i = 0; (float)i * 0.1f <= end; i++) {
        cam_t c = {0};
        cam_path_eval(p, (float)i * 0.1f, &c);
        float above = c.position[1] - terrain_world_height(w, c.position[0], c.position[2], NULL);
        worst = fminf(worst, above);
        for (int a = 0; a < 2; a++) {
            lo[a] = fminf(lo[a], c.position[2 * a]);
            hi[a] = fmaxf(hi[a], c.position[2 * a]);
        }
        if (i > 0) {
            float speed = hypotf(c.position[0] - prev.position[0], c.position[2] - prev.position[2]) / 0.1f;
            if (above < 2.5f && speed > 1.0f && speed < 2.0f) regime[WALK] += 0.1;
            if (above < 2.5f && speed > 5.0f && speed < 7.0f) regime[RUN] += 0.1;
            if (above > 6.0f && above < 20.0f) regime[LOW] += 0.1;
            if (above >= 80.0f) regime[HIGH] += 0.1;
        }
        prev = c;
    }
    printf("  camera: %d keys, %.0f s, lowest %.2f m above ground, x [%.0f, %.0f] z [%.0f, %.0f]; "
           "walk %.1f s, run %.1f s, low %.1f s, high %.1f s\n",
           p->count, (double)end, (double)worst, (double)lo[0], (double)hi[0], (double)lo[1], (double)hi[1],
           regime[WALK], regime[RUN], regime[LOW], regime[HIGH]);
    CHECK(end >= 60.0f);
    CHECK(worst >= 1.0f);
    CHECK(lo[0] > -half && lo[1] > -half && hi[0] < half && hi[1] < half);
    CHECK(hi[0] - lo[0] > 0.4f * half && hi[1] - lo[1] > 0.4f * half); /* across the world */
    for (int r = 0; r < REGIMES; r++) CHECK_MSG(regime[r] >= 4.0, "regime %d for %.1f s", r, regime[r]);
}

static void check_walkers(const scene_desc_t *s, const terrain_world_t *w)
{
    float half = w->size * 0.5f, lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
    CHECK(s->character_count == 16);
    for (int i = 0; i < s->character_count; i++) {
        const scene_character_t *c = &s->characters[i];
        CHECK(strcmp(c->model, "models/humanoid.gltf") == 0);
        CHECK(c->loop && c->waypoint_count >= 3 && c->speed > 0.5f && c->speed < 2.0f);
        for (int k = 0; k < c->waypoint_count; k++)
            for (int a = 0; a < 2; a++) {
                CHECK(fabsf(c->waypoints[k][a]) < half - 1.0f);
                lo[a] = fminf(lo[a], c->waypoints[k][a]);
                hi[a] = fmaxf(hi[a], c->waypoints[k][a]);
            }
    }
    printf("  walkers: %d over x [%.0f, %.0f] z [%.0f, %.0f]\n", s->character_count, (double)lo[0], (double)hi[0],
           (double)lo[1], (double)hi[1]);
    CHECK(hi[0] - lo[0] > half && hi[1] - lo[1] > half); /* spread over the world */
}

int main(void)
{
    static const char *const names[] = {"world_1km", "world", "world_4km"}; /* 1, 2, 4 km */
    static scene_desc_t s, first;
    for (int i = 0; i < 3; i++) {
        char path[1024], err[512];
        float size = 1024.0f * (float)(1 << i);
        snprintf(path, sizeof path, MEADOW_SOURCE_DIR "/scenes/bench/%s.json", names[i]);
        CHECK_MSG(scene_load(&s, path, err, sizeof err), "%s", err);
        printf("%s:\n", names[i]);
        CHECK(s.terrain.type == TERRAIN_WORLD && s.terrain.size == size && s.mode == SCENE_MODE_HYBRID);
        CHECK(s.camera.far >= 2000.0f);
        if (i == 0) first = s;
        CHECK(s.seed == first.seed && s.terrain.height == first.terrain.height);
        terrain_mesh_t m;
        CHECK(terrain_make_heightfield(&m, &s.terrain, s.seed));
        check_camera(&s, &m.world);
        check_walkers(&s, &m.world);
    }
    TEST_END();
}
