/* host_glfw: a host of libmeadow, built against the installed package:
 *   cc host_glfw.c $(pkg-config --cflags --libs meadow epoxy glfw3 egl) -lm
 * Its own window (GLFW), camera, framebuffer, a ball the arrow keys roll
 * through the grass, and a skinned character walking a square (the
 * library's loader). --headless --frames N renders N frames through its own
 * EGL context and writes --out (PNG). --scene PATH (default
 * scenes/lawn.json). docs/LIBRARY.md. */
#include <grass/grass.h>
#include <grass/grass_character.h>

#include <epoxy/gl.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#define W 640
#define H 360
#define BALL_R 0.3f

static const char *vs = "#version 450 core\nlayout(location=0) in vec3 p;uniform mat4 mvp;out vec3 n;"
                        "void main(){n=p;gl_Position=mvp*vec4(p,1);}";
static const char *fs = "#version 450 core\nin vec3 n;out vec4 c;void main(){"
                        "c=vec4(vec3(0.8,0.2,0.15)*(0.35+0.65*max(dot(normalize(n),normalize(vec3(.45,.8,.35))),0.)),1);}";

/* A GL 4.5 core context with no window: EGL's surfaceless or device platform. */
static int egl_context(void)
{
    EGLDisplay d = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, NULL, NULL)) {
        d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        if (d == EGL_NO_DISPLAY || !eglInitialize(d, NULL, NULL)) return 0;
    }
    EGLConfig cfg = NULL; /* no surface is made; the first GL config, else none */
    EGLint n = 0, cattr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    if (!eglBindAPI(EGL_OPENGL_API)) return 0;
    if (!eglChooseConfig(d, cattr, &cfg, 1, &n) || n < 1) cfg = EGL_NO_CONFIG_KHR;
    EGLint attr[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext c = eglCreateContext(d, cfg, EGL_NO_CONTEXT, attr);
    return c != EGL_NO_CONTEXT && eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c);
}

static GLuint shader(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL), glCompileShader(s);
    return s;
}

/* A UV sphere of radius BALL_R: its vertex array (position at attribute 0,
 * as grass_collider_t wants it) and index count. */
static GLuint ball_mesh(GLsizei *count)
{
    enum { SEG = 16, RING = 10 };
    static float v[(RING + 1) * (SEG + 1) * 3];
    static unsigned idx[RING * SEG * 6];
    int k = 0, m = 0;
    for (int r = 0; r <= RING; r++)
        for (int s = 0; s <= SEG; s++) {
            float th = 3.14159265f * (float)r / RING, ph = 6.2831853f * (float)s / SEG;
            v[k++] = BALL_R * sinf(th) * cosf(ph), v[k++] = BALL_R * cosf(th), v[k++] = BALL_R * sinf(th) * sinf(ph);
        }
    for (int r = 0; r < RING; r++)
        for (int s = 0; s < SEG; s++) {
            unsigned a = (unsigned)(r * (SEG + 1) + s), b = a + SEG + 1;
            unsigned q[6] = {a, b, a + 1, a + 1, b, b + 1};
            for (int i = 0; i < 6; i++) idx[m++] = q[i];
        }
    GLuint vao, buf[2];
    glCreateVertexArrays(1, &vao), glCreateBuffers(2, buf);
    glNamedBufferStorage(buf[0], sizeof v, v, 0), glNamedBufferStorage(buf[1], sizeof idx, idx, 0);
    glVertexArrayVertexBuffer(vao, 0, buf[0], 0, 3 * sizeof(float));
    glVertexArrayElementBuffer(vao, buf[1]);
    for (GLuint a = 0; a < 2; a++) { /* position, and the normal: a sphere's about its centre is its position */
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao, a, 0);
    }
    *count = m;
    return vao;
}

static void look_at(float m[16], const float e[3], const float c[3])
{
    float f[3] = {c[0] - e[0], c[1] - e[1], c[2] - e[2]}, l = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int i = 0; i < 3; i++) f[i] /= l;
    float s[3] = {-f[2], 0, f[0]}, ls = sqrtf(s[0] * s[0] + s[2] * s[2]); /* f x up */
    s[0] /= ls, s[2] /= ls;
    float u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]};
    float r[16] = {s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
                   -(s[0] * e[0] + s[1] * e[1] + s[2] * e[2]), -(u[0] * e[0] + u[1] * e[1] + u[2] * e[2]),
                   f[0] * e[0] + f[1] * e[1] + f[2] * e[2], 1};
    memcpy(m, r, sizeof r);
}

static void perspective(float m[16], float fovy, float aspect, float n, float f)
{
    float t = 1.0f / tanf(fovy * 0.5f);
    float r[16] = {t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (f + n) / (n - f), -1, 0, 0, 2 * f * n / (n - f), 0};
    memcpy(m, r, sizeof r);
}

int main(int argc, char **argv)
{
    const char *scene = "scenes/lawn.json", *out = "host_glfw.png";
    int headless = 0, frames = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--headless")) headless = 1;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc) frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else if (!strcmp(argv[i], "--scene") && i + 1 < argc) scene = argv[++i];
        else return fprintf(stderr, "host_glfw: unknown option %s\n", argv[i]), 2;
    }
    GLFWwindow *win = NULL;
    if (headless) {
        if (!egl_context()) return fprintf(stderr, "host_glfw: no EGL OpenGL 4.5 context\n"), 1;
    } else {
        if (!glfwInit()) return fprintf(stderr, "host_glfw: no display\n"), 1;
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4), glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        if (!(win = glfwCreateWindow(W, H, "meadow host", NULL, NULL))) return 1;
        glfwMakeContextCurrent(win);
    }
    grass_t *g = grass_make(&(grass_desc_t){.scene = scene, .width = W, .height = H});
    if (!g) return grass_last_error();
    printf("libmeadow %s: %s\n", grass_version(), scene);
    static const float square[4][2] = {{-2.5f, -2.5f}, {2.5f, -2.5f}, {2.5f, 2.5f}, {-2.5f, 2.5f}};
    grass_character_t *walker = grass_character_make(g, &(grass_character_desc_t){
        .model = "models/humanoid.gltf", .clip = "walk", .height = 1.75f, .waypoints = square, .waypoint_count = 4,
        .loop = true});
    if (!walker) return 2;
    GLuint tex[2], fbo;
    glCreateTextures(GL_TEXTURE_2D, 2, tex), glCreateFramebuffers(1, &fbo);
    glTextureStorage2D(tex[0], 1, GL_RGBA8, W, H), glTextureStorage2D(tex[1], 1, GL_DEPTH_COMPONENT32F, W, H);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex[0], 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, tex[1], 0);
    GLuint prog = glCreateProgram();
    glAttachShader(prog, shader(GL_VERTEX_SHADER, vs)), glAttachShader(prog, shader(GL_FRAGMENT_SHADER, fs));
    glLinkProgram(prog);
    GLsizei count;
    GLuint ball_vao = ball_mesh(&count);
    float ball[3] = {-3.5f, BALL_R, 0.5f}, eye[3] = {0, 2.5f, 6.5f}, at[3] = {0, 0, 0}, view[16], proj[16];
    perspective(proj, 1.047f, (float)W / H, 0.1f, 100.0f);
    const float dt = 1.0f / 60.0f;
    for (int f = 0; headless ? f < frames : !glfwWindowShouldClose(win); f++) {
        float t = (float)(f + 1) * dt, speed = 3.0f * dt;
        if (headless) ball[0] += speed; /* rolls along x through the lawn */
        else {
            glfwPollEvents();
            ball[0] += speed * (float)(glfwGetKey(win, GLFW_KEY_RIGHT) - glfwGetKey(win, GLFW_KEY_LEFT));
            ball[2] += speed * (float)(glfwGetKey(win, GLFW_KEY_DOWN) - glfwGetKey(win, GLFW_KEY_UP));
        }
        grass_character_update(walker, t, dt);
        grass_collider_t c[2] = {{.shape = GRASS_SHAPE_SPHERE, .position = {ball[0], ball[1], ball[2]},
                                  .radius = BALL_R, .vao = ball_vao, .index_count = count, .index_type = GL_UNSIGNED_INT,
                                  .model = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, ball[0], ball[1], ball[2], 1}},
                                 grass_character_collider(walker)};
        grass_update(g, c, 2, t, dt);
        /* the host's frame: the ground (the first occluder), its opaque ball and walker, then the grass */
        glBindFramebuffer(GL_FRAMEBUFFER, fbo), glViewport(0, 0, W, H);
        glClearColor(0.6f, 0.75f, 0.9f, 1), glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        look_at(view, eye, at);
        grass_view_t v;
        grass_view_make(&v, view, proj, W, H, t);
        grass_target_t target = {.fbo = fbo, .color_texture = tex[0], .depth_texture = tex[1], .width = W,
                                 .height = H, .samples = 1};
        grass_draw_part(g, &v, &target, GRASS_PART_GROUND);
        glUseProgram(prog);
        float mvp[16] = {0};
        for (int cidx = 0; cidx < 4; cidx++)
            for (int r = 0; r < 4; r++)
                for (int k = 0; k < 4; k++) mvp[cidx * 4 + r] += v.viewproj[k * 4 + r] * c[0].model[cidx * 4 + k];
        glUniformMatrix4fv(glGetUniformLocation(prog, "mvp"), 1, GL_FALSE, mvp);
        glBindVertexArray(ball_vao), glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, NULL);
        grass_character_draw(walker, &v);
        grass_draw_part(g, &v, &target, GRASS_PART_GRASS);
        if (!headless) {
            glBlitNamedFramebuffer(fbo, 0, 0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glfwSwapBuffers(win);
        }
    }
    static unsigned char px[W * H * 4];
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
    stbi_flip_vertically_on_write(1);
    int ok = headless ? stbi_write_png(out, W, H, 4, px, W * 4) : 1;
    grass_character_destroy(walker);
    grass_destroy(g);
    if (win) glfwTerminate();
    if (headless) printf("%s: %d frames\n", ok ? out : "cannot write the PNG", frames);
    return ok ? 0 : 1;
}
