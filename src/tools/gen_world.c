/* meadow_gen_world: writes the open-world bench scenes
 * scenes/bench/world_1km.json, world.json (2 km) and world_4km.json: the
 * same world (seed, generator, amplitude) cut to 1, 2 and 4 km, grass
 * everywhere but the noise clearings, hybrid mode, 16 walkers spread over
 * the world on looping paths, and a camera path of about 110 s that walks
 * (1.5 m/s, eye 1.7 m above the ground), runs (6 m/s), flies low (10 m)
 * and high (120 m) to the other side of the world, descends and walks
 * again. Heights come from terrain_world_height; the keys are then raised
 * where the Catmull-Rom path between them (cam_path_eval) would pass less
 * than WORLD_MIN_CLEARANCE above the ground (test_world_scenes checks
 * >= 1 m at 0.1 s steps). Blades thinned by the levels rule; world.json
 * names the lod table measured on it (docs/HYBRID.md). Run from the
 * repository root:
 *   ./build/src/tools/meadow_gen_world */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/core.h"
#include "scene/camera.h"
#include "terrain/terrain.h"

#define WORLD_SEED 32u
#define WORLD_HEIGHT 30.0f
#define WORLD_MIN_CLEARANCE 1.3f /* m, with margin over the test's 1 m */
#define WALKERS 16

/* One leg of the camera's trip: keys every `step` s for `duration` s. */
typedef struct leg_t {
    float duration, step, speed;  /* s, s, m/s (0: reach `to` at the leg's end) */
    float turn;                   /* heading change, degrees per second */
    float clearance;              /* eye above the ground at the leg's end (m); starts at the previous leg's */
    float pitch;                  /* look down (degrees) */
    float to[2];                  /* fraction of the world's side to head for when speed is 0 */
} leg_t;

static const leg_t legs[] = {
    {14.0f, 2.0f, 1.5f, 0.0f, 1.7f, 8.0f, {0}},     /* walk */
    {12.0f, 1.5f, 6.0f, 2.0f, 1.7f, 8.0f, {0}},     /* run */
    {4.0f, 2.0f, 9.0f, 0.0f, 10.0f, 12.0f, {0}},    /* take off */
    {20.0f, 2.5f, 15.0f, -3.0f, 10.0f, 12.0f, {0}}, /* fly low */
    {8.0f, 4.0f, 18.0f, 0.0f, 120.0f, 25.0f, {0}},  /* climb */
    {30.0f, 6.0f, 0.0f, 0.0f, 120.0f, 30.0f, {0.3f, -0.3f}}, /* fly high across the world */
    {10.0f, 2.5f, 0.0f, 0.0f, 10.0f, 20.0f, {0.2f, -0.15f}}, /* descend */
    {6.0f, 2.0f, 5.0f, 0.0f, 1.7f, 10.0f, {0}},     /* land */
    {8.0f, 2.0f, 1.5f, 0.0f, 1.7f, 8.0f, {0}},      /* walk */
};

static float ground(const terrain_world_t *w, float x, float z) { return terrain_world_height(w, x, z, NULL); }

/* Keys of the camera path for a world of side `size`. */
static void plan_camera(const terrain_world_t *w, cam_path_t *path)
{
    float size = w->size, x = -0.25f * size, z = 0.25f * size, heading = atan2f(-0.6f, 0.8f), t = 0.0f;
    float clearance = legs[0].clearance, pitch = legs[0].pitch;
    path->count = 0;
    for (size_t l = 0; l <= sizeof legs / sizeof legs[0]; l++) {
        const leg_t *g = l < sizeof legs / sizeof legs[0] ? &legs[l] : NULL;
        int steps = g ? (int)lroundf(g->duration / g->step) : 1;
        for (int s = 0; s < steps; s++) {
            float eye = ground(w, x, z) + clearance, ahead = 25.0f + clearance;
            cam_path_key_t *k = &path->keys[path->count++];
            k->t = t;
            glm_vec3_copy((vec3){x, eye, z}, k->position);
            glm_vec3_copy((vec3){x + ahead * cosf(heading), eye - ahead * tanf(glm_rad(pitch)),
                                 z + ahead * sinf(heading)},
                          k->target);
            if (!g) break;
            float speed = g->speed;
            if (speed <= 0.0f) {
                float dx = g->to[0] * size - x, dz = g->to[1] * size - z;
                heading = atan2f(dz, dx);
                speed = sqrtf(dx * dx + dz * dz) / (g->step * (float)(steps - s));
            }
            heading += glm_rad(g->turn) * g->step;
            x += speed * g->step * cosf(heading);
            z += speed * g->step * sinf(heading);
            clearance += (g->clearance - clearance) / (float)(steps - s);
            pitch = g->pitch;
            t += g->step;
        }
    }
}

/* Raises the keys around every 0.1 s sample less than WORLD_MIN_CLEARANCE
 * above the ground until none is. */
static void lift_camera(const terrain_world_t *w, cam_path_t *path)
{
    for (int pass = 0; pass < 100; pass++) {
        int low = 0;
        float end = path->keys[path->count - 1].t;
        for (int s = 0; (float)s * 0.1f <= end; s++) {
            cam_t cam = {0};
            float t = (float)s * 0.1f;
            cam_path_eval(path, t, &cam);
            float lack = WORLD_MIN_CLEARANCE - (cam.position[1] - ground(w, cam.position[0], cam.position[2]));
            if (lack <= 0.0f) continue;
            low++;
            for (int k = 0; k < path->count; k++)
                if (fabsf(path->keys[k].t - t) < 2.5f) {
                    path->keys[k].position[1] += lack * 0.5f;
                    path->keys[k].target[1] += lack * 0.5f;
                }
        }
        if (!low) return;
    }
}

/* Walker i: a loop of 6 waypoints around a centre on a 4 x 4 grid over the
 * world (jittered); walker 0 near the camera's start, 15 near its landing. */
static void walker_path(const terrain_world_t *w, int i, float pts[6][2])
{
    float size = w->size, cx, cz;
    if (i == 0) {
        cx = -0.25f * size + 12.0f;
        cz = 0.25f * size - 14.0f;
    } else if (i == WALKERS - 1) {
        cx = 0.2f * size - 20.0f;
        cz = -0.15f * size + 10.0f;
    } else {
        cx = (-0.375f + 0.25f * (float)(i % 4) + 0.1f * (core_hash_float(WORLD_SEED * 977u + (uint32_t)i) - 0.5f)) * size;
        cz = (-0.375f + 0.25f * (float)(i / 4) + 0.1f * (core_hash_float(WORLD_SEED * 991u + (uint32_t)i) - 0.5f)) * size;
    }
    float r = 10.0f + 10.0f * core_hash_float(WORLD_SEED * 733u + (uint32_t)i);
    for (int k = 0; k < 6; k++) {
        float a = (float)k * (float)GLM_PI / 3.0f, rr = r * (0.8f + 0.4f * (float)(k & 1));
        pts[k][0] = cx + rr * cosf(a);
        pts[k][1] = cz + rr * sinf(a);
    }
}

static void write_vec3(FILE *f, const char *key, const float *v, const char *tail)
{
    fprintf(f, "\"%s\": [%.2f, %.2f, %.2f]%s", key, (double)v[0], (double)v[1], (double)v[2], tail);
}

static void write_camera(FILE *f, const cam_path_t *path)
{
    fprintf(f, "  \"camera\": {\n    \"fov\": 60,\n    \"near\": 0.1,\n    \"far\": 2200,\n    ");
    write_vec3(f, "position", path->keys[0].position, ",\n    ");
    write_vec3(f, "target", path->keys[0].target, ",\n    \"path\": [\n");
    for (int k = 0; k < path->count; k++) {
        fprintf(f, "      {\"t\": %.1f, ", (double)path->keys[k].t);
        write_vec3(f, "position", path->keys[k].position, ", ");
        write_vec3(f, "target", path->keys[k].target, k + 1 < path->count ? "},\n" : "}\n");
    }
    fprintf(f, "    ]\n  },\n");
}

static void write_walkers(FILE *f, const terrain_world_t *w)
{
    fprintf(f, "  \"characters\": [\n");
    for (int i = 0; i < WALKERS; i++) {
        float pts[6][2];
        walker_path(w, i, pts);
        fprintf(f, "    {\"model\": \"models/humanoid.gltf\", \"clip\": \"walk\", \"speed\": %.2f, \"loop\": true, "
                   "\"path\": [",
                1.1 + 0.3 * core_hash_float(WORLD_SEED * 419u + (uint32_t)i));
        for (int k = 0; k < 6; k++)
            fprintf(f, "[%.1f, %.1f]%s", (double)pts[k][0], (double)pts[k][1], k < 5 ? ", " : "");
        fprintf(f, "]}%s\n", i + 1 < WALKERS ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
}

static bool write_scene(const char *path, float size, const char *lod_table)
{
    terrain_world_t w = terrain_world_make(
        &(terrain_desc_t){.type = TERRAIN_WORLD, .size = size, .height = WORLD_HEIGHT}, WORLD_SEED);
    cam_path_t cam;
    plan_camera(&w, &cam);
    lift_camera(&w, &cam);
    FILE *f = fopen(path, "w");
    if (!f) {
        core_log_error("%s: cannot write", path);
        return false;
    }
    float end = cam.keys[cam.count - 1].t;
    fprintf(f,
            "{\n  \"seed\": %u,\n  \"frames\": %d,\n  \"size\": [1920, 1080],\n  \"msaa\": 4,\n  \"mode\": \"hybrid\",\n"
            "  \"terrain\": {\"type\": \"world\", \"size\": %g, \"height\": %g},\n"
            "  \"grass\": {\"density\": 250, \"billboard_density\": 20, \"switch_distance\": 25, \"tile_size\": 8, "
            "\"lod\": {\"rule\": \"levels\"},\n"
            "            \"clearings\": {\"type\": \"noise\", \"fraction\": 0.15, \"size\": 64}%s%s%s},\n",
            WORLD_SEED, (int)lroundf(end * 60.0f), (double)size, (double)WORLD_HEIGHT,
            lod_table ? ",\n            \"lod_table\": \"" : "", lod_table ? lod_table : "", lod_table ? "\"" : "");
    write_camera(f, &cam);
    fprintf(f, "  \"wind\": [{\"type\": \"directional\", \"direction\": [1, 0.3], \"strength\": 1.0, "
               "\"wavelength\": 10, \"speed\": 2}],\n");
    write_walkers(f, &w);
    bool ok = fclose(f) == 0;
    core_log_info("%s: %d camera keys over %.0f s", path, cam.count, (double)end);
    return ok;
}

int main(void)
{
    static const struct {
        const char *path;
        float size;
        const char *lod_table; /* measured on that scene (docs/HYBRID.md) */
    } worlds[] = {{"scenes/bench/world_1km.json", 1024.0f, NULL},
                  {"scenes/bench/world.json", 2048.0f, "docs/perf/lod_h200_world.json"},
                  {"scenes/bench/world_4km.json", 4096.0f, NULL}};
    for (int i = 0; i < 3; i++)
        if (!write_scene(worlds[i].path, worlds[i].size, worlds[i].lod_table)) return 1;
    return 0;
}
