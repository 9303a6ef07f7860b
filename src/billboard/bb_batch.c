/* bb_batch: the collide batches of one update (beyond the paper, which
 * tests every object in one pass): the colliding leaves grouped greedily,
 * in Morton order, into batches whose objects number at most
 * BB_PASS_OBJECTS (bb_collide.geom's BB_MAX_CUBES); a leaf that meets more
 * is split into runs of billboards by their bounding spheres, keeping each
 * billboard's nearest objects. All batches' object entries are uploaded at
 * once and drawn in one transform feedback (docs/BILLBOARDS.md). */
#include "billboard/bb_local.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static bool plan_reserve(bb_batch_plan_t *pl, int batches, int ranges)
{
    if (batches > pl->cap) {
        int cap = batches > 2 * pl->cap ? batches : 2 * pl->cap;
        int *rs = realloc(pl->range_start, sizeof *rs * (size_t)(cap + 1));
        if (rs) pl->range_start = rs;
        int *oc = realloc(pl->obj_count, sizeof *oc * (size_t)cap);
        if (oc) pl->obj_count = oc;
        int(*ob)[BB_PASS_OBJECTS] = realloc(pl->obj, sizeof *ob * (size_t)cap);
        if (ob) pl->obj = ob;
        if (!rs || !oc || !ob) return false;
        pl->cap = cap;
    }
    if (ranges > pl->range_cap) {
        int cap = ranges > 2 * pl->range_cap ? ranges : 2 * pl->range_cap;
        GLint *fi = realloc(pl->first, sizeof *fi * (size_t)cap);
        if (fi) pl->first = fi;
        GLsizei *sz = realloc(pl->size, sizeof *sz * (size_t)cap);
        if (sz) pl->size = sz;
        if (!fi || !sz) return false;
        pl->range_cap = cap;
    }
    return true;
}

/* Adds billboards [first, first+count) that must be tested against objs
 * (n <= limit, ascending) to the open batch when the union of the two
 * object lists stays within limit, else opens a new batch. Ranges adjacent
 * in the buffer and in the same batch are merged. */
static bool plan_add(bb_batch_plan_t *pl, int limit, GLint first, GLsizei count, const int *objs, int n)
{
    int b = pl->count - 1, merged[BB_PASS_OBJECTS], m = 0;
    bool fits = b >= 0;
    if (fits) {
        const int *a = pl->obj[b];
        int na = pl->obj_count[b], i = 0, j = 0;
        while ((i < na || j < n) && fits) {
            int v;
            if (j == n || (i < na && a[i] < objs[j])) v = a[i++];
            else if (i == na || objs[j] < a[i]) v = objs[j++];
            else v = a[i++], j++;
            fits = m < limit;
            if (fits) merged[m++] = v;
        }
    }
    if (!plan_reserve(pl, pl->count + 1, pl->range_count + 1)) return false;
    if (!fits) {
        b = pl->count++;
        pl->range_start[b] = pl->range_count;
        memcpy(pl->obj[b], objs, sizeof *objs * (size_t)n);
        pl->obj_count[b] = n;
    } else {
        memcpy(pl->obj[b], merged, sizeof *merged * (size_t)m);
        pl->obj_count[b] = m;
    }
    int r = pl->range_count - 1;
    if (r >= pl->range_start[b] && pl->first[r] + pl->size[r] == first) {
        pl->size[r] += count;
    } else {
        pl->first[++r] = first;
        pl->size[r] = count;
        pl->range_count++;
    }
    pl->range_start[pl->count] = pl->range_count;
    return true;
}

static int cmp_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

/* A leaf whose box meets more than `limit` objects: each billboard's own
 * objects (bounding spheres closer than the sum of the radii, 1 mm of slack
 * over the shader's float test) join the plan one billboard at a time, so
 * runs of billboards share batches; billboards that touch nothing are left
 * out. More than `limit` objects on one billboard: the nearest (surface
 * distance) are kept and the rest counted in f->dropped. */
/* Distance from p to an object's bound (negative inside a sphere, 0 inside
 * a box: a swept object's capsule boxed). */
static float bound_distance(const bb_bound_t *b, const float p[3])
{
    if (b->kind == BB_BOUND_SPHERE) return sqrtf(glm_vec3_distance2((float *)p, (float *)b->centre)) - b->radius;
    float d2 = 0.0f;
    for (int a = 0; a < 3; a++) {
        float e = fmaxf(fabsf(p[a] - b->centre[a]) - b->half[a], 0.0f);
        d2 += e * e;
    }
    return sqrtf(d2);
}

static bool plan_split_leaf(bb_field_t *f, int limit, const bb_range_t *r, const bb_bound_t *bounds,
                            const int *objs, int n)
{
    for (uint32_t i = r->first; i < r->first + r->count; i++) {
        const float *sp = f->spheres[i];
        float dist[BB_MAX_OBJECTS];
        int hit[BB_MAX_OBJECTS], h = 0;
        for (int q = 0; q < n; q++) {
            float dd = bound_distance(&bounds[objs[q]], sp) - sp[3];
            if (dd < 1e-3f) dist[h] = dd, hit[h++] = objs[q];
        }
        if (h == 0) continue;
        if (h > limit) {
            for (int a = 1; a < h; a++) /* insertion sort by distance, ties by index */
                for (int c = a; c > 0 && dist[c] < dist[c - 1]; c--) {
                    float td = dist[c];
                    dist[c] = dist[c - 1], dist[c - 1] = td;
                    int ti = hit[c];
                    hit[c] = hit[c - 1], hit[c - 1] = ti;
                }
            f->dropped += h - limit;
            h = limit;
            qsort(hit, (size_t)h, sizeof *hit, cmp_int);
        }
        if (!plan_add(&f->plan, limit, (GLint)i, 1, hit, h)) return false;
    }
    return true;
}

/* The box of range r's leaf (the ring's: its slot's cell) in lo, hi;
 * returns its broad-phase margin. */
static float range_box(const bb_field_t *f, const bb_range_t *r, float lo[3], float hi[3])
{
    if (f->ring_on) {
        bb_ring_slot_box(&f->ring, (int)r->leaf, lo, hi);
        return f->ring.margin;
    }
    int node = bb_octree_leaf_node(&f->tree, r->leaf);
    for (int a = 0; a < 3; a++) lo[a] = f->tree.lo[node][a], hi[a] = f->tree.hi[node][a];
    return f->tree.desc.margin;
}

/* Groups the colliding leaf ranges f->ranges[0..ncol) into batches of at
 * most bb_pass_objects(f) objects; need[k] is set for every object in a batch. */
bool bb_plan_batches(bb_field_t *f, int ncol, const bb_bound_t *bounds, int count, bool *need)
{
    bb_batch_plan_t *pl = &f->plan;
    pl->count = pl->range_count = 0;
    int limit = bb_pass_objects(f);
    int dropped_before = f->dropped;
    for (int i = 0; i < ncol; i++) {
        const bb_range_t *r = &f->ranges[i];
        float lo[3], hi[3], margin = range_box(f, r, lo, hi);
        int objs[BB_MAX_OBJECTS], n = 0;
        for (int k = 0; k < count; k++)
            if (bb_bound_overlaps_box(&bounds[k], lo, hi, margin)) objs[n++] = k;
        if (n > limit && f->ring_on) { /* no per-billboard spheres: the first objects */
            f->dropped += n - limit;
            n = limit;
        }
        bool ok = n <= limit ? n == 0 || plan_add(pl, limit, (GLint)r->first, (GLsizei)r->count, objs, n)
                             : plan_split_leaf(f, limit, r, bounds, objs, n);
        if (!ok) {
            core_log_error("out of memory for %d collide batches", pl->count);
            return false;
        }
    }
    for (int b = 0; b < pl->count; b++)
        for (int j = 0; j < pl->obj_count[b]; j++) need[pl->obj[b][j]] = true;
    if (f->dropped > dropped_before && f->dropped_logged == 0) {
        core_log_warn("bb: a billboard's bounding sphere meets more than %d objects; it collides with the nearest "
                      "%d (%d object hits left out so far, see bb_stats_t.objects_dropped)",
                      limit, limit, f->dropped);
        f->dropped_logged = f->dropped;
    }
    return true;
}

/* Runs one transform-feedback pass of `prog` over the ranges first/size:
 * points -> scratch (appended in draw order), then copied back in place.
 * With a plan (collide), batch b binds its region of the objects buffer,
 * sets u_count and draws its own ranges, all inside the one transform
 * feedback. */
static void tf_pass(bb_field_t *f, gfx_program_t prog, const GLint *first, const GLsizei *size, int nranges,
                    const bb_batch_plan_t *pl)
{
    glUseProgram(prog.id);
    glBindVertexArray(f->points_vao);
    GLint fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, f->cube_target.fbo); /* draws need a complete framebuffer */
    glEnable(GL_RASTERIZER_DISCARD);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, f->tf);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, f->scratch.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POOL, f->pool.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_MESHES, f->meshes.id);
    glBeginTransformFeedback(GL_POINTS);
    if (!pl) {
        glMultiDrawArrays(GL_POINTS, first, size, nranges);
    } else {
        GLint count_loc = gfx_uniform(prog, "u_count");
        for (int b = 0; b < pl->count; b++) {
            glBindBufferRange(GL_UNIFORM_BUFFER, BB_UBO_OBJECTS, f->objects.id,
                              (GLintptr)(f->objects_stride * (size_t)b), (GLsizeiptr)f->objects_stride);
            glUniform1i(count_loc, pl->obj_count[b]);
            int r0 = pl->range_start[b];
            glMultiDrawArrays(GL_POINTS, first + r0, size + r0, pl->range_start[b + 1] - r0);
        }
    }
    glEndTransformFeedback();
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
    glDisable(GL_RASTERIZER_DISCARD);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    size_t off = 0;
    for (int i = 0; i < nranges; i++) {
        size_t bytes = (size_t)size[i] * sizeof(bb_point_t);
        glCopyNamedBufferSubData(f->scratch.id, f->points.id, (GLintptr)off,
                                 (GLintptr)((size_t)first[i] * sizeof(bb_point_t)), (GLsizeiptr)bytes);
        off += bytes;
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* Uploads every batch's object entries (one aligned region per batch, all
 * in a single update before the pass, so no batch waits on another's
 * upload) and runs the collide pass over the batches. */
bool bb_collide_batches(bb_field_t *f, const bb_object_gpu_t *gpu)
{
    bb_batch_plan_t *pl = &f->plan;
    size_t need = f->objects_stride * (size_t)pl->count;
    if (need > f->objects_size) {
        size_t size = need > 2 * f->objects_size ? need : 2 * f->objects_size;
        gfx_buffer_destroy(&f->objects);
        f->objects = gfx_buffer_make(&(gfx_buffer_desc_t){.size = size, .dynamic = true, .label = "bb.objects"});
        f->objects_size = f->objects.id ? size : 0;
        if (!f->objects.id) return false;
    }
    uint8_t *staging = calloc(need, 1);
    if (!staging) {
        core_log_error("out of memory for %d collide batches", pl->count);
        return false;
    }
    for (int b = 0; b < pl->count; b++) {
        bb_object_gpu_t *dst = (bb_object_gpu_t *)(staging + f->objects_stride * (size_t)b);
        for (int j = 0; j < pl->obj_count[b]; j++) dst[j] = gpu[pl->obj[b][j]];
    }
    gfx_buffer_update(f->objects, 0, need, staging);
    free(staging);

    tf_pass(f, f->collide_prog, f->plan.first, f->plan.size, f->plan.range_count, &f->plan);
    gfx_count_add("bb.collided", bb_range_total(f->plan.size, f->plan.range_count));
    gfx_count_add("bb.collide_batches", pl->count);
    return true;
}
