/* character_orient: up and forward of a model from its drawn pose, its
 * skeleton's names and its geometry (see character_orient.h). No paper
 * equations; the rules are measured on the assimp-testmodels corpus
 * (docs/CHARACTERS.md, test_character_corpus). */
#include "character/character_orient.h"

#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Case-insensitive strstr (strcasestr is a GNU extension). */
static bool contains_nocase(const char *s, const char *w)
{
    size_t k = strlen(w);
    for (; *s; s++)
        if (!strncasecmp(s, w, k)) return true;
    return false;
}

int character_orient_pose_clip(const character_model_t *m)
{
    for (int i = 0; i < m->clip_count; i++)
        if (contains_nocase(m->clips[i].name, "walk") && !m->clips[i].still) return i;
    for (int i = 0; i < m->clip_count; i++)
        if (!m->clips[i].still) return i;
    return m->clip_count ? 0 : -1;
}

void character_orient_pose(const character_model_t *m, int clip, character_pose_t *pose, float *positions)
{
    if (clip >= 0) character_sample_clip(m, clip, 0.0f, true, pose);
    else character_pose_bind(m, pose);
    character_pose_globals(m, pose);
    character_skin_cpu(m, pose, positions, NULL);
}

bool character_orient_box(const character_model_t *m, int clip, float lo[3], float hi[3])
{
    character_pose_t pose;
    float *p = malloc(sizeof(float) * 3 * (size_t)m->vertex_count);
    for (int k = 0; k < 3; k++) lo[k] = FLT_MAX, hi[k] = -FLT_MAX;
    if (!p || !character_pose_init(&pose, m)) {
        free(p);
        return false;
    }
    character_orient_pose(m, clip, &pose, p);
    for (int v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < 3; k++) lo[k] = fminf(lo[k], p[3 * v + k]), hi[k] = fmaxf(hi[k], p[3 * v + k]);
    character_pose_free(&pose);
    free(p);
    return true;
}

/* Case-insensitive: does name contain any of the words (NULL-ended)? A word
 * starting with '$' must end the name ("$hd": LFHD, a head marker). */
static bool name_has(const char *name, const char *const *words)
{
    size_t n = strlen(name);
    for (; *words; words++) {
        const char *w = *words;
        if (w[0] == '$') {
            size_t k = strlen(w + 1);
            if (n >= k && !strcasecmp(name + n - k, w + 1)) return true;
        } else if (contains_nocase(name, w)) {
            return true;
        }
    }
    return false;
}

/* Bones of the skeleton: those that move vertices and their ancestors
 * (not the mesh, group and marker nodes a file may name "head1"). */
static bool *skeleton_bones(const character_model_t *m)
{
    bool *used = calloc((size_t)m->bone_count, sizeof *used);
    if (!used) return NULL;
    for (int v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < CHARACTER_MAX_INFLUENCES; k++)
            if (m->vertices[v].weights[k] > 0.0f) used[m->vertices[v].joints[k]] = true;
    for (int b = m->bone_count - 1; b > 0; b--)
        if (used[b] && m->bones[b].parent >= 0) used[m->bones[b].parent] = true;
    return used;
}

/* Mean origin of the skeleton's bones whose names have one of the words;
 * false when none. */
static bool bones_mean(const character_model_t *m, const character_pose_t *pose, const char *const *words,
                       double out[3])
{
    int n = 0;
    out[0] = out[1] = out[2] = 0.0;
    bool *used = skeleton_bones(m);
    for (int b = 0; used && b < m->bone_count; b++) {
        if (!used[b] || !name_has(m->bones[b].name, words)) continue;
        for (int k = 0; k < 3; k++) out[k] += pose->global[b][12 + k];
        n++;
    }
    free(used);
    for (int k = 0; k < 3 && n; k++) out[k] /= n;
    return n > 0;
}

/* Nearest signed axis of d, skipping the axis `skip` (0: none); 0 when d is
 * farther than CHARACTER_ORIENT_MAX_ANGLE from it. */
static int snap_axis(const double d[3], int skip, float *cos_out)
{
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    int best = 0;
    double best_c = 0.0;
    for (int a = 0; a < 3 && len > 0.0; a++) {
        if (a + 1 == abs(skip)) continue;
        double c = fabs(d[a]) / len;
        if (c > best_c) best_c = c, best = (d[a] < 0.0 ? -1 : 1) * (a + 1);
    }
    if (cos_out) *cos_out = (float)best_c;
    return best_c >= cos(CHARACTER_ORIENT_MAX_ANGLE * 3.14159265358979 / 180.0) ? best : 0;
}

static const char *const top_words[] = {"head", "neck", "spine", "chest", "$hd", NULL};
static const char *const bottom_words[] = {"foot", "toe", "ankle", "heel", "leg", "knee", "shin", "thigh",
                                           "$ank", "$hel", "$kne", "$shn", "$thi", NULL};
static const char *const toe_words[] = {"toe", NULL};
static const char *const heel_words[] = {"heel", "ankle", "foot", "$ank", "$hel", NULL};

int character_orient_skeleton_up(const character_model_t *m, const character_pose_t *pose, float *cos_out)
{
    double top[3], bottom[3];
    if (cos_out) *cos_out = 0.0f;
    if (!bones_mean(m, pose, top_words, top) || !bones_mean(m, pose, bottom_words, bottom)) return 0;
    double d[3] = {top[0] - bottom[0], top[1] - bottom[1], top[2] - bottom[2]};
    return snap_axis(d, 0, cos_out);
}

/* Side of the body a bone name marks: +1 left, -1 right, 0 neither.
 * "left"/"right" anywhere, or a lone l/r between separators or the ends
 * ("HindLeg_L_01", "Bip01 R Thigh", "foot.l"). */
static int name_side(const char *name)
{
    if (contains_nocase(name, "left")) return 1;
    if (contains_nocase(name, "right")) return -1;
    for (size_t i = 0, n = strlen(name); i < n; i++) {
        char c = (char)(name[i] | 0x20);
        bool alone = (i == 0 || !isalnum((unsigned char)name[i - 1])) &&
                     (i + 1 == n || !isalnum((unsigned char)name[i + 1]));
        if (alone && (c == 'l' || c == 'r')) return c == 'l' ? 1 : -1;
    }
    return 0;
}

/* Forward from the sides: the mean of the skeleton's left bones minus the
 * mean of its right bones is the model's left, and left x up = forward
 * (a figure facing +Z with +Y up has its left at +X). */
static int side_forward(const character_model_t *m, const character_pose_t *pose, int up)
{
    double side[2][3] = {{0}};
    int n[2] = {0, 0};
    bool *used = skeleton_bones(m);
    for (int b = 0; used && b < m->bone_count; b++) {
        int s = used[b] ? name_side(m->bones[b].name) : 0;
        if (!s) continue;
        for (int k = 0; k < 3; k++) side[s < 0][k] += pose->global[b][12 + k];
        n[s < 0]++;
    }
    free(used);
    if (!n[0] || !n[1]) return 0;
    double left[3], u[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < 3; k++) left[k] = side[0][k] / n[0] - side[1][k] / n[1];
    u[abs(up) - 1] = up < 0 ? -1.0 : 1.0;
    double d[3] = {left[1] * u[2] - left[2] * u[1], left[2] * u[0] - left[0] * u[2], left[0] * u[1] - left[1] * u[0]};
    return snap_axis(d, up, NULL);
}

int character_orient_skeleton_forward(const character_model_t *m, const character_pose_t *pose, int up)
{
    double toe[3], heel[3];
    if (!up) return 0;
    if (!bones_mean(m, pose, toe_words, toe) || !bones_mean(m, pose, heel_words, heel))
        return side_forward(m, pose, up);
    double d[3] = {toe[0] - heel[0], toe[1] - heel[1], toe[2] - heel[2]};
    d[abs(up) - 1] = 0.0;
    return snap_axis(d, up, NULL);
}

/* Area of the model's horizontal box (axes other than a) that the
 * vertices within 3% of the bottom along `sign * a` cover, as a fraction. */
static double support(const character_model_t *m, const float *p, int a, int sign, const float lo[3],
                      const float hi[3])
{
    int b = (a + 1) % 3, c = (a + 2) % 3;
    float h = hi[a] - lo[a], bottom = sign > 0 ? lo[a] : hi[a];
    float clo[2] = {FLT_MAX, FLT_MAX}, chi[2] = {-FLT_MAX, -FLT_MAX};
    for (int v = 0; v < m->vertex_count; v++) {
        if (fabsf(p[3 * v + a] - bottom) > 0.03f * h) continue;
        clo[0] = fminf(clo[0], p[3 * v + b]), chi[0] = fmaxf(chi[0], p[3 * v + b]);
        clo[1] = fminf(clo[1], p[3 * v + c]), chi[1] = fmaxf(chi[1], p[3 * v + c]);
    }
    double eb = hi[b] - lo[b], ec = hi[c] - lo[c];
    /* a flat model (a plane): its thin axis counts as full */
    double fb = eb > 0.0 ? (chi[0] - clo[0]) / eb : 1.0, fc = ec > 0.0 ? (chi[1] - clo[1]) / ec : 1.0;
    return fmax(fb, 0.0) * fmax(fc, 0.0);
}

/* Area of the triangles within 3% of the bottom along `sign * a` that lie
 * flat on it (normal within 45 degrees of the axis): a sole or a foot
 * plate, where the other end of the axis has a rim or a tip. */
static double sole(const character_model_t *m, const float *p, int a, int sign, const float lo[3], const float hi[3])
{
    float h = hi[a] - lo[a], bottom = sign > 0 ? lo[a] : hi[a];
    double area = 0.0;
    for (int t = 0; t + 2 < m->index_count; t += 3) {
        const float *q[3] = {p + 3 * m->indices[t], p + 3 * m->indices[t + 1], p + 3 * m->indices[t + 2]};
        bool low = true;
        for (int k = 0; k < 3; k++) low &= fabsf(q[k][a] - bottom) <= 0.03f * h;
        if (!low) continue;
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) e1[k] = q[1][k] - q[0][k], e2[k] = q[2][k] - q[0][k];
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (len > 0.0 && fabs(n[a]) >= 0.7071 * len) area += 0.5 * len;
    }
    return area;
}

int character_orient_geometry_up(const character_model_t *m, const float *p, float *margin)
{
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (int v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < 3; k++) lo[k] = fminf(lo[k], p[3 * v + k]), hi[k] = fmaxf(hi[k], p[3 * v + k]);
    float size = fmaxf(hi[0] - lo[0], fmaxf(hi[1] - lo[1], hi[2] - lo[2]));
    double best[3] = {-1.0, -1.0, -1.0};
    int sign[3] = {1, 1, 1};
    for (int a = 0; a < 3; a++) {
        if (!(hi[a] - lo[a] > 1e-3f * size)) continue; /* flat along a: it cannot stand that way */
        double up = support(m, p, a, 1, lo, hi), down = support(m, p, a, -1, lo, hi);
        if (fabs(up - down) <= 0.2 * fmax(up, down))
            /* both ends touch alike (a grail, a box): it stands on the
             * end that lies flat */
            sign[a] = sole(m, p, a, 1, lo, hi) >= sole(m, p, a, -1, lo, hi) ? 1 : -1;
        else
            sign[a] = up > down ? 1 : -1;
        best[a] = fmax(up, down);
    }
    int win = 0;
    for (int a = 1; a < 3; a++)
        if (best[a] > best[win]) win = a;
    double second = 0.0;
    for (int a = 0; a < 3; a++)
        if (a != win) second = fmax(second, best[a]);
    if (margin) *margin = second > 0.0 ? (float)(best[win] / second) : best[win] > 0.0 ? 1e3f : 1.0f;
    return sign[win] * (win + 1);
}

/* Cells per axis of the grid over the box that body_forward mirrors. */
#define MIRROR_CELLS 24

static int cell_of(float x, float lo, float hi)
{
    return hi > lo ? (int)((x - lo) / (hi - lo) * (MIRROR_CELLS - 1) + 0.5f) : 0;
}

/* Marks the grid cells the triangles' surface passes through, sampling
 * each triangle finer than a cell. */
static void fill_cells(const character_model_t *m, const float *p, const float lo[3], const float hi[3],
                       unsigned char *grid)
{
    for (int t = 0; t + 2 < m->index_count; t += 3) {
        const float *q[3] = {p + 3 * m->indices[t], p + 3 * m->indices[t + 1], p + 3 * m->indices[t + 2]};
        float edge = 0.0f;
        for (int e = 0; e < 3; e++)
            for (int k = 0; k < 3; k++)
                if (hi[k] > lo[k])
                    edge = fmaxf(edge, fabsf(q[(e + 1) % 3][k] - q[e][k]) / (hi[k] - lo[k]) * (MIRROR_CELLS - 1));
        int n = (int)fminf(ceilf(edge), MIRROR_CELLS);
        if (n < 1) n = 1;
        for (int i = 0; i <= n; i++)
            for (int j = 0; i + j <= n; j++) {
                float u = (float)i / (float)n, w = (float)j / (float)n;
                int c[3];
                for (int k = 0; k < 3; k++)
                    c[k] = cell_of((1.0f - u - w) * q[0][k] + u * q[1][k] + w * q[2][k], lo[k], hi[k]);
                grid[(c[0] * MIRROR_CELLS + c[1]) * MIRROR_CELLS + c[2]] = 1;
            }
    }
}

/* Fraction of the filled cells whose mirror across the middle of axis a
 * (or a cell beside it along a) is empty: 0 for a shape symmetric across
 * that plane. */
static double mirror_miss(const unsigned char *grid, int a)
{
    int filled = 0, missed = 0;
    for (int i = 0; i < MIRROR_CELLS * MIRROR_CELLS * MIRROR_CELLS; i++) {
        if (!grid[i]) continue;
        int c[3] = {i / (MIRROR_CELLS * MIRROR_CELLS), i / MIRROR_CELLS % MIRROR_CELLS, i % MIRROR_CELLS};
        int mirror = MIRROR_CELLS - 1 - c[a];
        bool found = false;
        for (int d = -1; d <= 1 && !found; d++) {
            c[a] = mirror + d;
            if (c[a] >= 0 && c[a] < MIRROR_CELLS) found = grid[(c[0] * MIRROR_CELLS + c[1]) * MIRROR_CELLS + c[2]];
        }
        filled++;
        missed += !found;
    }
    return filled ? (double)missed / filled : 0.0;
}

int character_orient_body_forward(const character_model_t *m, const float *p, int up)
{
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (int v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < 3; k++) lo[k] = fminf(lo[k], p[3 * v + k]), hi[k] = fmaxf(hi[k], p[3 * v + k]);
    int u = abs(up) - 1, a = (u + 1) % 3, b = (u + 2) % 3;
    unsigned char *grid = calloc((size_t)MIRROR_CELLS * MIRROR_CELLS * MIRROR_CELLS, 1);
    if (!up || !grid) {
        free(grid);
        return 0;
    }
    fill_cells(m, p, lo, hi, grid);
    double miss_a = mirror_miss(grid, a), miss_b = mirror_miss(grid, b);
    free(grid);
    /* the body's length: the axis the mirror does not map onto itself */
    int len_axis = miss_a > miss_b ? a : b;
    double side = fmin(miss_a, miss_b), length = fmax(miss_a, miss_b);
    float len = hi[len_axis] - lo[len_axis], height = hi[u] - lo[u];
    if (side > CHARACTER_ORIENT_MIRROR || length < 2.0 * CHARACTER_ORIENT_MIRROR || !(height > 0.0f) || len < height)
        return 0;
    double mean = 0.0;
    for (int v = 0; v < m->vertex_count; v++) mean += p[3 * v + len_axis];
    double off = (mean / m->vertex_count - 0.5 * (lo[len_axis] + hi[len_axis])) / len;
    if (fabs(off) < 0.03) return 0;
    return (off < 0.0 ? -1 : 1) * (len_axis + 1);
}
