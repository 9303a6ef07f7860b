/* test_work_counters: the work counters of summary.txt (draw calls,
 * dispatches, work groups, primitives generated and transform-feedback
 * primitives written per pass, items per pass; gfx_count) for small scenes
 * in billboard, blade and hybrid modes match a committed baseline. They do
 * not depend on timing, so an algorithmic regression (recovery touching
 * every leaf, a dispatch issued twice) fails here even without a GPU.
 *
 * On a mismatch each moved counter is printed with its baseline and new
 * value. When the change is intended, rewrite the baseline with
 *   MEADOW_UPDATE_BASELINE=1 ctest --test-dir build -R test_work_counters
 * and commit tests/data/work_baseline.txt with the change. */
#include "app/app.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BASELINE "tests/data/work_baseline.txt"
#define MAX_VALUES 512
#define TOLERANCE 1e-6 /* relative: the counters are exact, printed to 3 decimals */

typedef struct value_t {
    char key[96];
    double v;
} value_t;

typedef struct config_t {
    const char *name, *scene, *mode;
} config_t;

static const config_t configs[] = {
    {"tiny_billboard", "scenes/tiny.json", "billboard"},
    {"tiny_blade", "scenes/tiny.json", "blade"},
    {"tiny_hybrid", "scenes/tiny.json", "hybrid"},
};

static int add(value_t *vals, int n, const char *config, const char *what, const char *kind, double v)
{
    if (n >= MAX_VALUES) return n;
    snprintf(vals[n].key, sizeof vals[n].key, "%s %s%s%s", config, what, kind[0] ? "." : "", kind);
    vals[n].v = v;
    return n + 1;
}

/* The "work per frame" table and "items per frame" list of a summary. */
static int parse_summary(const char *path, const char *config, value_t *vals, int n)
{
    static const char *const kinds[6] = {"draws", "ranges", "dispatches", "groups", "primitives", "tf_written"};
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    char line[512];
    int section = 0; /* 1: work table, 2: items */
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "work per frame", 14) == 0) {
            section = 1;
            if (!fgets(line, sizeof line, f)) break; /* column header */
            continue;
        }
        if (strncmp(line, "items per frame", 15) == 0) {
            section = 2;
            continue;
        }
        if (strncmp(line, "  ", 2) != 0) {
            section = 0;
            continue;
        }
        char name[64];
        double v[6];
        if (section == 1 && sscanf(line, "%63s %lf %lf %lf %lf %lf %lf", name, &v[0], &v[1], &v[2], &v[3], &v[4],
                                   &v[5]) == 7)
            for (int k = 0; k < 6; k++) n = add(vals, n, config, name, kinds[k], v[k]);
        else if (section == 2 && sscanf(line, "%63s %lf", name, &v[0]) == 2)
            n = add(vals, n, config, name, "", v[0]);
    }
    fclose(f);
    return n;
}

static int run_config(const config_t *c, value_t *vals, int n)
{
    char out[512], summary[600];
    snprintf(out, sizeof out, "%s/%s", test_out_dir(), c->name);
    char *argv[] = {"meadow", "--headless", "--quiet", "--scene", (char *)c->scene, "--mode", (char *)c->mode,
                    "--frames", "40", "--size", "160x90", "--screenshot-every", "0", "--out", out,
                    "--raster", "hw"}; /* the baseline counts the hardware path (auto measures both) */
    app_options_t o;
    char err[256];
    if (app_parse_args((int)(sizeof argv / sizeof argv[0]), argv, &o, err, sizeof err) != 0) return -1;
    int rc = app_run(&o, NULL);
    if (rc == 1) TEST_SKIP("no GL context");
    if (rc != 0) return -1;
    snprintf(summary, sizeof summary, "%s/summary.txt", out);
    return parse_summary(summary, c->name, vals, n);
}

static int load_baseline(value_t *vals)
{
    FILE *f = fopen(BASELINE, "r");
    if (!f) return -1;
    char line[256];
    int n = 0;
    while (fgets(line, sizeof line, f) && n < MAX_VALUES) {
        char config[48], what[48];
        double v;
        if (line[0] == '#' || sscanf(line, "%47s %47s %lf", config, what, &v) != 3) continue;
        snprintf(vals[n].key, sizeof vals[n].key, "%s %s", config, what);
        vals[n++].v = v;
    }
    fclose(f);
    return n;
}

static bool write_baseline(const value_t *vals, int n)
{
    FILE *f = fopen(BASELINE, "w");
    if (!f) return false;
    fprintf(f, "# Work counters per frame (tests/test_work_counters.c): scene_mode counter value.\n"
               "# Rewritten by MEADOW_UPDATE_BASELINE=1 ctest --test-dir build -R test_work_counters\n");
    for (int i = 0; i < n; i++) fprintf(f, "%s %.3f\n", vals[i].key, vals[i].v);
    return fclose(f) == 0;
}

static const value_t *find(const value_t *vals, int n, const char *key)
{
    for (int i = 0; i < n; i++)
        if (strcmp(vals[i].key, key) == 0) return &vals[i];
    return NULL;
}

int main(void)
{
    static value_t now[MAX_VALUES], base[MAX_VALUES];
    int n = 0;
    for (size_t c = 0; c < sizeof configs / sizeof configs[0]; c++) {
        n = run_config(&configs[c], now, n);
        CHECK(n > 0);
        if (n <= 0) TEST_END();
    }
    CHECK(n < MAX_VALUES);
    const char *update = getenv("MEADOW_UPDATE_BASELINE");
    if (update && strcmp(update, "1") == 0) {
        CHECK(write_baseline(now, n));
        printf("wrote %s (%d counters)\n", BASELINE, n);
        TEST_END();
    }
    int nb = load_baseline(base);
    CHECK(nb > 0);
    int moved = 0;
    for (int i = 0; i < nb; i++) {
        const value_t *v = find(now, n, base[i].key);
        double b = base[i].v;
        if (!v) {
            fprintf(stderr, "work counter gone: %s (baseline %.3f)\n", base[i].key, b);
            moved++;
        } else if (fabs(v->v - b) > TOLERANCE * fmax(1.0, fabs(b))) {
            fprintf(stderr, "work counter moved: %s: baseline %.3f, now %.3f (%+.3f, %+.1f%%)\n", base[i].key, b, v->v,
                   v->v - b, b != 0.0 ? 100.0 * (v->v - b) / b : 100.0);
            moved++;
        }
    }
    for (int i = 0; i < n; i++) {
        if (find(base, nb, now[i].key)) continue;
        fprintf(stderr, "work counter new: %s = %.3f (not in the baseline)\n", now[i].key, now[i].v);
        moved++;
    }
    if (moved)
        fprintf(stderr, "%d work counter(s) differ from %s. If the change is intended, rewrite it with\n"
               "  MEADOW_UPDATE_BASELINE=1 ctest --test-dir build -R test_work_counters\n"
               "and commit it with the change.\n",
               moved, BASELINE);
    CHECK(moved == 0);
    TEST_END();
}
