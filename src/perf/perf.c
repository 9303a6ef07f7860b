/* bench_perf: `meadow bench --perf DIR`: the bench scenes
 * (scenes/bench/{orthmann,nature,helicopter,fan128}.json in their own mode,
 * meadow_large.json in hybrid, billboard and blade mode, the 1, 2 and 4 km
 * worlds in hybrid mode and the 2 km world in blade mode), each through the
 * hardware and the compute rasterizer, in one process (one offscreen
 * session each, measure_session.c). Per run: the median of every GPU pass
 * over the frames after warm-up (frames/4), their sum, the hardware floor
 * of its grass triangles (measure_floor_ms), grass counts and GPU memory.
 * Writes DIR/perf.json and regenerates from it the section of
 * docs/PERFORMANCE.md between PERF_BEGIN and PERF_END and README.md's
 * summary between SUMMARY_BEGIN and SUMMARY_END (the rest of each file is
 * hand-written and kept; --doc FILE regenerates whichever sections FILE
 * has). --quick runs scenes/tiny.json in each mode for CI.
 * `--from FILE` takes a saved perf.json instead of running; `--baseline
 * FILE` then checks it against a committed one (perf_baseline.c). */
#include "perf/perf.h"

#include "measure/measure.h"
#include "measure/measure_session.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "platform/plat.h"
#include "scene/scene_fields.h"
#include "scene/scene_json.h"

#define PERF_BEGIN "<!-- perf:begin -->"
#define PERF_END "<!-- perf:end -->"
#define PERF_DOC "docs/PERFORMANCE.md"
#define SUMMARY_BEGIN "<!-- perf-summary:begin -->"
#define SUMMARY_END "<!-- perf-summary:end -->"
#define SUMMARY_DOC "README.md"

typedef struct perf_case_t {
    const char *scene;
    scene_mode_t mode;
} perf_case_t;

static const perf_case_t full_cases[] = {
    {"scenes/bench/orthmann.json", SCENE_MODE_BILLBOARD},   {"scenes/bench/nature.json", SCENE_MODE_BLADE},
    {"scenes/bench/helicopter.json", SCENE_MODE_BLADE},     {"scenes/bench/fan128.json", SCENE_MODE_BLADE},
    {"scenes/bench/meadow_large.json", SCENE_MODE_HYBRID},  {"scenes/bench/meadow_large.json", SCENE_MODE_BILLBOARD},
    {"scenes/bench/meadow_large.json", SCENE_MODE_BLADE},
    {"scenes/bench/world_1km.json", SCENE_MODE_HYBRID},     {"scenes/bench/world.json", SCENE_MODE_HYBRID},
    {"scenes/bench/world_4km.json", SCENE_MODE_HYBRID},     {"scenes/bench/world.json", SCENE_MODE_BLADE},
};
static const perf_case_t quick_cases[] = {
    {"scenes/tiny.json", SCENE_MODE_HYBRID},
    {"scenes/tiny.json", SCENE_MODE_BILLBOARD},
    {"scenes/tiny.json", SCENE_MODE_BLADE},
};

/* ---- measuring --------------------------------------------------------------------- */

/* Filled by the frame hook on the last frame. */
typedef struct perf_probe_t {
    int last;
    perf_run_t *run;
    measure_stats_t stats;
    bool compute;
    int raster_samples; /* the world's compute rasterizer samples per pixel */
} perf_probe_t;

static void probe_frame(world_t *w, int frame, float t, void *user)
{
    (void)t;
    perf_probe_t *p = user;
    if (frame != p->last) return;
    const scene_desc_t *s = world_info(w).scene;
    p->run->size[0] = s->size[0];
    p->run->size[1] = s->size[1];
    p->run->msaa = s->msaa;
    p->run->memory_mb = (double)gfx_memory_bytes() / (1024.0 * 1024.0);
    world_info_t wi = world_info(w);
    p->compute = wi.raster_compute;
    p->raster_samples = wi.raster_samples ? wi.raster_samples : SCENE_DEFAULT_RASTER_SAMPLES;
    measure_stats(w, &p->stats);
}

static void scene_short(const char *path, char *out, size_t size)
{
    const char *b = strrchr(path, '/');
    snprintf(out, size, "%s", b ? b + 1 : path);
    char *dot = strrchr(out, '.');
    if (dot) *dot = 0;
}

/* The smaller of two timings, ignoring a failed one (negative). */
static double faster(double a, double b)
{
    return a < 0.0 ? b : (b < 0.0 ? a : (b < a ? b : a));
}

static int measure_run(const perf_session_desc_t *o, const perf_case_t *c, scene_raster_t raster, int frames,
                       perf_run_t *r)
{
    char name[32];
    scene_short(c->scene, name, sizeof name);
    memset(r, 0, sizeof *r);
    snprintf(r->name, sizeof r->name, "%s/%s/%s", name, scene_mode_name(c->mode), scene_raster_name(raster));
    snprintf(r->scene, sizeof r->scene, "%s", c->scene);
    snprintf(r->mode, sizeof r->mode, "%s", scene_mode_name(c->mode));
    snprintf(r->raster, sizeof r->raster, "%s", scene_raster_name(raster));
    world_options_t oc = o->world;
    oc.scene = c->scene;
    oc.raster = 1 + (int)raster;
    measure_session_desc_t d = {.world = oc, .mode = c->mode, .mode_set = true, .frames = frames};
    perf_probe_t probe = {.last = frames - 1, .run = r};
    measure_session_hooks_t h = {.frame = probe_frame, .user = &probe};
    measure_metrics_t m;
    int rc = measure_session_run_hooks(&d, &h, NULL, &m);
    if (rc) return rc;
    r->fell_back = raster == SCENE_RASTER_COMPUTE && !probe.compute;
    if (r->fell_back) core_log_warn("perf: %s drew with the hardware path (no compute rasterizer)", r->name);
    r->cpu_ms = m.cpu_ms;
    /* A pass without a sample since warm-up (median 0) belongs to an
     * earlier session: the timers outlive the worlds. */
    for (int i = 0; i < m.pass_count; i++) {
        if (m.pass_ms[i] <= 0.0) continue;
        snprintf(r->pass_name[r->pass_count], sizeof r->pass_name[0], "%s", m.pass_name[i]);
        r->pass_ms[r->pass_count++] = m.pass_ms[i];
        if (strcmp(m.pass_name[i], "bb.generate") != 0) r->frame_ms += m.pass_ms[i];
    }
    r->blades = probe.stats.blades;
    r->blades_drawn = probe.stats.blade_survivors;
    r->billboards = probe.stats.billboards;
    r->triangles = probe.stats.triangles;
    /* Each floor the faster of two measurements: on the H100 one of them now
     * and then ran 3.7 times slower (meadow_large's hardware floor read
     * 27.7 ms in one run, 7.5 ms in every other). */
    r->floor_ms = -1.0;
    r->compute_floor_ms = -1.0;
    for (int k = 0; k < 2 && probe.stats.triangles > 0; k++) {
        r->floor_ms = faster(r->floor_ms, measure_floor_ms(probe.stats.triangles, r->size[0], r->size[1], r->msaa));
        r->compute_floor_ms = faster(r->compute_floor_ms, measure_floor_compute_ms(probe.stats.triangles, r->size[0],
                                                                               r->size[1], r->msaa,
                                                                               probe.raster_samples));
    }
    return 0;
}

static int measure(const perf_session_desc_t *o, bool quick, perf_t *p)
{
    const perf_case_t *cases = quick ? quick_cases : full_cases;
    int nc = quick ? (int)(sizeof quick_cases / sizeof quick_cases[0])
                   : (int)(sizeof full_cases / sizeof full_cases[0]);
    p->frames = o->frames_set ? o->frames : (quick ? 16 : 400);
    p->quick = quick;
    snprintf(p->renderer, sizeof p->renderer, "%s", (const char *)glGetString(GL_RENDERER));
    snprintf(p->gl_version, sizeof p->gl_version, "%s", (const char *)glGetString(GL_VERSION));
    time_t now = time(NULL);
    strftime(p->date, sizeof p->date, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    int total = nc * 2;
    double t0 = plat_time();
    for (int i = 0; i < nc; i++)
        for (int k = 0; k < 2; k++) {
            if (perf_interrupted(o)) {
                core_log_error("perf: interrupted after %d of %d runs", p->run_count, total);
                return 1;
            }
            perf_run_t *r = &p->runs[p->run_count];
            int rc = measure_run(o, &cases[i], k ? SCENE_RASTER_COMPUTE : SCENE_RASTER_HW, p->frames, r);
            if (rc) {
                core_log_error("perf: %s failed", r->name);
                return rc;
            }
            p->run_count++;
            fprintf(stderr, "perf: %2d/%d %-30s frame %8.3f ms  floor %7.3f ms  (%.0f s)\n", p->run_count, total,
                    r->name, r->frame_ms, r->floor_ms, plat_time() - t0);
        }
    return 0;
}

/* ---- perf.json ------------------------------------------------------------------- */

static void json_string(core_buf_t *b, const char *s)
{
    core_buf_put(b, "\"", 1);
    for (; *s; s++) {
        if (*s == '"' || *s == '\\') core_buf_printf(b, "\\%c", *s);
        else if ((unsigned char)*s < 0x20) core_buf_printf(b, "\\u%04x", (unsigned char)*s);
        else core_buf_put(b, s, 1);
    }
    core_buf_put(b, "\"", 1);
}

static bool write_json(const perf_t *p, const char *path)
{
    core_buf_t b = {0};
    core_buf_printf(&b, "{\n  \"renderer\": ");
    json_string(&b, p->renderer);
    core_buf_printf(&b, ",\n  \"gl_version\": ");
    json_string(&b, p->gl_version);
    core_buf_printf(&b, ",\n  \"date\": \"%s\",\n  \"frames\": %d,\n  \"quick\": %s,\n  \"runs\": [\n", p->date,
                    p->frames, p->quick ? "true" : "false");
    for (int i = 0; i < p->run_count; i++) {
        const perf_run_t *r = &p->runs[i];
        core_buf_printf(&b, "    {\n      \"name\": ");
        json_string(&b, r->name);
        core_buf_printf(&b, ",\n      \"scene\": ");
        json_string(&b, r->scene);
        core_buf_printf(&b,
                        ",\n      \"mode\": \"%s\", \"raster\": \"%s\", \"fell_back\": %s, \"size\": [%d, %d], "
                        "\"msaa\": %d,\n      \"frame_ms\": %.4f, \"cpu_ms\": %.3f, \"floor_ms\": %.4f, "
                        "\"compute_floor_ms\": %.4f, "
                        "\"memory_mb\": %.1f,\n      \"blades\": %ld, \"blades_drawn\": %ld, \"billboards\": %ld, "
                        "\"triangles\": %ld,\n      \"passes\": {",
                        r->mode, r->raster, r->fell_back ? "true" : "false", r->size[0], r->size[1], r->msaa,
                        r->frame_ms, r->cpu_ms, r->floor_ms, r->compute_floor_ms, r->memory_mb, r->blades,
                        r->blades_drawn,
                        r->billboards, r->triangles);
        for (int k = 0; k < r->pass_count; k++) {
            core_buf_printf(&b, "%s", k ? ", " : "");
            json_string(&b, r->pass_name[k]);
            core_buf_printf(&b, ": %.4f", r->pass_ms[k]);
        }
        core_buf_printf(&b, "}\n    }%s\n", i + 1 < p->run_count ? "," : "");
    }
    core_buf_printf(&b, "  ]\n}\n");
    bool ok = core_buf_write(&b, path);
    core_buf_free(&b);
    return ok;
}

static const char *get_string(const scene_json_t *o, const char *key)
{
    const scene_json_t *v = scene_json_get(o, key);
    return v && v->type == SCENE_JSON_STRING ? v->string : NULL;
}

static double get_number(const scene_json_t *o, const char *key, double fallback)
{
    const scene_json_t *v = scene_json_get(o, key);
    return v && v->type == SCENE_JSON_NUMBER ? v->number : fallback;
}

static bool get_bool(const scene_json_t *o, const char *key)
{
    const scene_json_t *v = scene_json_get(o, key);
    return v && v->type == SCENE_JSON_BOOL && v->boolean;
}

/* One run object; false with err set when it lacks name or passes. */
static bool read_run(const scene_json_t *o, perf_run_t *r, char *err, size_t err_size)
{
    const char *name = get_string(o, "name");
    const scene_json_t *passes = scene_json_get(o, "passes");
    if (o->type != SCENE_JSON_OBJECT || !name || !passes || passes->type != SCENE_JSON_OBJECT) {
        snprintf(err, err_size, "%d: a run needs a \"name\" string and a \"passes\" object", o->line);
        return false;
    }
    snprintf(r->name, sizeof r->name, "%s", name);
    snprintf(r->scene, sizeof r->scene, "%s", get_string(o, "scene") ? get_string(o, "scene") : "");
    snprintf(r->mode, sizeof r->mode, "%s", get_string(o, "mode") ? get_string(o, "mode") : "");
    snprintf(r->raster, sizeof r->raster, "%s", get_string(o, "raster") ? get_string(o, "raster") : "");
    r->fell_back = get_bool(o, "fell_back");
    const scene_json_t *size = scene_json_get(o, "size");
    if (size && size->type == SCENE_JSON_ARRAY && size->count == 2) {
        r->size[0] = (int)size->child->number;
        r->size[1] = (int)size->child->next->number;
    }
    r->msaa = (int)get_number(o, "msaa", 0);
    r->frame_ms = get_number(o, "frame_ms", 0);
    r->cpu_ms = get_number(o, "cpu_ms", 0);
    r->floor_ms = get_number(o, "floor_ms", -1);
    r->compute_floor_ms = get_number(o, "compute_floor_ms", -1);
    r->memory_mb = get_number(o, "memory_mb", 0);
    r->blades = (long)get_number(o, "blades", 0);
    r->blades_drawn = (long)get_number(o, "blades_drawn", 0);
    r->billboards = (long)get_number(o, "billboards", 0);
    r->triangles = (long)get_number(o, "triangles", 0);
    for (const scene_json_t *v = passes->child; v; v = v->next) {
        if (v->type != SCENE_JSON_NUMBER || v->number < 0) {
            snprintf(err, err_size, "%d: pass \"%s\" of run \"%s\" is not a number of ms", v->line, v->key, name);
            return false;
        }
        if (r->pass_count == GFX_TIMER_MAX_PASSES) {
            snprintf(err, err_size, "%d: run \"%s\" has more than %d passes", v->line, name, GFX_TIMER_MAX_PASSES);
            return false;
        }
        snprintf(r->pass_name[r->pass_count], sizeof r->pass_name[0], "%s", v->key);
        r->pass_ms[r->pass_count++] = v->number;
    }
    return true;
}

int perf_read(const char *path, perf_t *p)
{
    memset(p, 0, sizeof *p);
    char err[512];
    char *text = core_fs_read(path, NULL, err, sizeof err);
    if (!text) {
        core_log_error("%s: %s", path, err);
        return 2;
    }
    scene_json_doc_t doc = {0};
    bool ok = scene_json_parse(&doc, text, path, err, sizeof err);
    free(text);
    if (!ok) {
        core_log_error("%s", err);
        return 2;
    }
    const scene_json_t *root = doc.root;
    const char *renderer = root->type == SCENE_JSON_OBJECT ? get_string(root, "renderer") : NULL;
    const scene_json_t *runs = renderer ? scene_json_get(root, "runs") : NULL;
    if (!runs || runs->type != SCENE_JSON_ARRAY) {
        core_log_error("%s: not a perf.json (needs a \"renderer\" string and a \"runs\" array)", path);
        scene_json_free(&doc);
        return 2;
    }
    snprintf(p->renderer, sizeof p->renderer, "%s", renderer);
    snprintf(p->gl_version, sizeof p->gl_version, "%s", get_string(root, "gl_version") ? get_string(root, "gl_version") : "");
    snprintf(p->date, sizeof p->date, "%s", get_string(root, "date") ? get_string(root, "date") : "");
    p->frames = (int)get_number(root, "frames", 0);
    p->quick = get_bool(root, "quick");
    int rc = 0;
    for (const scene_json_t *r = runs->child; r && rc == 0; r = r->next) {
        if (p->run_count == PERF_MAX_RUNS) {
            core_log_error("%s:%d: more than %d runs", path, r->line, PERF_MAX_RUNS);
            rc = 2;
        } else if (!read_run(r, &p->runs[p->run_count++], err, sizeof err)) {
            core_log_error("%s:%s", path, err);
            rc = 2;
        }
    }
    scene_json_free(&doc);
    return rc;
}

/* ---- docs/PERFORMANCE.md ----------------------------------------------------------- */

const perf_run_t *perf_find(const perf_t *p, const char *name)
{
    for (int i = 0; i < p->run_count; i++)
        if (strcmp(p->runs[i].name, name) == 0) return &p->runs[i];
    return NULL;
}

/* The run of r's scene and mode through the other rasterizer
 * ("<scene>/<mode>/hw" <-> ".../compute"); NULL when the perf.json has none. */
static const perf_run_t *run_twin(const perf_t *p, const perf_run_t *r)
{
    size_t len = strlen(r->name), tail = strlen(r->raster);
    if (len <= tail || strcmp(r->name + len - tail, r->raster) != 0) return NULL;
    char name[80];
    snprintf(name, sizeof name, "%.*s%s", (int)(len - tail), r->name, strcmp(r->raster, "hw") == 0 ? "compute" : "hw");
    return perf_find(p, name);
}

static double pass_sum(const perf_run_t *r, const char *const *names)
{
    double s = 0;
    for (; *names; names++)
        for (int k = 0; k < r->pass_count; k++)
            if (strcmp(r->pass_name[k], *names) == 0) s += r->pass_ms[k];
    return s;
}

/* Targets of the project (issue 1), checked on both rasterizers: a target is
 * met when one of them meets it (--raster auto takes the faster). */
typedef enum perf_measure_t { MEASURE_FRAME = 0, MEASURE_PASSES, MEASURE_MEMORY } perf_measure_t;
typedef struct perf_target_t {
    const char *label, *run; /* run: name without the "/<raster>" */
    perf_measure_t measure;
    const char *passes[4];
    double limit; /* ms or MB */
} perf_target_t;

static const perf_target_t targets[] = {
    {"nature: frame <= 2 ms", "nature/blade", MEASURE_FRAME, {0}, 2.0},
    {"nature: physics <= 0.1 ms", "nature/blade", MEASURE_PASSES, {"blade.physics"}, 0.1},
    {"fan128: simulation <= 0.5 ms", "fan128/blade", MEASURE_PASSES, {"blade.physics"}, 0.5},
    {"fan128: frame <= 5 ms", "fan128/blade", MEASURE_FRAME, {0}, 5.0},
    {"orthmann: collision + recovery <= 0.5 ms", "orthmann/billboard", MEASURE_PASSES,
     {"bb.cubemaps", "bb.collide", "bb.recover"}, 0.5},
    {"meadow: frame <= 8 ms", "meadow_large/hybrid", MEASURE_FRAME, {0}, 8.0},
    {"meadow: GPU memory <= 512 MB", "meadow_large/hybrid", MEASURE_MEMORY, {0}, 512.0},
    {"world: GPU memory <= 512 MB", "world/hybrid", MEASURE_MEMORY, {0}, 512.0},
};

static double target_value(const perf_target_t *t, const perf_run_t *r)
{
    switch (t->measure) {
    case MEASURE_PASSES: return pass_sum(r, t->passes);
    case MEASURE_MEMORY: return r->memory_mb;
    default: return r->frame_ms;
    }
}

/* v with its unit ("-" when negative: not measured); MB to 0.1, ms to 0.001. */
static void cell(char *out, size_t size, double v, const char *unit)
{
    if (v < 0) snprintf(out, size, "-");
    else snprintf(out, size, "%.*f%s", strcmp(unit, " MB") == 0 ? 1 : 3, v, unit);
}

static void write_section(core_buf_t *b, const perf_t *p)
{
    core_buf_printf(b,
                    "<!-- generated by `meadow bench --perf` from its perf.json: edit src/perf/perf.c, "
                    "not this section -->\n\n"
                    "- renderer: `%s` (%s)\n- run: %s, %d frames per run%s; each pass figure is the median of its "
                    "GL timer over the frames after the first %d (at most the last 256); frame = sum of the pass "
                    "medians\n\n",
                    p->renderer, p->gl_version[0] ? p->gl_version : "?", p->date[0] ? p->date : "?",
                    p->frames, p->quick ? " (--quick: CI sizes, not the bench scenes)" : "", p->frames / 4);
    if (strstr(p->renderer, "llvmpipe"))
        core_buf_printf(b, "GPU times from llvmpipe are not meaningful (CPU rasteriser); rerun on a GPU.\n\n");
    core_buf_printf(b, "### Per run\n\n"
                       "| run | size, MSAA | grass | frame ms (sum) | compute/hw | floor ms | frame/floor | "
                       "compute floor ms | frame/compute floor | GPU memory | CPU ms/frame |\n"
                       "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (int i = 0; i < p->run_count; i++) {
        const perf_run_t *r = &p->runs[i], *hw = strcmp(r->raster, "compute") == 0 ? run_twin(p, r) : NULL;
        char grass[128] = "", vs[32] = "-", fl[32], ratio[32] = "-", cfl[32], cratio[32] = "-";
        int n = 0;
        if (r->blades) n += snprintf(grass + n, sizeof grass - (size_t)n, "%ld blades, %ld drawn", r->blades,
                                     r->blades_drawn);
        if (r->billboards && n < (int)sizeof grass)
            n += snprintf(grass + n, sizeof grass - (size_t)n, "%s%ld billboards", n ? "; " : "", r->billboards);
        if (hw && hw->frame_ms > 0) snprintf(vs, sizeof vs, "%.2f", r->frame_ms / hw->frame_ms);
        cell(fl, sizeof fl, r->floor_ms, "");
        if (r->floor_ms > 0) snprintf(ratio, sizeof ratio, "%.2f", r->frame_ms / r->floor_ms);
        cell(cfl, sizeof cfl, r->compute_floor_ms, "");
        if (r->compute_floor_ms > 0) snprintf(cratio, sizeof cratio, "%.2f", r->frame_ms / r->compute_floor_ms);
        core_buf_printf(b, "| %s%s | %dx%d, %dx | %s | **%.3f** | %s | %s | %s | %s | %s | %.1f MB | %.2f |\n",
                        r->name, r->fell_back ? " (fell back to hw)" : "", r->size[0], r->size[1], r->msaa,
                        grass[0] ? grass : "-", r->frame_ms, vs, fl, ratio, cfl, cratio, r->memory_mb, r->cpu_ms);
    }
    core_buf_printf(b, "\n### Pass medians (ms)\n\n| run | passes |\n| --- | --- |\n");
    for (int i = 0; i < p->run_count; i++) {
        const perf_run_t *r = &p->runs[i];
        core_buf_printf(b, "| %s |", r->name);
        for (int k = 0; k < r->pass_count; k++)
            core_buf_printf(b, "%s %s %.4f", k ? "," : "", r->pass_name[k], r->pass_ms[k]);
        core_buf_printf(b, " |\n");
    }
    bool header = false;
    for (int i = 0; i < (int)(sizeof targets / sizeof targets[0]); i++) {
        const perf_target_t *t = &targets[i];
        char name[80];
        snprintf(name, sizeof name, "%s/hw", t->run);
        const perf_run_t *hw = perf_find(p, name);
        snprintf(name, sizeof name, "%s/compute", t->run);
        const perf_run_t *cs = perf_find(p, name);
        if (!hw && !cs) continue;
        if (!header)
            core_buf_printf(b, "\n### Targets\n\n| target | hw | compute | met? |\n| --- | --- | --- | --- |\n");
        header = true;
        const char *unit = t->measure == MEASURE_MEMORY ? " MB" : " ms";
        double vh = hw ? target_value(t, hw) : -1, vc = cs ? target_value(t, cs) : -1;
        char ch[32], cc[32];
        cell(ch, sizeof ch, vh, unit);
        cell(cc, sizeof cc, vc, unit);
        bool mh = hw && vh <= t->limit, mc = cs && vc <= t->limit;
        core_buf_printf(b, "| %s | %s | %s | %s |\n", t->label, ch, cc,
                        mh && mc ? "yes" : mh ? "yes (hw)" : mc ? "yes (compute)" : "**no**");
    }
    core_buf_printf(b, "\n");
}

/* README.md's summary: frame times of the largest scene's runs (meadow_large
 * in the bench set, the first run's scene otherwise), hardware against
 * compute rasterizer per mode. */
static void write_summary(core_buf_t *b, const perf_t *p)
{
    char scene[64] = "";
    for (int i = 0; i < p->run_count && !scene[0]; i++)
        if (strncmp(p->runs[i].name, "meadow_large/", 13) == 0) snprintf(scene, sizeof scene, "meadow_large/");
    if (!scene[0] && p->run_count) snprintf(scene, sizeof scene, "%.*s/", (int)strcspn(p->runs[0].name, "/"),
                                            p->runs[0].name);
    core_buf_printf(b, "<!-- generated by `meadow bench --perf` from its perf.json (the committed one: "
                       "docs/perf/h100.json): edit src/perf/perf.c, not this section -->\n\n");
    bool first = true;
    for (int i = 0; i < p->run_count; i++) {
        const perf_run_t *hw = &p->runs[i];
        if (strcmp(hw->raster, "hw") != 0 || strncmp(hw->name, scene, strlen(scene)) != 0) continue;
        const perf_run_t *cs = run_twin(p, hw);
        if (!cs) continue;
        if (first)
            core_buf_printf(b, "%.*s at %dx%d on `%s` (%s), frame = sum of the GL pass medians, hardware -> "
                               "compute rasterizer:",
                            (int)strlen(scene) - 1, scene, hw->size[0], hw->size[1], p->renderer,
                            p->date[0] ? p->date : "?");
        core_buf_printf(b, "%s %s %.2f -> %.2f ms", first ? "" : ",", hw->mode, hw->frame_ms, cs->frame_ms);
        first = false;
    }
    core_buf_printf(b, first ? "No hardware/compute pair of runs in this perf.json.\n\n" : ".\n\n");
}

typedef struct perf_section_t {
    const char *begin, *end;
    void (*write)(core_buf_t *b, const perf_t *p);
} perf_section_t;

static const perf_section_t sections[] = {
    {PERF_BEGIN, PERF_END, write_section},
    {SUMMARY_BEGIN, SUMMARY_END, write_summary},
};

/* Replaces the text between the markers of every section doc holds; a doc
 * with none is an error. */
static int update_doc(const perf_t *p, const char *doc)
{
    char err[512];
    char *text = core_fs_read(doc, NULL, err, sizeof err);
    if (!text) {
        core_log_error("%s: %s", doc, err);
        return 2;
    }
    int found = 0;
    for (size_t k = 0; k < sizeof sections / sizeof sections[0]; k++) {
        const perf_section_t *sec = &sections[k];
        char *begin = strstr(text, sec->begin);
        char *end = begin ? strstr(begin, sec->end) : NULL;
        if (!end) continue;
        core_buf_t b = {0};
        core_buf_put(&b, text, (size_t)(begin - text) + strlen(sec->begin));
        core_buf_printf(&b, "\n");
        sec->write(&b, p);
        core_buf_printf(&b, "%s", end);
        core_buf_put(&b, "", 1);
        free(text);
        text = b.data;
        found++;
    }
    if (!found) {
        core_log_error("%s: no '%s' ... '%s' (or '%s' ... '%s') section to regenerate", doc, PERF_BEGIN, PERF_END,
                       SUMMARY_BEGIN, SUMMARY_END);
        free(text);
        return 2;
    }
    core_buf_t out = {0};
    core_buf_put(&out, text, strlen(text));
    int rc = core_buf_write(&out, doc) ? 0 : 1;
    core_buf_free(&out);
    free(text);
    if (rc == 0) core_log_info("perf: regenerated %d measured section(s) of %s", found, doc);
    return rc;
}

/* ---- the command ------------------------------------------------------------------- */

static int measure_and_write(const perf_options_t *o, perf_t *p, char *json, size_t json_size)
{
    char err[1024];
    const char *dir = o->perf ? o->perf : o->out ? o->out : "out/bench";
    if (!core_fs_check_writable_dir(dir, err, sizeof err) || !core_fs_lock_dir(dir, err, sizeof err)) {
        core_log_error("%s: %s", o->perf ? "--perf" : "--out", err);
        return 2;
    }
    if (!plat_init(&(plat_desc_t){.backend = PLAT_BACKEND_EGL}, err, sizeof err)) {
        core_log_error("no OpenGL 4.5 context: %s", err);
        return 1;
    }
    gfx_init();
    int rc = measure(&o->session, o->quick, p);
    gfx_shutdown(true);
    int gl_errors = plat_gl_error_count();
    plat_shutdown();
    if (gl_errors) {
        core_log_error("%d GL error(s) during bench --perf", gl_errors);
        rc = rc ? rc : 1;
    }
    if (rc) return rc;
    snprintf(json, json_size, "%s/perf.json", dir);
    if (!write_json(p, json)) return 1;
    core_log_info("perf: wrote %s (%d runs)", json, p->run_count);
    /* The doc and the check take the numbers as written (rounded), so the
     * doc regenerated later from this file comes out the same. */
    return perf_read(json, p);
}

int perf_main(const perf_options_t *o)
{
    perf_t *cur = calloc(1, sizeof *cur), *base = NULL;
    if (!cur) return 1;
    char json[1100];
    int rc = o->perf_from ? perf_read(o->perf_from, cur) : measure_and_write(o, cur, json, sizeof json);
    const char *doc = o->doc ? o->doc : o->perf && !o->quick ? PERF_DOC : NULL;
    /* The committed doc describes the H100: a run elsewhere (a laptop,
     * llvmpipe) leaves it alone unless --doc names a file. */
    if (rc == 0 && doc && !o->doc && !strstr(cur->renderer, "H100")) {
        core_log_info("perf: %s not regenerated: renderer '%s' is not the H100 it describes (--doc FILE writes "
                      "one anyway)", doc, cur->renderer);
        doc = NULL;
    }
    if (rc == 0 && doc) rc = update_doc(cur, doc);
    if (rc == 0 && doc && !o->doc) rc = update_doc(cur, SUMMARY_DOC);
    if (rc == 0 && o->baseline) {
        base = calloc(1, sizeof *base);
        rc = !base ? 1 : perf_read(o->baseline, base);
        if (rc == 0) rc = perf_baseline_check(cur, base, o->baseline, o->force);
    }
    free(cur);
    free(base);
    return rc;
}
