/* bench_papers: `meadow bench --papers DIR`: the measurements that make the
 * papers' own numbers readable beside ours.
 *   ablation  blade mode (forced) on each paper scene
 *             (scenes/bench/{orthmann,nature,helicopter,fan128}.json; the
 *             --scene alone outside --report): all features, collision off
 *             (no colliders and no characters), culling off (every
 *             BLADE_CULL_* test skipped, grass_tuning_t.cull_disable) and each
 *             test alone off, the distance test as eq. 19-20 state it
 *             (grass.lod rule LEVELS: the default WIDTH thins nothing on a
 *             field within its 10 m start, the CI's tiny.json), on the
 *             hardware and the compute rasterizer:
 *             GPU pass medians, blades drawn and culled by each test (the
 *             counters of summary.txt, measure_stats) at the last frame;
 *   leaves    Orthmann et al. 2009's cost against the number of colliding
 *             octree leaves: orthmann.json in billboard mode with 1, 2, 4,
 *             8, 16 balls (--quick: 1, 4) spread over its field, the mean
 *             of the leaves in the colliding state (bb_stats_t.leaves) over
 *             the timed frames against the bb.cubemaps, bb.collide,
 *             bb.recover and render pass medians, both paths;
 *   papers    per paper scene: the paper's hardware and published figure
 *             (paper_facts below, with their sources; "not available here"
 *             where no source at hand gives it), ours on both paths (the
 *             scene in its own mode) on the renderer the run names, and
 *             what the scene holds.
 * Writes DIR/papers.json, ablation.csv, leaves.csv, papers_leaves.dat, its
 * gnuplot chart (papers_leaves.png/.svg) and papers.md, the RESULTS.md
 * section (bench --report with --papers). Timings: the median of each pass
 * over the frames after warm-up (frames/4), as bench --perf; every figure
 * is the median over PAPERS_RUNS (3) sessions. */
#include "perf/perf.h"

#include "eval/eval.h"

#include "measure/measure.h"
#include "measure/measure_session.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "platform/plat.h"

/* What the papers publish, from the sources named (checked 2026-11-26). */
typedef struct paper_fact_t {
    const char *scene;    /* scenes/bench/<scene>.json */
    const char *paper;
    const char *hardware; /* the paper's GPU */
    const char *figure;   /* its published timing for the scene */
    const char *setup;    /* its scene as published */
    const char *source;
} paper_fact_t;

#define NOT_HERE "not available here"
static const paper_fact_t paper_facts[] = {
    {"orthmann", "Orthmann, Rezk-Salama, Kolb 2009, GPU-based responsive grass (J. WSCG 17, 65-72)", NOT_HERE,
     NOT_HERE, "billboard clumps against scene objects; scene " NOT_HERE, "https://dspace5.zcu.cz/handle/11025/1290"},
    {"nature", "Jahrmann, Wimmer 2017, Responsive real-time grass rendering for general 3D scenes (I3D)", NOT_HERE,
     NOT_HERE, NOT_HERE, "https://www.cg.tuwien.ac.at/research/publications/2017/JAHRMANN-2017-RRTG/"},
    {"helicopter", "Jahrmann, Wimmer 2017 (as above)", NOT_HERE, NOT_HERE, NOT_HERE,
     "https://www.cg.tuwien.ac.at/research/publications/2017/JAHRMANN-2017-RRTG/"},
    {"fan128", "Fan, Li, Hillesland, Sheng 2015, Simulation and rendering for millions of grass blades (I3D, "
               "doi 10.1145/2699276.2699283)",
     NOT_HERE, "frame < 20 ms, of it a few ms simulation", "over a million blades, 128 moving objects",
     "https://vdocuments.us/simulation-and-rendering-for-millions-of-grass-blades-and-rendering-for-millions.html"},
};
#define PAPER_COUNT ((int)(sizeof paper_facts / sizeof paper_facts[0]))

#define CULL_ALL (BLADE_CULL_ORIENTATION | BLADE_CULL_FRUSTUM | BLADE_CULL_DISTANCE | BLADE_CULL_OCCLUSION)
const perf_ablation_t perf_ablations[PERF_ABLATION_COUNT] = {
    {"all", false, 0},
    {"collision_off", true, 0},
    {"culling_off", false, CULL_ALL},
    {"orientation_off", false, BLADE_CULL_ORIENTATION},
    {"frustum_off", false, BLADE_CULL_FRUSTUM},
    {"distance_off", false, BLADE_CULL_DISTANCE},
    {"occlusion_off", false, BLADE_CULL_OCCLUSION},
};

#define MAX_SCENES PAPER_COUNT
#define MAX_LEAF_RUNS 5
static const int leaf_colliders[MAX_LEAF_RUNS] = {1, 2, 4, 8, 16};
#define LEAVES_SCENE "scenes/bench/orthmann.json"

/* One session's numbers. */
typedef struct papers_run_t {
    int scene;        /* index into papers_t.scene */
    int variant;      /* ablation index; -1 the scene in its own mode; -2 a leaves run */
    int colliders;    /* colliders (and characters) in the world */
    int size[2], msaa; /* the world's target, the MSAA its scene asks for */
    bool compute, fell_back;
    scene_mode_t mode;
    double frame_ms;  /* sum of the pass medians, bb.generate left out */
    double physics_ms, cull_ms, draw_ms; /* blade.physics, blade.cull, blade.draw or blade.raster */
    double cubemaps_ms, collide_ms, recover_ms, render_ms; /* bb.*; render: bb.render or bb.raster */
    long blades, drawn, billboards;
    unsigned culled[4];
    long patch_culled; /* blades of patches culled whole (blade_gpu stats; no BLADE_CULL test) */
    double leaves, recovering; /* colliding / recovering leaves, mean over the timed frames */
    double frame_spread; /* half the range of frame_ms over the PAPERS_RUNS runs */
} papers_run_t;

/* Sessions behind every figure: the timings (and leaves) are their
 * medians, the counters the first's (the same in every run: fixed seeds). */
#define PAPERS_RUNS 3
/* The fields a figure takes as the median over its runs. */
static const size_t papers_timed[] = {
    offsetof(papers_run_t, frame_ms),    offsetof(papers_run_t, physics_ms),  offsetof(papers_run_t, cull_ms),
    offsetof(papers_run_t, draw_ms),     offsetof(papers_run_t, cubemaps_ms), offsetof(papers_run_t, collide_ms),
    offsetof(papers_run_t, recover_ms),  offsetof(papers_run_t, render_ms),   offsetof(papers_run_t, leaves),
    offsetof(papers_run_t, recovering)};

#define MAX_RUNS (MAX_SCENES * (PERF_ABLATION_COUNT + 1) * 2 + MAX_LEAF_RUNS * 2)
typedef struct papers_t {
    char renderer[256];
    int frames, scene_count, run_count;
    bool quick;  /* --quick: fewer leaf runs, fewer colliders */
    int planned; /* runs of the whole set; more than run_count when interrupted */
    char scene[MAX_SCENES][256]; /* scene files */
    char name[MAX_SCENES][32];   /* their short names */
    scene_desc_t *desc;          /* MAX_SCENES scene files as loaded */
    papers_run_t runs[MAX_RUNS];
} papers_t;

/* ---- sessions ----------------------------------------------------------------------- */

typedef struct papers_probe_t {
    papers_run_t *run;
    int warmup, last, samples;
    int colliders_wanted; /* leaves runs: balls spread over the field; 0 = the scene's */
    const perf_ablation_t *ablation;
} papers_probe_t;

/* Leaves runs: n balls like the scene's first, each crossing the field
 * along x (every other one the other way) on its own line of z. */
static void spread_balls(scene_desc_t *s, int n)
{
    scene_collider_t ball = s->colliders[0];
    float half = 0.4f * s->terrain.size;
    for (int i = 0; i < n; i++) {
        scene_collider_t *k = &s->colliders[i];
        *k = ball;
        k->loop = true;
        k->path.count = 3;
        float z = -half + 2.0f * half * ((float)i + 0.5f) / (float)n, x = (i & 1) ? half : -half;
        for (int e = 0; e < 3; e++) {
            k->path.keys[e].t = 8.0f * (float)e;
            k->path.keys[e].position[0] = e == 1 ? -x : x;
            k->path.keys[e].position[1] = ball.radius;
            k->path.keys[e].position[2] = z;
        }
    }
    s->collider_count = n;
    s->character_count = 0;
}

static void papers_tweak(scene_desc_t *s, void *user)
{
    const papers_probe_t *p = user;
    if (p->ablation) s->grass.lod.rule = BLADE_LOD_LEVELS;
    if (p->ablation && p->ablation->no_collision) {
        s->collider_count = 0;
        s->character_count = 0;
    }
    if (p->colliders_wanted > 0 && s->collider_count > 0) spread_balls(s, p->colliders_wanted);
}

static void papers_frame(world_t *w, int frame, float t, void *user)
{
    (void)t;
    papers_probe_t *p = user;
    if (world_info(w).billboards && frame >= p->warmup) {
        measure_grass_t mg;
        measure_grass(w, MEASURE_GRASS_LEAVES, false, &mg);
        p->run->leaves += mg.bb_leaves_colliding;
        p->run->recovering += mg.bb_leaves_recovering;
        p->samples++;
    }
    if (frame != p->last) return;
    measure_stats_t st;
    measure_stats(w, &st);
    p->run->blades = st.blades;
    p->run->drawn = st.blade_survivors;
    p->run->billboards = st.billboards;
    memcpy(p->run->culled, st.blade_culled, sizeof p->run->culled);
    p->run->patch_culled = st.blade_patch_culled;
    p->run->colliders = world_collider_count(w) + st.characters;
    const scene_desc_t *s = world_info(w).scene;
    p->run->size[0] = s->size[0];
    p->run->size[1] = s->size[1];
    p->run->msaa = s->msaa;
}

/* The median of pass `name` in m; 0 when it did not run in this session
 * (the timers outlive the worlds: a stale pass has no sample after warm-up). */
static double pass_of(const measure_metrics_t *m, const char *name)
{
    for (int i = 0; i < m->pass_count; i++)
        if (strcmp(m->pass_name[i], name) == 0) return m->pass_ms[i] > 0.0 ? m->pass_ms[i] : 0.0;
    return 0.0;
}

static void fill_passes(papers_run_t *r, const measure_metrics_t *m)
{
    for (int i = 0; i < m->pass_count; i++)
        if (m->pass_ms[i] > 0.0 && strcmp(m->pass_name[i], "bb.generate") != 0) r->frame_ms += m->pass_ms[i];
    r->physics_ms = pass_of(m, "blade.physics");
    r->cull_ms = pass_of(m, "blade.cull");
    r->draw_ms = pass_of(m, r->compute ? "blade.raster" : "blade.draw");
    r->cubemaps_ms = pass_of(m, "bb.cubemaps");
    r->collide_ms = pass_of(m, "bb.collide");
    r->recover_ms = pass_of(m, "bb.recover");
    r->render_ms = pass_of(m, r->compute ? "bb.raster" : "bb.render");
}

/* One session of scene `file` in `mode` through the path `compute`. */
static int papers_session(const perf_session_desc_t *o, const char *file, papers_run_t *r, int frames, papers_probe_t *p)
{
    world_options_t oc = o->world;
    oc.scene = file;
    oc.raster = 1 + (r->compute ? SCENE_RASTER_COMPUTE : SCENE_RASTER_HW);
    measure_session_desc_t d = {.world = oc, .mode = r->mode, .mode_set = true, .frames = frames,
                              .tweak = papers_tweak, .user = p};
    if (p->ablation) d.tuning.cull_disable = p->ablation->cull_disable;
    p->run = r;
    p->warmup = frames / 4;
    p->last = frames - 1;
    measure_session_hooks_t h = {.frame = papers_frame, .user = p};
    measure_metrics_t m;
    int rc = measure_session_run_hooks(&d, &h, NULL, &m);
    if (rc) return rc;
    r->fell_back = r->compute && !m.raster_compute;
    fill_passes(r, &m);
    if (p->samples > 0) {
        r->leaves /= p->samples;
        r->recovering /= p->samples;
    }
    return 0;
}

static void scene_short(const char *path, char *out, size_t size)
{
    const char *b = strrchr(path, '/');
    snprintf(out, size, "%s", b ? b + 1 : path);
    char *dot = strrchr(out, '.');
    if (dot) *dot = 0;
}

/* Sets up run r and its probe: scene s of P (scene_count: the leaves
 * figure), variant v (-1 the scene's own mode; the leaves: the v-th
 * collider count), path k (1 compute). Returns the scene file. */
static const char *plan_run(const papers_t *P, int s, int v, int k, papers_run_t *r,
                            papers_probe_t *probe)
{
    memset(r, 0, sizeof *r);
    memset(probe, 0, sizeof *probe);
    r->compute = k == 1;
    if (s == P->scene_count) {
        r->scene = -1;
        r->variant = -2;
        r->mode = SCENE_MODE_BILLBOARD;
        probe->colliders_wanted = leaf_colliders[P->quick ? 2 * v : v];
        return LEAVES_SCENE;
    }
    r->scene = s;
    r->variant = v;
    r->mode = v < 0 ? P->desc[s].mode : SCENE_MODE_BLADE;
    probe->ablation = v < 0 ? NULL : &perf_ablations[v];
    return P->scene[s];
}

/* Figure r (scene s, variant v, path k; plan_run) from PAPERS_RUNS
 * sessions: the first's counters, the median of each timed field, the
 * frame's spread. Returns 0 or the failed session's code. */
static int papers_figure(const perf_session_desc_t *o, const papers_t *P, int s, int v, int k, papers_run_t *r)
{
    papers_run_t runs[PAPERS_RUNS];
    for (int n = 0; n < PAPERS_RUNS; n++) {
        papers_probe_t probe;
        const char *file = plan_run(P, s, v, k, &runs[n], &probe);
        int rc = papers_session(o, file, &runs[n], P->frames, &probe);
        if (rc) {
            core_log_error("papers: %s failed", file);
            return rc;
        }
    }
    *r = runs[0];
    for (size_t f = 0; f < sizeof papers_timed / sizeof papers_timed[0]; f++) {
        double v3[PAPERS_RUNS];
        for (int n = 0; n < PAPERS_RUNS; n++) v3[n] = *(const double *)((const char *)&runs[n] + papers_timed[f]);
        *(double *)((char *)r + papers_timed[f]) = measure_percentile(v3, PAPERS_RUNS, 0.5);
    }
    double lo = runs[0].frame_ms, hi = lo;
    for (int n = 1; n < PAPERS_RUNS; n++) {
        lo = fmin(lo, runs[n].frame_ms);
        hi = fmax(hi, runs[n].frame_ms);
        r->fell_back = r->fell_back || runs[n].fell_back;
    }
    r->frame_spread = 0.5 * (hi - lo);
    return 0;
}

/* Every figure of the set, in order: per scene its own mode when that is
 * not blade, then the ablations; then the leaves. Interrupted (Ctrl-C):
 * returns 0 with the figures made so far. */
static int papers_measure(const perf_session_desc_t *o, papers_t *P)
{
    int leaf_n = P->quick ? 2 : MAX_LEAF_RUNS;
    P->planned = 2 * leaf_n;
    for (int s = 0; s < P->scene_count; s++)
        P->planned += 2 * (PERF_ABLATION_COUNT + (P->desc[s].mode != SCENE_MODE_BLADE));
    double t0 = plat_time();
    for (int s = 0; s <= P->scene_count; s++) {
        bool leaves = s == P->scene_count;
        int v0 = !leaves && P->desc[s].mode != SCENE_MODE_BLADE ? -1 : 0;
        for (int v = v0; v < (leaves ? leaf_n : PERF_ABLATION_COUNT); v++)
            for (int k = 0; k < 2; k++) {
                if (perf_interrupted(o)) {
                    core_log_warn("papers: interrupted after %d of %d figures; writing those", P->run_count,
                                  P->planned);
                    return 0;
                }
                papers_run_t *r = &P->runs[P->run_count];
                int rc = papers_figure(o, P, s, v, k, r);
                if (rc) return rc;
                P->run_count++;
                fprintf(stderr, "papers: %2d/%d %-12s %-16s %-7s frame %8.3f +- %.3f ms  (%.0f s)\n", P->run_count,
                        P->planned, leaves ? "orthmann" : P->name[s],
                        leaves ? "leaves" : v < 0 ? scene_mode_name(r->mode) : perf_ablations[v].name,
                        r->compute ? "compute" : "hw", r->frame_ms, r->frame_spread, plat_time() - t0);
            }
    }
    return 0;
}

/* ---- output ------------------------------------------------------------------------- */

static const char *path_name(const papers_run_t *r)
{
    return r->fell_back ? "hw (fell back)" : r->compute ? "compute" : "hw";
}

static const char *variant_name(const papers_run_t *r)
{
    return r->variant >= 0 ? perf_ablations[r->variant].name : r->variant == -1 ? "own_mode" : "leaves";
}

static bool write_json(const papers_t *P, const char *dir)
{
    core_buf_t b = {0};
    core_buf_printf(&b, "{\n  \"renderer\": \"%s\",\n  \"frames\": %d,\n  \"runs_per_figure\": %d,\n  \"runs\": [\n",
                    P->renderer, P->frames, PAPERS_RUNS);
    for (int i = 0; i < P->run_count; i++) {
        const papers_run_t *r = &P->runs[i];
        core_buf_printf(&b,
                        "    {\"scene\": \"%s\", \"variant\": \"%s\", \"mode\": \"%s\", \"raster\": \"%s\", "
                        "\"fell_back\": %s, \"colliders\": %d, \"frame_ms\": %.4f, \"frame_ms_spread\": %.4f, "
                        "\"physics_ms\": %.4f, "
                        "\"cull_ms\": %.4f, \"draw_ms\": %.4f, \"cubemaps_ms\": %.4f, \"collide_ms\": %.4f, "
                        "\"recover_ms\": %.4f, \"render_ms\": %.4f, \"blades\": %ld, \"drawn\": %ld, "
                        "\"billboards\": %ld, \"culled\": [%u, %u, %u, %u], \"patch_culled\": %ld, "
                        "\"colliding_leaves\": %.2f, "
                        "\"recovering_leaves\": %.2f}%s\n",
                        r->scene >= 0 ? P->name[r->scene] : "orthmann", variant_name(r), scene_mode_name(r->mode),
                        r->compute ? "compute" : "hw", r->fell_back ? "true" : "false", r->colliders, r->frame_ms,
                        r->frame_spread, r->physics_ms, r->cull_ms, r->draw_ms, r->cubemaps_ms, r->collide_ms,
                        r->recover_ms,
                        r->render_ms, r->blades, r->drawn, r->billboards, r->culled[0], r->culled[1], r->culled[2],
                        r->culled[3], r->patch_culled, r->leaves, r->recovering, i + 1 < P->run_count ? "," : "");
    }
    core_buf_printf(&b, "  ]\n}\n");
    char path[1200];
    snprintf(path, sizeof path, "%s/papers.json", dir);
    bool ok = core_buf_write(&b, path);
    core_buf_free(&b);
    return ok;
}

/* ablation.csv, leaves.csv and papers_leaves.dat. */
static bool write_tables(const papers_t *P, const char *dir)
{
    core_buf_t a = {0}, l = {0}, d = {0};
    core_buf_printf(&a, "scene,variant,raster,frame_ms,physics_ms,cull_ms,draw_ms,blades,drawn,culled_orientation,"
                        "culled_frustum,culled_distance,culled_occlusion,patch_culled,colliders,frame_ms_spread\n");
    core_buf_printf(&l, "colliders,raster,colliding_leaves,recovering_leaves,cubemaps_ms,collide_ms,recover_ms,"
                        "render_ms,frame_ms,billboards,frame_ms_spread\n");
    core_buf_printf(&d, "# colliding_leaves collide_ms recover_ms render_ms cubemaps_ms colliders compute\n");
    for (int i = 0; i < P->run_count; i++) {
        const papers_run_t *r = &P->runs[i];
        if (r->variant >= 0)
            core_buf_printf(&a, "%s,%s,%s,%.4f,%.4f,%.4f,%.4f,%ld,%ld,%u,%u,%u,%u,%ld,%d,%.4f\n", P->name[r->scene],
                            variant_name(r), path_name(r), r->frame_ms, r->physics_ms, r->cull_ms, r->draw_ms,
                            r->blades, r->drawn, r->culled[0], r->culled[1], r->culled[2], r->culled[3],
                            r->patch_culled, r->colliders, r->frame_spread);
        if (r->variant != -2) continue;
        core_buf_printf(&l, "%d,%s,%.2f,%.2f,%.4f,%.4f,%.4f,%.4f,%.4f,%ld,%.4f\n", r->colliders, path_name(r),
                        r->leaves, r->recovering, r->cubemaps_ms, r->collide_ms, r->recover_ms, r->render_ms,
                        r->frame_ms, r->billboards, r->frame_spread);
        core_buf_printf(&d, "%.2f %.4f %.4f %.4f %.4f %d %d\n", r->leaves, r->collide_ms, r->recover_ms,
                        r->render_ms, r->cubemaps_ms, r->colliders, r->compute ? 1 : 0);
    }
    char path[1200];
    bool ok = true;
    const struct {
        core_buf_t *b;
        const char *name;
    } files[] = {{&a, "ablation.csv"}, {&l, "leaves.csv"}, {&d, "papers_leaves.dat"}};
    for (int f = 0; f < 3; f++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[f].name);
        ok = core_buf_write(files[f].b, path) && ok;
        core_buf_free(files[f].b);
    }
    return ok;
}

static void write_chart(const char *dir)
{
    char data[1200], body[8192];
    snprintf(data, sizeof data, "%s/papers_leaves.dat", dir);
    const char *hw = "< awk '$7 == 0' ", *cp = "< awk '$7 == 1' ";
    snprintf(body, sizeof body,
             "set title 'Billboards (Orthmann et al. 2009): cost against colliding leaves'\n"
             "set xlabel 'colliding octree leaves (mean over the timed frames)'\nset ylabel 'GPU ms per frame "
             "(pass median)'\nset grid\nset key below\nset yrange [0:*]\n"
             "plot \"%s%s\" using 1:2 with linespoints lw 2 pt 7 title 'bb.collide', "
             "\"%s%s\" using 1:3 with linespoints lw 2 pt 5 title 'bb.recover', "
             "\"%s%s\" using 1:5 with linespoints lw 2 pt 9 title 'bb.cubemaps', "
             "\"%s%s\" using 1:4 with linespoints lw 2 pt 11 title 'bb.render (hardware path)', "
             "\"%s%s\" using 1:4 with linespoints lw 2 dt 3 pt 13 title 'bb.raster (compute path)'",
             hw, data, hw, data, hw, data, hw, data, cp, data);
    eval_gnuplot_chart(dir, "papers_leaves", body);
}

/* A pass cell: "n/a" for a pass the run did not have. */
static void ms_cell(char out[24], double v)
{
    if (v > 0.0) snprintf(out, 24, "%.3f", v);
    else snprintf(out, 24, "n/a");
}

static void md_ablation(const papers_t *P, core_buf_t *md)
{
    core_buf_printf(md, "### Ablations: blade mode on the papers' scenes\n\n"
                        "Blade mode forced on each scene (Jahrmann & Wimmer 2017). `collision_off`: no colliders "
                        "and no characters (a scene without either reads as `all`); `culling_off`: the "
                        "orientation, frustum, distance and occlusion tests all skipped; `X_off`: that test alone "
                        "skipped. GPU ms: pass medians after warm-up (frame: their sum; draw: blade.draw on the "
                        "hardware path, blade.raster on the compute path), each the median over %d runs (frame: +- "
                        "half their range). Blades drawn and culled by each test: "
                        "the last frame's counters (summary.txt's `blade_culled`); patch: blades of patches culled "
                        "whole before the per-blade tests (the CPU's frustum test, off with the frustum test). "
                        "Drawn plus culled can be fewer than the blades: blades of height 0 (thinned) fall in "
                        "no column.\n\n",
                    PAPERS_RUNS);
    for (int s = 0; s < P->scene_count; s++) {
        core_buf_printf(md, "#### %s (%s)\n\n| variant | path | frame ms | physics ms | cull ms | draw ms | "
                            "colliders | blades drawn | culled orientation | culled frustum | culled distance | "
                            "culled occlusion | patch |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | "
                            "--- | --- | --- |\n",
                        P->name[s], P->scene[s]);
        for (int i = 0; i < P->run_count; i++) {
            const papers_run_t *r = &P->runs[i];
            if (r->scene != s || r->variant < 0) continue;
            char c[3][24];
            ms_cell(c[0], r->physics_ms);
            ms_cell(c[1], r->cull_ms);
            ms_cell(c[2], r->draw_ms);
            core_buf_printf(md,
                            "| %s | %s | %.3f +- %.3f | %s | %s | %s | %d | %ld of %ld | %u | %u | %u | %u | %ld |\n",
                            variant_name(r), path_name(r), r->frame_ms, r->frame_spread, c[0], c[1], c[2],
                            r->colliders, r->drawn,
                            r->blades, r->culled[0], r->culled[1], r->culled[2], r->culled[3], r->patch_culled);
        }
        core_buf_printf(md, "\n");
    }
}

/* images: the folder of the chart as seen from the markdown ("" or "images/"). */
static void md_leaves(const papers_t *P, core_buf_t *md, const char *images)
{
    core_buf_printf(md, "### Billboard cost against colliding leaves (Orthmann et al. 2009)\n\n"
                        "%s in billboard mode with N balls like its own crossing the field on lines spread over "
                        "80 %% of its side. Colliding leaves: octree leaves in the colliding state, mean over the "
                        "timed frames; pass medians after warm-up (render: bb.render on the hardware path, "
                        "bb.raster on the compute path); each figure the median over %d runs (frame: +- half their "
                        "range).\n\n![papers_leaves](%spapers_leaves.png)\n\n"
                        "| balls | path | colliding leaves | recovering leaves | bb.cubemaps ms | bb.collide ms | "
                        "bb.recover ms | render ms | frame ms | billboards |\n"
                        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n",
                    LEAVES_SCENE, PAPERS_RUNS, images);
    for (int i = 0; i < P->run_count; i++) {
        const papers_run_t *r = &P->runs[i];
        if (r->variant != -2) continue;
        char c[4][24];
        ms_cell(c[0], r->cubemaps_ms);
        ms_cell(c[1], r->collide_ms);
        ms_cell(c[2], r->recover_ms);
        ms_cell(c[3], r->render_ms);
        core_buf_printf(md, "| %d | %s | %.1f | %.1f | %s | %s | %s | %s | %.3f +- %.3f | %ld |\n", r->colliders,
                        path_name(r), r->leaves, r->recovering, c[0], c[1], c[2], c[3], r->frame_ms, r->frame_spread,
                        r->billboards);
    }
    core_buf_printf(md, "\n");
}

/* The run of scene s drawn the paper's way: its own mode (own_mode when
 * not blade, else the ablation's `all`) through path `compute`. */
static const papers_run_t *own_run(const papers_t *P, int s, bool compute)
{
    int want = P->desc[s].mode != SCENE_MODE_BLADE ? -1 : 0;
    for (int i = 0; i < P->run_count; i++)
        if (P->runs[i].scene == s && P->runs[i].variant == want && P->runs[i].compute == compute)
            return &P->runs[i];
    return NULL;
}

static void ours_cell(const papers_run_t *r, char *out, size_t size)
{
    if (!r) {
        snprintf(out, size, "not run");
        return;
    }
    bool bb = r->mode == SCENE_MODE_BILLBOARD;
    double sim = bb ? r->cubemaps_ms + r->collide_ms + r->recover_ms : r->physics_ms;
    snprintf(out, size, "frame %.3f ms, simulation %.3f ms%s", r->frame_ms, sim,
             r->fell_back ? " (fell back to hw)" : "");
}

static void md_papers(const papers_t *P, core_buf_t *md)
{
    core_buf_printf(md, "### The papers' scenes: published figures and ours\n\n"
                        "Ours: the scene in its own mode on `%s`, %d frames, the median of %d runs; frame = the "
                        "summed GPU pass medians, simulation = blade.physics (blades) or bb.cubemaps + bb.collide + "
                        "bb.recover "
                        "(billboards). The papers' hardware and figures are quoted from the source named; "
                        "\"%s\": none of the sources at hand states it.%s\n\n"
                        "| scene | paper | paper's hardware | published figure | paper's scene | ours, hardware path "
                        "| ours, compute path | our scene | source |\n"
                        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n",
                    P->renderer, P->frames, PAPERS_RUNS, NOT_HERE,
                    P->run_count < P->planned ? " **Interrupted: only the runs listed below were made.**" : "");
    /* The papers' scenes, then the scenes run that are none of them (--scene). */
    for (int f = 0; f < PAPER_COUNT + P->scene_count; f++) {
        int s = -1;
        if (f >= PAPER_COUNT) {
            s = f - PAPER_COUNT;
            bool paper = false;
            for (int k = 0; k < PAPER_COUNT; k++) paper = paper || strcmp(P->name[s], paper_facts[k].scene) == 0;
            if (paper) continue;
        } else {
            for (int k = 0; k < P->scene_count; k++)
                if (strcmp(P->name[k], paper_facts[f].scene) == 0) s = k;
        }
        static const paper_fact_t none = {NULL, "none (not a paper scene)", "-", "-", "-", "-"};
        const paper_fact_t *p = f < PAPER_COUNT ? &paper_facts[f] : &none;
        char hw[160], cp[160], ours[320] = "not run (--scene)";
        ours_cell(s >= 0 ? own_run(P, s, false) : NULL, hw, sizeof hw);
        ours_cell(s >= 0 ? own_run(P, s, true) : NULL, cp, sizeof cp);
        const papers_run_t *r = s >= 0 ? own_run(P, s, false) : NULL;
        if (r) {
            const scene_desc_t *d = &P->desc[s];
            bool bb = r->mode == SCENE_MODE_BILLBOARD;
            snprintf(ours, sizeof ours, "%s mode, %.0f m field, %ld %s, colliders %d, characters %d, winds %d, "
                                        "%dx%d, %dx MSAA",
                     scene_mode_name(d->mode), (double)d->terrain.size, bb ? r->billboards : r->blades,
                     bb ? "billboards" : "blades", d->collider_count, d->character_count, d->wind_count, r->size[0],
                     r->size[1], r->msaa);
        }
        core_buf_printf(md, "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", s >= 0 ? P->name[s] : p->scene,
                        p->paper, p->hardware, p->figure, p->setup, hw, cp, ours, p->source);
    }
    core_buf_printf(md, "\n");
}

/* ---- entry -------------------------------------------------------------------------- */

/* The paper scenes, or `one` alone. */
static int papers_scenes(const char *one, papers_t *P)
{
    char err[1024];
    for (int f = 0; f < (one ? 1 : PAPER_COUNT); f++) {
        int s = P->scene_count;
        if (one) snprintf(P->scene[s], sizeof P->scene[s], "%s", one);
        else snprintf(P->scene[s], sizeof P->scene[s], "scenes/bench/%s.json", paper_facts[f].scene);
        scene_short(P->scene[s], P->name[s], sizeof P->name[s]);
        if (!scene_load(&P->desc[s], P->scene[s], err, sizeof err)) return 2;
        P->scene_count++;
    }
    return 0;
}

int perf_papers_run(const perf_session_desc_t *o, bool quick, const char *dir, core_buf_t *md)
{
    char err[1024];
    if (!core_fs_mkdirs(dir) || !core_fs_check_writable_dir(dir, err, sizeof err)) {
        core_log_error("--papers: %s", err);
        return 2;
    }
    papers_t *P = calloc(1, sizeof *P);
    scene_desc_t *desc = P ? calloc(MAX_SCENES, sizeof *desc) : NULL;
    if (!desc) {
        free(P);
        return 1;
    }
    P->desc = desc;
    P->quick = quick;
    P->frames = o->frames_set ? o->frames : (quick ? 6 : 120);
    snprintf(P->renderer, sizeof P->renderer, "%s", (const char *)glGetString(GL_RENDERER));
    /* With the report, --scene names the sweep's scene: the set runs the papers'. */
    int rc = papers_scenes(md ? NULL : o->world.scene, P);
    if (rc == 0) rc = papers_measure(o, P);
    if (rc == 0 && !(write_json(P, dir) && write_tables(P, dir))) rc = 1;
    bool leaves = false;
    for (int i = 0; i < P->run_count; i++) leaves = leaves || P->runs[i].variant == -2;
    if (rc == 0 && leaves) write_chart(dir);
    if (rc == 0) {
        for (int k = 0; k < (md ? 2 : 1); k++) {
            core_buf_t section = {0};
            md_papers(P, &section);
            md_ablation(P, &section);
            md_leaves(P, &section, k ? "images/" : "");
            char path[1200];
            snprintf(path, sizeof path, "%s/papers.md", dir);
            if (k) core_buf_printf(md, "%s", section.data);
            else if (!core_buf_write(&section, path)) rc = 1;
            core_buf_free(&section);
        }
        if (rc == 0) core_log_info("papers: wrote %s/papers.md, papers.json, ablation.csv, leaves.csv and the chart", dir);
    }
    free(desc);
    free(P);
    return rc;
}
