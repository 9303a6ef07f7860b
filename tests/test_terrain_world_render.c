/* test_terrain_world_render: a 4 km world terrain drawn by ground_draw as a
 * clipmap (terrain_world.vert + terrain.frag) on llvmpipe, read back. The
 * vertex shader's positions and normals (transform feedback, every vertex
 * of every level) against terrain_clipmap_vertex + terrain_world_height
 * within 1e-3 m and 1e-3 (float rounding, fused multiply-adds). Seen
 * straight down from 250 m (over a point on the snap lines of every level)
 * and from 1500 m (all 7 levels in view), every pixel has terrain depth (no
 * hole at any level border); the depth under the centre pixel unprojects to
 * terrain_world_height there within 5 cm; a walker's view 1.7 m above the
 * ground covers the lower half of the image. The walker's view is written
 * to $MEADOW_TEST_OUT/world_walk.png. */
#include "ground/ground.h"
#include "platform/plat.h"
#include "terrain/terrain.h"
#include "terrain/terrain_clipmap.h"
#include "test.h"
#include "test_gl.h"

#include <cglm/cglm.h>
#include <stdlib.h>
#include <string.h>

enum { W = 160, H = 120 };

/* The frame's view and the inverse view-projection the sky needs. */
typedef struct view_t {
    grass_view_t frame;
    mat4 inv_viewproj;
} view_t;

static void view_at(view_t *v, const float eye[3], const float target[3], const float up[3])
{
    memset(v, 0, sizeof *v);
    mat4 view, proj, vp;
    glm_lookat((float *)eye, (float *)target, (float *)up, view);
    glm_perspective(glm_rad(90.0f), (float)W / (float)H, 1.0f, 6000.0f, proj);
    glm_mat4_mul(proj, view, vp);
    glm_mat4_inv(vp, v->inv_viewproj);
    memcpy(v->frame.viewproj, vp, sizeof v->frame.viewproj);
    glm_vec3_copy((float *)eye, v->frame.camera);
    glm_vec3_copy((vec3){0.4f, 0.8f, 0.3f}, v->frame.sun);
    glm_vec3_normalize(v->frame.sun);
}

/* Draws and reads depth; returns the pixels without terrain in rows [row0, H). */
static int draw_holes(const ground_t *t, const gfx_target_t *tg, const view_t *v, int row0, float *depth)
{
    gfx_target_bind(tg);
    glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    ground_draw(t, &v->frame, (const float *)v->inv_viewproj);
    gfx_target_resolve(tg);
    CHECK(gfx_target_read_depth(tg, depth));
    int holes = 0;
    for (int y = row0; y < H; y++)
        for (int x = 0; x < W; x++) holes += !(depth[y * W + x] < 1.0f);
    return holes;
}

/* Every vertex of every level through terrain_world.vert (the clipmap's
 * grid as ground.c uploads it), captured, against the CPU twin. */
static void check_vertex_twin(const terrain_world_t *w, const float eye[3])
{
    static const char *const varyings[] = {"v_pos", "v_normal", NULL};
    gfx_program_t prog = gfx_program_make(&(gfx_program_desc_t){
        .vs = "ground/terrain_world.vert", .tf_varyings = varyings, .label = "world.vertex_twin"});
    CHECK(prog.id != 0);
    terrain_world_gpu_t g = terrain_world_gpu(w);
    gfx_world_height_uniforms(prog, g.keys, TERRAIN_WORLD_LAYERS, g.height);
    terrain_clipmap_t c;
    CHECK(terrain_clipmap_make(&c, &(terrain_clipmap_desc_t){0}));
    size_t bytes = sizeof(float) * 6 * c.vertex_count;
    gfx_buffer_t out = gfx_buffer_make(&(gfx_buffer_desc_t){.size = bytes, .label = "world.vertex_twin.out"});
    float *got = malloc(bytes);
    double dp = 0.0, dn = 0.0;
    glUseProgram(prog.id);
    glUniform3fv(gfx_uniform(prog, "u_camera"), 1, eye);
    glUniformMatrix4fv(gfx_uniform(prog, "u_viewproj"), 1, GL_FALSE, (const float *)GLM_MAT4_IDENTITY);
    gfx_buffer_t grid = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof(uint16_t) * 2 * c.vertex_count,
                                                             .data = c.grid, .label = "world.vertex_twin.grid"});
    GLuint vao = gfx_vertex_array_make("world.vertex_twin.vao");
    glVertexArrayVertexBuffer(vao, 0, grid.id, 0, 2 * sizeof(uint16_t));
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribIFormat(vao, 0, 2, GL_UNSIGNED_SHORT, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    glBindVertexArray(vao);
    glEnable(GL_RASTERIZER_DISCARD);
    for (int l = 0; l < c.desc.levels; l++) {
        terrain_clipmap_level_t lv = terrain_clipmap_place(&c, l, eye[0], eye[2]);
        glUniform2fv(gfx_uniform(prog, "u_origin"), 1, lv.origin);
        glUniform1f(gfx_uniform(prog, "u_cell"), lv.cell);
        glUniform2fv(gfx_uniform(prog, "u_morph"), 1, lv.morph);
        glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, out.id);
        glBeginTransformFeedback(GL_POINTS);
        glDrawArrays(GL_POINTS, 0, (GLsizei)c.vertex_count);
        glEndTransformFeedback();
        CHECK(gfx_buffer_read(out, 0, bytes, got));
        for (uint32_t v = 0; v < c.vertex_count; v++) {
            float xz[2];
            vec3 n;
            terrain_clipmap_vertex(&lv, c.grid[2 * v], c.grid[2 * v + 1], eye[0], eye[2], xz);
            float want[3] = {xz[0], terrain_world_height(w, xz[0], xz[1], n), xz[1]};
            for (int k = 0; k < 3; k++) {
                dp = fmax(dp, fabs(got[6 * v + (uint32_t)k] - want[k]));
                dn = fmax(dn, fabs(got[6 * v + 3 + (uint32_t)k] - n[k]));
            }
        }
    }
    glDisable(GL_RASTERIZER_DISCARD);
    printf("terrain_world.vert vs terrain_clipmap_vertex + terrain_world_height (%u vertices x %d levels): "
           "worst position %.2g m, normal %.2g\n", c.vertex_count, c.desc.levels, dp, dn);
    CHECK(dp < 1e-3);
    CHECK(dn < 1e-3);
    free(got);
    gfx_vertex_array_destroy(&vao);
    gfx_buffer_destroy(&grid);
    gfx_buffer_destroy(&out);
    gfx_program_destroy(&prog);
    terrain_clipmap_free(&c);
}

int main(void)
{
    test_gl_init();
    terrain_mesh_t mesh;
    CHECK(terrain_make_world(&mesh, &(terrain_desc_t){.type = TERRAIN_WORLD, .size = 4096, .height = 30}, 3));
    ground_t *t = ground_make(&mesh);
    CHECK(t != NULL);
    gfx_target_t tg = gfx_target_make(&(gfx_target_desc_t){.w = W, .h = H, .samples = 1, .label = "world.target"});
    float *depth = malloc(sizeof(float) * W * H);
    gfx_target_bind(&tg); /* draws need a complete framebuffer */
    check_vertex_twin(&mesh.world, (float[3]){-1000.3f, 12.0f, 733.7f});
    view_t v;
    static const float north[3] = {0.0f, 0.0f, -1.0f}, up[3] = {0.0f, 1.0f, 0.0f};

    float x = 1024.0f, z = -512.0f, g = terrain_world_height(&mesh.world, x, z, NULL);
    view_at(&v, (float[3]){x, g + 250.0f, z}, (float[3]){x, g, z}, north);
    int holes = draw_holes(t, &tg, &v, 0, depth);
    /* depth of the centre (between the 4 middle pixels: read one, W/2, H/2) */
    float d = depth[(H / 2) * W + W / 2];
    vec4 ndc = {((float)(W / 2) + 0.5f) / W * 2.0f - 1.0f, 1.0f - ((float)(H / 2) + 0.5f) / H * 2.0f, d * 2.0f - 1.0f,
                1.0f},
         p;
    glm_mat4_mulv(v.inv_viewproj, ndc, p);
    float px = p[0] / p[3], py = p[1] / p[3], pz = p[2] / p[3];
    float want = terrain_world_height(&mesh.world, px, pz, NULL);
    printf("top-down from 250 m: %d pixels without terrain; centre at (%.2f, %.2f): drawn %.3f m, function %.3f m\n",
           holes, (double)px, (double)pz, (double)py, (double)want);
    CHECK(holes == 0);
    CHECK_NEAR(py, want, 0.05);

    view_at(&v, (float[3]){-700.0f, 1500.0f, 300.0f}, (float[3]){-700.0f, 0.0f, 300.0f}, north);
    holes = draw_holes(t, &tg, &v, 0, depth);
    printf("top-down from 1500 m: %d pixels without terrain\n", holes);
    CHECK(holes == 0);

    g = terrain_world_height(&mesh.world, -300.0f, 200.0f, NULL);
    view_at(&v, (float[3]){-300.0f, g + 1.7f, 200.0f}, (float[3]){-280.0f, g - 3.0f, 180.0f}, up);
    holes = draw_holes(t, &tg, &v, H / 2, depth);
    printf("walker's view: %d pixels of the lower half without terrain\n", holes);
    CHECK(holes == 0);
    glFinish();
    double t0 = plat_time();
    for (int k = 0; k < 10; k++) draw_holes(t, &tg, &v, H, depth);
    printf("walker's view, %dx%d, 7 levels: %.1f ms per draw and readback (timing only)\n", W, H,
           (plat_time() - t0) * 100.0);
    const char *out = getenv("MEADOW_TEST_OUT");
    if (out) {
        char path[1024];
        core_fs_mkdirs(out);
        snprintf(path, sizeof path, "%s/world_walk.png", out);
        CHECK(gfx_target_screenshot(&tg, path));
    }
    free(depth);
    gfx_target_destroy(&tg);
    ground_destroy(t);
    terrain_free(&mesh);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}
