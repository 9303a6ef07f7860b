/* blade_clump: the billboards' grass-clump layers baked from the blade
 * model (see blade_clump.h): blades settled by eq. 3-13, shaped by eq. 21,
 * rasterised on the CPU with a coverage calibration. The billboards
 * (bb_layout) only receive the images. */
#include "blade/blade_clump.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "blade/blade_ref.h"

static float clump_clamp01(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

static uint8_t clump_byte(float x) { return (uint8_t)lrintf(clump_clamp01(x) * 255.0f); }

static bool clump_zero3(const float v[3]) { return v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f; }

blade_clump_desc_t blade_clump_desc_defaults(const blade_clump_desc_t *desc)
{
    blade_clump_desc_t c = desc ? *desc : (blade_clump_desc_t){0};
    c.population = blade_population_defaults(&c.population);
    if (c.size[0] <= 0.0f) c.size[0] = BLADE_CLUMP_DEFAULT_WIDTH;
    if (c.size[1] <= 0.0f) c.size[1] = BLADE_CLUMP_DEFAULT_HEIGHT;
    static const float sun[3] = BLADE_CLUMP_SUN;
    if (clump_zero3(c.sun)) memcpy(c.sun, sun, sizeof sun);
    if (c.wind_dir[0] == 0.0f && c.wind_dir[1] == 0.0f) c.wind_dir[0] = 1.0f;
    if (c.depth <= 0.0f) c.depth = 1.5707963f / (c.size[0] * BLADE_CLUMP_DEFAULT_CARD_DENSITY);
    assert(c.population.shape >= BLADE_SHAPE_QUADRATIC && c.population.shape <= BLADE_SHAPE_DANDELION);
    assert(c.population.height[0] <= c.population.height[1] && c.population.width[0] <= c.population.width[1] &&
           c.population.stiffness[0] <= c.population.stiffness[1]);
    return c;
}

/* ---- the bake ----------------------------------------------------------------
 * Layer frame: x across the billboard (its `right`, the viewer's right), y
 * up (its growth direction), z horizontal towards the viewer; roots on
 * y = 0. Each blade is a blade_t of the blade model with root (x, 0, z),
 * z in [-depth, 0], and up +y, rasterised as the blade path draws it:
 * BLADE_CLUMP_SEGMENTS quads along v, each vertex from blade_ref_surface
 * (eq. 21 with the scene's width profile).
 *
 * Views (bb_view.h; beyond the paper): the blades settle once under
 * gravity and the scene's mean wind (blade_wind_wave's mean, half its
 * strength) blowing along -z; view (theta, phi) turns every blade about
 * its root by phi (the physics is invariant under the turn, so this is the
 * blade settled under a wind at azimuth phi) and projects it obliquely
 * along the view direction d = (0, sin theta, cos theta) onto the card
 * plane z = 0: image height y + (-z) tan theta, depth p . d. The slab is
 * as deep as the mean free path between cards (blade_clump_desc_t.depth), so
 * from above a card shows the blades up to the next card behind it. A
 * grid of BLADE_CLUMP_SS x BLADE_CLUMP_SS samples per texel with a depth test
 * (nearest wins); a texel's alpha is its covered fraction, its colour the
 * mean albedo mix(root, tip, v) of its covered samples (straight alpha),
 * and a second image their mean lit colour as blade_shade lights them
 * before fog: shade() (lighting.glsl) of the sample's albedo, its unit
 * normal turned towards d as blade_shade turns it towards the viewer,
 * ambient occlusion mix(0.45, 1, v), and the sun in the view's frame (the
 * scene's sun and wind fix it for each azimuth), linear, so the mip
 * levels average it as the pixels would (a square root kept more of the
 * dark colours' bits but darkened the minified cards: the mean of a root
 * squared is below the mean). A plain card shows that colour times its
 * tint, fogged.
 *
 * Coverage, calibrated (per view): a ray through the blade field meets
 * blade surface at the rate the layer's `blades` blades (bb_clump_blades:
 * per billboard as many as the field grows, times pi / 2) give counted
 * with their overlaps, a mean overlap count T per sample; through the
 * billboards it meets cards, each hit letting 1 - alpha through, and
 * random hits make the transmittance exp(-rate x mean alpha) (Campbell's
 * theorem). The blades of one layer overlap each other, so its mean alpha
 * (their union) falls short of T, and the cards let more ground through
 * than the blades they stand for. So the layer takes more blades, from the
 * same stream, until its mean alpha reaches the mean over sample rows of
 * min(T_row, 1) (a row already covered cannot be more opaque), at most
 * 4 x `blades` and BLADE_CLUMP_MAX_BLADES (blade_clump_stats_t says how many). */

static float clump_range(core_rng_t *rng, const float r[2]) { return core_rng_range(rng, r[0], r[1]); }

/* One blade of a layer, settled with its root at the origin; *x: its
 * draw for the root's place across the layer (clump_place), *z: its
 * root's depth, in [-depth, 0] (front, views off: over the layer width,
 * as the front-only bake placed them). */
static void clump_blade(blade_t *b, core_rng_t *rng, const blade_clump_desc_t *c, const blade_env_t *env, bool front,
                        float *x, float *z)
{
    const blade_population_t *pop = &c->population;
    float h = clump_range(rng, pop->height), w = clump_range(rng, pop->width), s = clump_range(rng, pop->stiffness);
    float angle = core_rng_range(rng, 0.0f, 6.2831853f);
    *x = core_rng_float(rng);
    float u = core_rng_float(rng);
    *z = front ? (u - 0.5f) * c->size[0] : -u * c->depth;
    *b = (blade_t){.v0 = {0.0f, 0.0f, 0.0f, angle}, .v1 = {0.0f, h, 0.0f, h}, .v2 = {0.0f, h, 0.0f, w},
                   .up = {0.0f, 1.0f, 0.0f, s}};
    float eta = 0.0f;
    for (int i = 0; i < BLADE_CLUMP_SETTLE_STEPS; i++) blade_ref_step_one(b, &eta, env, NULL);
}

/* Settled blade b (root at the origin) turned about its root by phi (the
 * wind's -z goes to (sin phi, 0, -cos phi)) and placed: root depth z, root
 * across at draw x of the range that keeps the turned blade's projection
 * `margin` metres off the layer's sides (no blade is cut). */
static blade_t clump_place(const blade_t *b, const blade_clump_desc_t *c, float phi, float x, float z, float margin)
{
    blade_t t = *b;
    if (phi != 0.0f) {
        float cs = cosf(phi), sn = sinf(phi);
        float *pts[2] = {t.v1, t.v2};
        for (int k = 0; k < 2; k++) {
            float dx = pts[k][0], dz = pts[k][2];
            pts[k][0] = dx * cs - dz * sn;
            pts[k][2] = dx * sn + dz * cs;
        }
        t.v0[3] = b->v0[3] + phi;
    }
    float lo = 0.0f, hi = 0.0f;
    for (int i = 0; i <= BLADE_CLUMP_SEGMENTS; i++)
        for (int e = 0; e < 2; e++) {
            float p[3], n[3];
            blade_ref_surface(&t, c->population.shape, (float)e, (float)i / BLADE_CLUMP_SEGMENTS, p, n);
            lo = fminf(lo, p[0]);
            hi = fmaxf(hi, p[0]);
        }
    float half = 0.5f * c->size[0] - margin, x0 = -half - lo, x1 = half - hi;
    float root = x1 > x0 ? x0 + x * (x1 - x0) : 0.5f * (x0 + x1);
    float shift[3] = {root, 0.0f, z};
    for (int k = 0; k < 3; k++) {
        t.v0[k] += shift[k];
        t.v1[k] += shift[k];
        t.v2[k] += shift[k];
    }
    return t;
}

/* shade() of shaders/common/lighting.glsl (its twin: keep the constants
 * alike): Lambert sun and hemispheric sky ambient of albedo at unit normal
 * n under the unit sun direction, ambient occlusion ao. */
static void clump_shade(const float albedo[3], const float n[3], const float sun[3], float ao, float out[3])
{
    static const float sun_color[3] = {1.0f, 0.95f, 0.85f}, down[3] = {0.18f, 0.17f, 0.14f},
                       up[3] = {0.35f, 0.42f, 0.55f};
    float ndl = fmaxf(n[0] * sun[0] + n[1] * sun[1] + n[2] * sun[2], 0.0f), t = n[1] * 0.5f + 0.5f;
    for (int k = 0; k < 3; k++)
        out[k] = albedo[k] * (sun_color[k] * ndl * 0.85f + (down[k] + (up[k] - down[k]) * t) * ao);
}

/* Sample buffer of one view: nearest depth, the blade parameter v and the
 * normal (attributes 1-4 of the triangles). */
#define BLADE_CLUMP_ATTRS 5 /* depth, v, normal xyz */
typedef struct clump_samples_t {
    int w, h; /* samples */
    float *z, *v, *n;
    uint16_t *hits; /* surfaces over each sample, overlaps counted; NULL: not counted */
    long covered;   /* samples some surface covers */
} clump_samples_t;

/* Rasterises the triangle (a, b, c) of sample-space x, y and the
 * BLADE_CLUMP_ATTRS attributes (depth z, blade parameter v, normal), either
 * winding: per sample row, the span of sample centres inside it (where the
 * row's centre line crosses its edges); attributes from the triangle's
 * plane; a sample takes them when nearer than what it holds. */
static void clump_triangle(clump_samples_t *sb, const float *a, const float *b, const float *c)
{
    float area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (fabsf(area) < 1e-6f) return;
    /* Attribute k at (x, y): at[k] + dx[k] (x - a.x) + dy[k] (y - a.y). */
    float dx[BLADE_CLUMP_ATTRS], dy[BLADE_CLUMP_ATTRS];
    for (int k = 0; k < BLADE_CLUMP_ATTRS; k++) {
        float fb = b[2 + k] - a[2 + k], fc = c[2 + k] - a[2 + k];
        dx[k] = (fb * (c[1] - a[1]) - fc * (b[1] - a[1])) / area;
        dy[k] = (fc * (b[0] - a[0]) - fb * (c[0] - a[0])) / area;
    }
    const float *v[3] = {a, b, c};
    float ylo = fminf(a[1], fminf(b[1], c[1])), yhi = fmaxf(a[1], fmaxf(b[1], c[1]));
    int y0 = (int)ceilf(ylo - 0.5f), y1 = (int)floorf(yhi - 0.5f);
    y0 = y0 < 0 ? 0 : y0;
    y1 = y1 > sb->h - 1 ? sb->h - 1 : y1;
    for (int y = y0; y <= y1; y++) {
        float py = (float)y + 0.5f, xlo = INFINITY, xhi = -INFINITY;
        for (int e = 0; e < 3; e++) {
            const float *p = v[e], *q = v[(e + 1) % 3];
            if ((p[1] > py) == (q[1] > py)) continue;
            float x = p[0] + (py - p[1]) * (q[0] - p[0]) / (q[1] - p[1]);
            xlo = fminf(xlo, x);
            xhi = fmaxf(xhi, x);
        }
        int x0 = (int)ceilf(xlo - 0.5f), x1 = (int)floorf(xhi - 0.5f);
        x0 = x0 < 0 ? 0 : x0;
        x1 = x1 > sb->w - 1 ? sb->w - 1 : x1;
        size_t row = (size_t)y * (size_t)sb->w;
        float ry = py - a[1];
        for (int x = x0; x <= x1; x++) {
            float rx = (float)x + 0.5f - a[0];
            float z = a[2] + dx[0] * rx + dy[0] * ry;
            if (sb->hits) {
                uint16_t *hit = sb->hits + row + (size_t)x;
                *hit = *hit < UINT16_MAX ? (uint16_t)(*hit + 1) : *hit;
            }
            sb->covered += sb->z[row + (size_t)x] == -INFINITY;
            if (z <= sb->z[row + (size_t)x]) continue;
            sb->z[row + (size_t)x] = z;
            sb->v[row + (size_t)x] = fminf(fmaxf(a[3] + dx[1] * rx + dy[1] * ry, 0.0f), 1.0f);
            for (int k = 0; k < 3; k++)
                sb->n[(row + (size_t)x) * 3 + (size_t)k] = a[4 + k] + dx[2 + k] * rx + dy[2 + k] * ry;
        }
    }
}

/* The oblique projection of view elevation theta: image height and depth
 * of layer point p (see the banner). */
typedef struct clump_proj_t {
    float tan_t, sin_t, cos_t;
} clump_proj_t;

static float clump_proj_y(const clump_proj_t *pr, const float p[3]) { return p[1] - p[2] * pr->tan_t; }

/* One blade into the sample buffer (sx, sy: samples per metre). */
static void clump_raster(clump_samples_t *sb, const blade_t *b, const blade_clump_desc_t *c, const clump_proj_t *pr,
                         float sx, float sy)
{
    float q[BLADE_CLUMP_SEGMENTS + 1][2][2 + BLADE_CLUMP_ATTRS];
    for (int i = 0; i <= BLADE_CLUMP_SEGMENTS; i++) {
        float v = (float)i / BLADE_CLUMP_SEGMENTS;
        for (int u = 0; u < 2; u++) {
            float p[3], nrm[3];
            blade_ref_surface(b, c->population.shape, (float)u, v, p, nrm);
            q[i][u][0] = (p[0] + 0.5f * c->size[0]) * sx;
            q[i][u][1] = (float)sb->h - clump_proj_y(pr, p) * sy;
            q[i][u][2] = p[1] * pr->sin_t + p[2] * pr->cos_t;
            q[i][u][3] = v;
            for (int k = 0; k < 3; k++) q[i][u][4 + k] = nrm[k];
        }
    }
    for (int i = 0; i < BLADE_CLUMP_SEGMENTS; i++) {
        clump_triangle(sb, q[i][0], q[i][1], q[i + 1][0]);
        clump_triangle(sb, q[i][1], q[i + 1][1], q[i + 1][0]);
    }
}

/* View (theta, phi) of one layer's settled blades b[0..pool) into img
 * (albedo, alpha) and light (the lit colour under sun, a unit direction in
 * the view's frame), placed by place[2n], place[2n + 1] (clump_blade's
 * x and z) and margin, sy samples per metre up, calibrated as the banner
 * says; *stats: its blades, mean alpha and target. sb: the sample buffer
 * (its arrays allocated), turned: room for pool blades. False when out of
 * memory. */
static bool clump_view(core_image_t *img, core_image_t *light, clump_samples_t *sb, const blade_t *b,
                       const float *place, blade_t *turned, int pool, int blades, int layer,
                       const blade_clump_desc_t *c, float theta, float phi, float sy, float margin, const float sun[3],
                       blade_clump_stats_t *stats)
{
    int w = img->w, h = img->h;
    size_t ns = (size_t)sb->w * (size_t)sb->h;
    for (size_t i = 0; i < ns; i++) sb->z[i] = -INFINITY;
    memset(sb->hits, 0, ns * sizeof *sb->hits);
    sb->covered = 0;
    clump_proj_t pr = {tanf(theta), sinf(theta), cosf(theta)};
    for (int n = 0; n < pool; n++) turned[n] = clump_place(&b[n], c, phi, place[2 * n], place[2 * n + 1], margin);
    float sx = (float)sb->w / c->size[0];
    uint16_t *hits = sb->hits;
    for (int n = 0; n < blades; n++) clump_raster(sb, &turned[n], c, &pr, sx, sy);
    /* Target coverage: the mean over sample rows of min(T_row, 1). */
    double target = 0.0;
    for (int y = 0; y < sb->h; y++) {
        long row = 0;
        for (int x = 0; x < sb->w; x++) row += hits[(size_t)y * (size_t)sb->w + (size_t)x];
        target += fmin((double)row / sb->w, 1.0) / sb->h;
    }
    sb->hits = NULL;
    int n = blades;
    for (; (double)sb->covered / (double)ns < target && n < pool; n++) clump_raster(sb, &turned[n], c, &pr, sx, sy);
    sb->hits = hits;
    *stats = (blade_clump_stats_t){
        .blades = n, .alpha = (float)((double)sb->covered / (double)ns), .target = (float)target};
    if (stats->alpha < target)
        core_log_warn("billboards: clump layer %d covers %.3f of its samples with %d blades (4 x %d, at most "
                      "BLADE_CLUMP_MAX_BLADES = %d), short of the %.3f its field's blades cover",
                      layer, stats->alpha, n, blades, BLADE_CLUMP_MAX_BLADES, target);
    /* Resolve: coverage, mean albedo and mean lit colour per texel;
     * transparent texels take the view's means. */
    const float *ra = c->population.albedo_root, *ta = c->population.albedo_tip;
    float d[3] = {0.0f, pr.sin_t, pr.cos_t};
    double mean[6] = {0}, wsum = 0.0;
    float *acc = malloc(sizeof(float) * 7 * (size_t)w * (size_t)h);
    if (!acc) return false;
    for (int ty = 0; ty < h; ty++)
        for (int tx = 0; tx < w; tx++) {
            float sum[6] = {0};
            int covered = 0;
            for (int sy0 = 0; sy0 < BLADE_CLUMP_SS; sy0++) {
                size_t row = (size_t)(ty * BLADE_CLUMP_SS + sy0) * (size_t)sb->w + (size_t)(tx * BLADE_CLUMP_SS);
                for (int sx0 = 0; sx0 < BLADE_CLUMP_SS; sx0++) {
                    size_t s = row + (size_t)sx0;
                    if (sb->z[s] == -INFINITY) continue;
                    covered++;
                    float v = sb->v[s], *sn = sb->n + s * 3;
                    float len = sqrtf(sn[0] * sn[0] + sn[1] * sn[1] + sn[2] * sn[2]), un[3], albedo[3], lit[3];
                    for (int k = 0; k < 3; k++) un[k] = len > 0.0f ? sn[k] / len : d[k];
                    if (un[0] * d[0] + un[1] * d[1] + un[2] * d[2] < 0.0f)
                        for (int k = 0; k < 3; k++) un[k] = -un[k];
                    for (int k = 0; k < 3; k++) albedo[k] = ra[k] + (ta[k] - ra[k]) * v;
                    clump_shade(albedo, un, sun, 0.45f + 0.55f * v, lit);
                    for (int k = 0; k < 3; k++) {
                        sum[k] += albedo[k];
                        sum[3 + k] += lit[k];
                    }
                }
            }
            float *o = acc + ((size_t)ty * (size_t)w + (size_t)tx) * 7;
            o[6] = (float)covered / (float)(BLADE_CLUMP_SS * BLADE_CLUMP_SS);
            for (int k = 0; k < 6; k++) {
                o[k] = covered ? sum[k] / (float)covered : 0.0f;
                mean[k] += sum[k];
            }
            wsum += covered;
        }
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
        const float *o = acc + i * 7;
        float m[6];
        for (int k = 0; k < 6; k++) m[k] = o[6] > 0.0f ? o[k] : (wsum > 0.0 ? (float)(mean[k] / wsum) : 0.0f);
        for (int k = 0; k < 3; k++) {
            img->px[i * 4 + k] = clump_byte(m[k]);
            light->px[i * 4 + k] = clump_byte(m[3 + k]);
        }
        img->px[i * 4 + 3] = clump_byte(o[6]);
        light->px[i * 4 + 3] = 255;
    }
    free(acc);
    return true;
}

bool blade_clump_bake(const blade_clump_desc_t *desc, const blade_clump_bake_t *bake)
{
    blade_clump_desc_t d = blade_clump_desc_defaults(desc);
    const blade_clump_desc_t *c = &d;
    int w = bake->albedo[0].w, blades = bake->blades, layer = bake->layer;
    clump_samples_t sb = {.w = w * BLADE_CLUMP_SS, .h = bake->albedo[0].h * BLADE_CLUMP_SS};
    size_t ns = (size_t)sb.w * (size_t)sb.h;
    sb.z = malloc(sizeof(float) * ns);
    sb.v = malloc(sizeof(float) * ns);
    sb.n = malloc(sizeof(float) * 3 * ns);
    sb.hits = malloc(ns * sizeof *sb.hits);
    /* The calibration's blades come from the same stream: all are settled
     * first, so each view's vertical scale fits the tallest of them. */
    int pool = blades * 4 < BLADE_CLUMP_MAX_BLADES ? blades * 4 : BLADE_CLUMP_MAX_BLADES;
    pool = pool > blades ? pool : blades;
    blade_t *b = malloc(sizeof *b * (size_t)pool), *turned = malloc(sizeof *b * (size_t)pool);
    float *place = malloc(sizeof(float) * 2 * (size_t)pool);
    bool ok = sb.z && sb.v && sb.n && sb.hits && b && turned && place;
    core_rng_t rng;
    core_rng_seed(&rng, bake->seed, 100u + (uint64_t)layer);
    blade_env_t env = {.dt = BLADE_SETTLE_DT, .gravity = c->population.gravity};
    if (c->wind > 0.0f && bake->views_on)
        env.winds[env.wind_count++] = blade_wind_wave(0.0f, -1.0f, c->wind, 1.0f, 0.0f);
    env = blade_env_defaults(&env);
    float margin = BLADE_CLUMP_MARGIN * c->size[0] / (float)w, top = 0.0f;
    for (int n = 0; ok && n < pool; n++) {
        clump_blade(&b[n], &rng, c, &env, !bake->views_on, &place[2 * n], &place[2 * n + 1]);
        for (int i = 0; i <= BLADE_CLUMP_SEGMENTS; i++) {
            float p[3], nrm[3];
            blade_ref_surface(&b[n], c->population.shape, 0.5f, (float)i / BLADE_CLUMP_SEGMENTS, p, nrm);
            top = fmaxf(top, p[1]);
        }
    }
    /* Metres to samples up: by size[1], or by what the tallest blade needs
     * when it would reach above 0.98 of it; every view alike (an elevated
     * view's blades rising above the card are cut: the card's frame is
     * its window on the field). */
    float sy = (float)sb.h / fmaxf(c->size[1], top / 0.98f);
    for (int v = 0; ok && v < bake->views; v++) {
        float theta = bake->angles[v][0], phi = bake->angles[v][1];
        int i = v * bake->stride;
        /* The view's frame in the world: the wind W at azimuth phi, so
         * z = -cos phi W + sin phi W_perp, x = y cross z. */
        float cs = cosf(phi), sn = sinf(phi), wl = hypotf(c->wind_dir[0], c->wind_dir[1]);
        float W[2] = {c->wind_dir[0] / wl, c->wind_dir[1] / wl}, P[2] = {-W[1], W[0]};
        float z[2] = {-cs * W[0] + sn * P[0], -cs * W[1] + sn * P[1]}, x[2] = {z[1], -z[0]};
        float sl = sqrtf(c->sun[0] * c->sun[0] + c->sun[1] * c->sun[1] + c->sun[2] * c->sun[2]);
        float sun[3] = {(c->sun[0] * x[0] + c->sun[2] * x[1]) / sl, c->sun[1] / sl,
                        (c->sun[0] * z[0] + c->sun[2] * z[1]) / sl};
        ok = clump_view(&bake->albedo[i], &bake->light[i], &sb, b, place, turned, pool, blades, layer, c, theta, phi,
                        sy, margin, sun, &bake->stats[i]);
    }
    free(sb.z);
    free(sb.v);
    free(sb.n);
    free(sb.hits);
    free(b);
    free(turned);
    free(place);
    return ok;
}

