/* app_bench: `meadow bench` sweeps configurations of deterministic scenes
 * headless (fixed seed, dt, camera and colliders), and writes per-pass GPU
 * times, CPU time, accuracy metrics and image error against the reference
 * rendering to bench.csv and bench.json, plus a speed-vs-accuracy chart per
 * sweep (PNG and SVG, gnuplot) with the Pareto front marked. --quick runs a
 * small sweep for CI. */
#include "app/app_world.h"

#include <stdio.h>
#include <string.h>

#include "eval/eval.h"
#include "platform/plat.h"

typedef struct bench_config_t {
    const char *group; /* one chart per group */
    char label[48];
    scene_mode_t mode;
    int cube_resolution, subdiv, springs; /* billboard knobs, 0 = scene */
    float switch_distance;                /* hybrid knob, 0 = scene */
    app_tuning_t tuning;
} bench_config_t;

static void tweak(scene_desc_t *s, void *user)
{
    const bench_config_t *c = user;
    if (c->cube_resolution) s->grass.cube_resolution = c->cube_resolution;
    if (c->subdiv) s->grass.subdiv[0] = s->grass.subdiv[1] = c->subdiv;
    if (c->springs) s->grass.spring_iterations = c->springs;
    if (c->switch_distance > 0) s->grass.switch_distance = c->switch_distance;
}

#define MAX_CONFIGS 96

static int build_configs(bench_config_t *c, bool quick)
{
    int n = 0;
    static const int cubes_full[] = {16, 32, 64}, subdivs_full[] = {2, 4, 6}, springs_full[] = {1, 2, 4};
    static const int cubes_quick[] = {16}, subdivs_quick[] = {2, 4}, springs_quick[] = {2};
    const int *cubes = quick ? cubes_quick : cubes_full, *subdivs = quick ? subdivs_quick : subdivs_full;
    const int *springs = quick ? springs_quick : springs_full;
    int nc = quick ? 1 : 3, ns = quick ? 2 : 3, nk = quick ? 1 : 3;
    for (int a = 0; a < nc; a++)
        for (int b = 0; b < ns; b++)
            for (int k = 0; k < nk; k++) {
                bench_config_t *x = &c[n++];
                *x = (bench_config_t){.group = "billboard_collision", .mode = SCENE_MODE_BILLBOARD,
                                      .cube_resolution = cubes[a], .subdiv = subdivs[b], .springs = springs[k]};
                snprintf(x->label, sizeof x->label, "cube%d_sub%d_k%d", cubes[a], subdivs[b], springs[k]);
            }
    static const int tess_full[] = {1, 2, 3, 5, 7, 10}, levels_full[] = {1, 2, 4, 8, 16, 32};
    int nt = quick ? 2 : 6;
    for (int i = 0; i < nt; i++) {
        bench_config_t *x = &c[n++];
        *x = (bench_config_t){.group = "blade_tessellation", .mode = SCENE_MODE_BLADE,
                              .tuning = {.tess_max = tess_full[i]}};
        snprintf(x->label, sizeof x->label, "tess%d", tess_full[i]);
    }
    for (int i = 0; i < nt; i++) {
        bench_config_t *x = &c[n++];
        *x = (bench_config_t){.group = "blade_distance_levels", .mode = SCENE_MODE_BLADE,
                              .tuning = {.distance_levels = levels_full[i]}};
        snprintf(x->label, sizeof x->label, "levels%d", levels_full[i]);
    }
    static const float sw_full[] = {2, 4, 8, 12, 20, 40};
    for (int i = 0; i < nt; i++) {
        bench_config_t *x = &c[n++];
        *x = (bench_config_t){.group = "hybrid_switch_distance", .mode = SCENE_MODE_HYBRID,
                              .switch_distance = sw_full[i]};
        snprintf(x->label, sizeof x->label, "switch%gm", sw_full[i]);
    }
    static const scene_mode_t modes[3] = {SCENE_MODE_BILLBOARD, SCENE_MODE_BLADE, SCENE_MODE_HYBRID};
    for (int i = 0; i < 3; i++) {
        bench_config_t *x = &c[n++];
        *x = (bench_config_t){.group = "modes", .mode = modes[i]};
        snprintf(x->label, sizeof x->label, "%s", scene_mode_name(modes[i]));
    }
    return n;
}

static void write_chart(const char *out, const char *group, const char *ylabel, int ycol)
{
    char path[1200], data[1200];
    snprintf(data, sizeof data, "%s/bench_%s.dat", out, group);
    eval_text_t g = {0};
    for (int term = 0; term < 2; term++) {
        eval_text_printf(&g, term ? "set terminal svg size 800,500\nset output '%s/bench_%s.svg'\n"
                                  : "set terminal pngcairo size 800,500\nset output '%s/bench_%s.png'\n",
                         out, group);
        eval_text_printf(&g,
                         "set title '%s: speed vs accuracy'\nset xlabel 'GPU ms per frame'\nset ylabel '%s'\n"
                         "set grid\nset key top right\n"
                         "plot '%s' using 1:2 with points pt 7 ps 1.2 title 'configurations', "
                         "'' using 1:2:3 with labels offset 0,1 font ',8' notitle, "
                         "'< grep \" 1$\" %s | sort -g' using 1:2 with linespoints lw 2 pt 6 ps 2 title 'Pareto front'\n",
                         group, ylabel, data, data);
    }
    (void)ycol;
    snprintf(path, sizeof path, "%s/bench_%s.gp", out, group);
    if (eval_text_write(&g, path)) eval_gnuplot(path);
    eval_text_free(&g);
}

int app_bench(const app_options_t *o)
{
    char out[1024], err[1024], path[1200];
    snprintf(out, sizeof out, "%s", o->out ? o->out : "out/bench");
    if (!core_fs_check_writable_dir(out, err, sizeof err)) {
        core_log_error("--out: %s", err);
        return 2;
    }
    if (!plat_init(&(plat_desc_t){.backend = PLAT_BACKEND_EGL}, err, sizeof err)) {
        core_log_error("no OpenGL 4.5 context: %s", err);
        return 1;
    }
    gfx_init();
    bench_config_t *cfg = calloc(MAX_CONFIGS, sizeof *cfg);
    app_metrics_t *met = calloc(MAX_CONFIGS, sizeof *met);
    double *err_img = calloc(MAX_CONFIGS, sizeof(double));
    int n = build_configs(cfg, o->quick);
    int frames = o->frames_set ? o->frames : (o->quick ? 8 : 120);
    core_image_t ref = {0}, img = {0};
    app_session_desc_t rd = {.opts = o, .mode = SCENE_MODE_BLADE, .mode_set = true, .frames = frames,
                             .reference = true, .msaa = 8};
    core_log_info("bench: reference rendering (%d frames)", frames);
    int rc = app_session_run(&rd, &ref, NULL);
    double t0 = plat_time();
    for (int i = 0; i < n && rc == 0; i++) {
        app_session_desc_t d = {.opts = o, .mode = cfg[i].mode, .mode_set = true, .frames = frames,
                                .tweak = tweak, .user = &cfg[i], .tuning = cfg[i].tuning};
        rc = app_session_run(&d, &img, &met[i]);
        if (rc) break;
        err_img[i] = 1.0 - eval_image_ssim(&img, &ref);
        core_image_free(&img);
        double el = plat_time() - t0;
        fprintf(stderr, "\rbench: %d/%d %-22s %-26s %8.3f ms  1-SSIM %.4f  (eta %.0f s)   ", i + 1, n,
                cfg[i].group, cfg[i].label, met[i].frame_ms, err_img[i], el / (i + 1) * (n - i - 1));
    }
    fputc('\n', stderr);
    if (rc == 0) {
        eval_text_t csv = {0}, json = {0};
        eval_text_printf(&csv, "group,label,mode,gpu_ms,cpu_ms,image_error,penetration_fraction,penetration_max,"
                               "blade_length_error,spring_error,passes\n");
        eval_text_printf(&json, "{\n  \"renderer\": \"%s\",\n  \"frames\": %d,\n  \"configs\": [\n",
                         (const char *)glGetString(GL_RENDERER), frames);
        for (int i = 0; i < n; i++) {
            const app_metrics_t *m = &met[i];
            eval_text_printf(&csv, "%s,%s,%s,%.4f,%.3f,%.6f,%.6f,%.6f,%.6f,%.6f,", cfg[i].group, cfg[i].label,
                             scene_mode_name(cfg[i].mode), m->frame_ms, m->cpu_ms, err_img[i],
                             m->penetration_fraction, m->penetration_max, m->blade_length_error, m->spring_error);
            eval_text_printf(&json,
                             "    { \"group\": \"%s\", \"label\": \"%s\", \"mode\": \"%s\", \"gpu_ms\": %.4f, "
                             "\"cpu_ms\": %.3f, \"image_error\": %.6f, \"penetration_fraction\": %.6f, "
                             "\"penetration_max\": %.6f, \"blade_length_error\": %.6f, \"spring_error\": %.6f, "
                             "\"passes\": {",
                             cfg[i].group, cfg[i].label, scene_mode_name(cfg[i].mode), m->frame_ms, m->cpu_ms,
                             err_img[i], m->penetration_fraction, m->penetration_max, m->blade_length_error,
                             m->spring_error);
            for (int p = 0; p < m->pass_count; p++) {
                eval_text_printf(&csv, "%s%s=%.4f", p ? ";" : "", m->pass_name[p], m->pass_ms[p]);
                eval_text_printf(&json, "%s\"%s\": %.4f", p ? ", " : "", m->pass_name[p], m->pass_ms[p]);
            }
            eval_text_printf(&csv, "\n");
            eval_text_printf(&json, "} }%s\n", i + 1 < n ? "," : "");
        }
        eval_text_printf(&json, "  ]\n}\n");
        snprintf(path, sizeof path, "%s/bench.csv", out);
        if (!eval_text_write(&csv, path)) rc = 1;
        snprintf(path, sizeof path, "%s/bench.json", out);
        if (!eval_text_write(&json, path)) rc = 1;
        eval_text_free(&csv);
        eval_text_free(&json);
        /* One data file and chart per group: x GPU ms, y image error. */
        for (int i = 0; i < n && rc == 0; i++) {
            if (i > 0 && strcmp(cfg[i].group, cfg[i - 1].group) == 0) continue;
            int j = i;
            double xs[MAX_CONFIGS], ys[MAX_CONFIGS];
            bool front[MAX_CONFIGS];
            while (j < n && strcmp(cfg[j].group, cfg[i].group) == 0) {
                xs[j - i] = met[j].frame_ms;
                ys[j - i] = err_img[j];
                j++;
            }
            eval_pareto(xs, ys, j - i, front);
            eval_text_t dat = {0};
            eval_text_printf(&dat, "# gpu_ms image_error label pareto\n");
            for (int k = i; k < j; k++)
                eval_text_printf(&dat, "%.5f %.6f %s %d\n", xs[k - i], ys[k - i], cfg[k].label, front[k - i]);
            snprintf(path, sizeof path, "%s/bench_%s.dat", out, cfg[i].group);
            if (!eval_text_write(&dat, path)) rc = 1;
            eval_text_free(&dat);
            write_chart(out, cfg[i].group, "image error (1 - SSIM vs reference)", 2);
        }
        if (rc == 0) core_log_info("bench: wrote %s/bench.csv, bench.json and charts (%d configurations)", out, n);
    }
    core_image_free(&ref);
    free(cfg);
    free(met);
    free(err_img);
    gfx_shutdown(true);
    int gl_errors = plat_gl_error_count();
    plat_shutdown();
    if (gl_errors) {
        core_log_error("%d GL error(s) during bench", gl_errors);
        return 1;
    }
    return rc;
}
