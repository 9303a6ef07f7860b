/* measure_floor: the floors of a frame: the GPU time to draw the same number of
 * triangles with trivial shaders from a prebuilt buffer into a target of
 * the same size and MSAA, through the hardware pipeline (measure_floor_ms) or
 * the compute rasterizer (measure_floor_compute_ms: its start, the draw and
 * its composite, raster_floor.comp). Blade-like thin triangles scattered
 * over the screen, so rasterisation and vertex work are both exercised. */
#include "measure/measure.h"

#include <stdlib.h>
#include <string.h>

#include "common/bindings_raster.glsl"
#include "platform/plat.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The triangles in clip space (three vec4 each); id 0 when out of memory. */
static gfx_buffer_t floor_triangles(long triangles, int w, int h)
{
    size_t bytes = (size_t)triangles * 3 * 4 * sizeof(float);
    float *v = malloc(bytes);
    if (!v) return (gfx_buffer_t){0};
    core_rng_t rng;
    core_rng_seed(&rng, 99, 7);
    /* Each triangle: a 14-triangle blade is about 4 px wide and 40 px tall at
     * 1080p; use thin slivers of that size in NDC, depth-sorted randomly. */
    float sx = 4.0f / (float)w, sy = 40.0f / (float)h;
    for (long t = 0; t < triangles; t++) {
        float x = core_rng_range(&rng, -1, 1), y = core_rng_range(&rng, -1, 1), z = core_rng_range(&rng, 0, 1);
        float tri[12] = {x, y, z, 1, x + sx, y, z, 1, x + sx * 0.5f, y + sy / 7.0f, z, 1};
        memcpy(v + t * 12, tri, sizeof tri);
    }
    gfx_buffer_t buf = gfx_buffer_make(&(gfx_buffer_desc_t){.size = bytes, .data = v, .label = "floor.vertices"});
    free(v);
    return buf;
}

static double median(double *ms, int n)
{
    if (!n) return -1.0;
    qsort(ms, (size_t)n, sizeof ms[0], cmp_double);
    return ms[n / 2];
}

double measure_floor_ms(long triangles, int w, int h, int samples)
{
    if (triangles <= 0) return 0.0;
    gfx_buffer_t buf = floor_triangles(triangles, w, h);
    if (!buf.id) return -1.0;
    gfx_target_t t = gfx_target_make(&(gfx_target_desc_t){.w = w, .h = h, .samples = samples, .label = "floor"});
    gfx_program_t p = gfx_program_make(&(gfx_program_desc_t){.vs = "measure/floor.vert", .fs = "measure/floor.frag",
                                                             .label = "floor.program"});
    GLuint vao = gfx_vertex_array_make("floor.vao");
    glVertexArrayVertexBuffer(vao, 0, buf.id, 0, 4 * sizeof(float));
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    GLuint q = gfx_query_make(GL_TIME_ELAPSED, "floor.timer");
    double ms[12];
    int n = 0;
    for (int i = 0; i < 14 && t.fbo && p.id; i++) {
        gfx_target_bind(&t);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glUseProgram(p.id);
        glBindVertexArray(vao);
        glBeginQuery(GL_TIME_ELAPSED, q);
        glDrawArrays(GL_TRIANGLES, 0, (GLsizei)(triangles * 3));
        glEndQuery(GL_TIME_ELAPSED);
        GLuint64 ns = 0;
        glGetQueryObjectui64v(q, GL_QUERY_RESULT, &ns);
        if (i >= 2) ms[n++] = (double)ns * 1e-6;
    }
    glBindVertexArray(0);
    gfx_query_destroy(&q);
    gfx_vertex_array_destroy(&vao);
    gfx_program_destroy(&p);
    gfx_target_destroy(&t);
    gfx_buffer_destroy(&buf);
    return median(ms, n);
}

static void bind_floor(gfx_program_t p, void *user)
{
    const gfx_buffer_t *buf = user;
    glUniform1ui(gfx_uniform(p, "u_count"), (GLuint)(buf->size / (12 * sizeof(float))));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, RASTER_BIND_FLOOR_TRIS, buf->id);
}

double measure_floor_compute_ms(long triangles, int w, int h, int samples, int raster_samples)
{
    if (triangles <= 0) return 0.0;
    if (triangles > 0x7fffffffL / 3) return -1.0;
    gfx_buffer_t buf = floor_triangles(triangles, w, h);
    if (!buf.id) return -1.0;
    gfx_target_t t = gfx_target_make(&(gfx_target_desc_t){.w = w, .h = h, .samples = samples, .label = "floor"});
    raster_t r;
    bool ok = t.fbo && raster_make(&r, &(raster_desc_t){.w = w, .h = h, .samples = raster_samples,
                                                         .label = "floor.raster"});
    raster_program_t p = {0};
    if (ok) p = raster_program_make(&r, "raster/raster_floor.comp", NULL, "floor.raster");
    GLuint q[2] = {gfx_query_make(GL_TIMESTAMP, "floor.t0"), gfx_query_make(GL_TIMESTAMP, "floor.t1")};
    raster_items_t items = {.count = (uint32_t)triangles};
    double ms[12];
    int n = 0;
    for (int i = 0; i < 14 && ok && p.prim.id; i++) {
        gfx_target_bind(&t);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glQueryCounter(q[0], GL_TIMESTAMP);
        raster_begin(&r, &t);
        raster_draw(&r, &p, &items, bind_floor, &buf);
        raster_end(&r, &t);
        glQueryCounter(q[1], GL_TIMESTAMP);
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(q[0], GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(q[1], GL_QUERY_RESULT, &t1);
        if (i >= 2 && t1 >= t0) ms[n++] = (double)(t1 - t0) * 1e-6;
    }
    gfx_query_destroy(&q[0]);
    gfx_query_destroy(&q[1]);
    raster_program_destroy(&p);
    if (ok) raster_destroy(&r);
    gfx_target_destroy(&t);
    gfx_buffer_destroy(&buf);
    return median(ms, n);
}
