/* bb.glsl: GLSL twins of src/billboard/bb_ref.c, bb_layout.c and
 * src/collide/collide_cube.c for the billboard grass of Orthmann, Rezk-Salama
 * & Kolb 2009: the stored billboard struct, depth cube map lookup, inside
 * test (eq. 1-3), push-out (eq. 4-5), spring relaxation (eq. 6-7), recovery
 * (eq. 8), the procedural wind pose and the generation rule. Each function
 * mirrors the C function of the same name (bb_ref_x -> bb_x; the cube map
 * functions as listed at their section) statement by statement; see
 * collide_cube.h for the cube map face table and texel addressing. Integer results match the C code bit
 * for bit; float results to rounding (sin/sqrt precision, fma contraction).
 *
 * Requires hash_u32(uint) (common/hash.glsl, twin of core_hash_u32) to be
 * declared before this file when bb_generate is used (define BB_NO_GENERATE
 * to leave it out). Mesh size: define BB_N (columns) and BB_M (rows) before
 * including, default 4 x 4; BB_MAX_CUBES (default 4) bounds the objects per
 * bb_collide call. */
#ifndef BB_GLSL
#define BB_GLSL

#ifndef BB_N
#define BB_N 4
#endif
#ifndef BB_M
#define BB_M 4
#endif
#ifndef BB_MAX_CUBES
#define BB_MAX_CUBES 4
#endif

#define BB_STATE_IDLE 0u
#define BB_STATE_COLLIDING 1u
#define BB_STATE_RECOVERING 2u

/* One stored billboard; std430, 64 bytes, mirrors bb_point_t. As a vertex
 * buffer (stride 64) the attributes are:
 *   location 0: vec4  position.xyz, angle        offset 0
 *   location 1: vec4  growth.xyz, messiness      offset 16
 *   location 2: vec2  size                       offset 32
 *   location 3: uvec2 layer, state (IPointer)    offset 40
 *   location 4: float recover_time               offset 48
 *   location 5: uint  seed (IPointer)            offset 52 */
struct bb_point {
    vec3 position;
    float angle;
    vec3 growth;
    float messiness;
    vec2 size;
    uint layer;
    uint state;
    float recover_time;
    uint seed;
    uint pad0;
    uint pad1;
};

/* Mirrors collide_cubemap_t (half -> half_size: "half" is reserved in GLSL); the
 * texels live in a sampler2DArray (RGBA32F, layer = layer0 + face, texel (i, j) = texelFetch(ivec3(i, j, layer), 0)). */
struct bb_cube {
    vec3 centre;
    float half_size;
    int res;
    int layer0;
};

/* ---- cube map: the face table of collide_get_face_basis; bb_lookup,
 * bb_inside and bb_push_out mirror collide_lookup_texel, collide_test_inside
 * and collide_push_out (collide/collide_cube.c) ---- */

const vec3 bb_face_u[6] = vec3[6](vec3(0, 0, -1), vec3(0, 0, 1), vec3(1, 0, 0),
                                  vec3(1, 0, 0), vec3(1, 0, 0), vec3(-1, 0, 0));
const vec3 bb_face_v[6] = vec3[6](vec3(0, 1, 0), vec3(0, 1, 0), vec3(0, 0, -1),
                                  vec3(0, 0, 1), vec3(0, 1, 0), vec3(0, 1, 0));
const vec3 bb_face_in[6] = vec3[6](vec3(-1, 0, 0), vec3(1, 0, 0), vec3(0, -1, 0),
                                   vec3(0, 1, 0), vec3(0, 0, -1), vec3(0, 0, 1));

float bb_lookup(sampler2DArray tex, bb_cube cube, int face, vec3 q, out vec4 texel)
{
    vec3 rel = q - cube.centre;
    float pu = dot(rel, bb_face_u[face]);
    float pv = dot(rel, bb_face_v[face]);
    float depth = dot(rel, bb_face_in[face]) + cube.half_size;
    float scale = float(cube.res) / (2.0 * cube.half_size);
    int i = int(floor((pu + cube.half_size) * scale));
    int j = int(floor((pv + cube.half_size) * scale));
    i = clamp(i, 0, cube.res - 1);
    j = clamp(j, 0, cube.res - 1);
    texel = texelFetch(tex, ivec3(i, j, cube.layer0 + face), 0);
    return depth;
}

bool bb_inside(sampler2DArray tex, bb_cube cube, vec3 q)
{
    for (int f = 0; f < 6; f++) {
        vec4 tx;
        float d = bb_lookup(tex, cube, f, q, tx);
        if (!(d > tx.x)) return false;
    }
    return true;
}

bool bb_push_out(sampler2DArray tex, bb_cube cube, vec3 q, out vec3 o)
{
    float best = 3.402823e38;
    vec3 n = vec3(0.0);
    for (int f = 0; f < 6; f++) {
        vec4 tx;
        float pen = bb_lookup(tex, cube, f, q, tx) - tx.x;
        if (!(pen > 0.0)) {
            o = q;
            return false;
        }
        if (pen < best) {
            best = pen;
            n = tx.yzw;
        }
    }
    o = q + best * n;
    return true;
}

/* ---- billboard mesh (bb_mesh_t): vertex (i, j) at j*BB_N + i, row 0 fixed ---- */

vec3 bb_pos[BB_N * BB_M];
vec3 bb_rest[BB_N * BB_M];

/* Normal of mesh vertex (i, j) from central differences of bb_pos
 * (one-sided at the borders); `fallback` where they are degenerate. */
vec3 bb_mesh_normal(int i, int j, vec3 fallback)
{
    vec3 du = bb_pos[j * BB_N + min(i + 1, BB_N - 1)] - bb_pos[j * BB_N + max(i - 1, 0)];
    vec3 dv = bb_pos[min(j + 1, BB_M - 1) * BB_N + i] - bb_pos[max(j - 1, 0) * BB_N + i];
    vec3 n = cross(du, dv);
    float l = length(n);
    return l > 1e-12 ? n / l : fallback;
}

void bb_spring(int a, int b, float r)
{
    bool fa = a < BB_N, fb = b < BB_N;
    if (fa && fb) return;
    vec3 delta = bb_pos[b] - bb_pos[a];
    float l = length(delta);
    if (l < 1e-12) return;
    float l0 = distance(bb_rest[a], bb_rest[b]);
    vec3 c = delta * ((l - l0) / l);
    if (fa) {
        bb_pos[b] += c * -r;
    } else if (fb) {
        bb_pos[a] += c * r;
    } else {
        bb_pos[a] += c * (0.5 * r);
        bb_pos[b] += c * (-0.5 * r);
    }
}

void bb_relax_springs(float r1, float r2, int iterations)
{
    for (int it = 0; it < iterations; it++) {
        for (int j = 1; j < BB_M; j++)
            for (int i = 0; i < BB_N - 1; i++) bb_spring(j * BB_N + i, j * BB_N + i + 1, r1);
        for (int i = 0; i < BB_N; i++)
            for (int j = 0; j < BB_M - 1; j++) bb_spring(j * BB_N + i, (j + 1) * BB_N + i, r1);
        for (int j = 0; j < BB_M - 1; j++) {
            for (int i = 0; i < BB_N - 1; i++) {
                bb_spring(j * BB_N + i, (j + 1) * BB_N + i + 1, r2);
                bb_spring(j * BB_N + i + 1, (j + 1) * BB_N + i, r2);
            }
        }
    }
}

/* Bend limit (bb_ref.c bb_bend, bb_ref_bend_limit): joint a between
 * segments b-a and a-v bends by at most about acos(BB_BEND_COS); a
 * violated joint is projected along the constraint's gradients (b < 0:
 * t is a root's rest column direction, b does not move). */
const float BB_BEND_COS = 0.25;

void bb_bend(vec3 t, int b, int a, int v)
{
    float tl = length(t);
    if (tl < 1e-12) return;
    t *= 1.0 / tl;
    vec3 av = bb_pos[v] - bb_pos[a];
    float c = dot(av, t) - BB_BEND_COS * distance(bb_rest[a], bb_rest[v]);
    if (c >= 0.0) return;
    vec3 p = av - t * dot(av, t);
    float inv = b >= 0 ? 1.0 / tl : 0.0;
    float wa = a >= BB_N ? 1.0 : 0.0, wb = b >= BB_N ? 1.0 : 0.0;
    vec3 ga = -t + p * inv, gb = -p * inv;
    float lambda = -c / (1.0 + wa * dot(ga, ga) + wb * dot(gb, gb));
    bb_pos[v] += t * lambda;
    bb_pos[a] += ga * (wa * lambda);
    if (b >= 0) bb_pos[b] += gb * (wb * lambda);
}

void bb_bend_limit()
{
    for (int i = 0; i < BB_N; i++)
        for (int j = 1; j < BB_M; j++) {
            int v = j * BB_N + i, a = v - BB_N;
            vec3 t = j == 1 ? bb_rest[v] - bb_rest[a] : bb_pos[a] - bb_pos[a - BB_N];
            bb_bend(t, j == 1 ? -1 : a - BB_N, a, v);
        }
    for (int j = 1; j < BB_M; j++)
        for (int i = 2; i < BB_N; i++) {
            int v = j * BB_N + i, a = v - 1;
            bb_bend(bb_pos[a] - bb_pos[a - 1], a - 1, a, v);
        }
}

/* Swept collision (bb_ref.c sweep_shift): the translation moving cube c
 * back along its sweep s (current to previous world position) to the
 * point of the step's path nearest p. */
vec3 bb_sweep_shift(bb_cube cube, mat4 c2w, vec3 s, vec3 p)
{
    vec3 centre = (c2w * vec4(cube.centre, 1.0)).xyz;
    float ss = dot(s, s);
    return ss > 0.0 ? s * clamp(dot(p - centre, s) / ss, 0.0, 1.0) : vec3(0.0);
}

/* Where cube c's push-out takes world point x (bb_ref.c push_target). */
bool bb_push_target(sampler2DArray tex, bb_cube cube, mat4 w2c, mat4 c2w, vec3 sweep, vec3 x, out vec3 to)
{
    vec3 shift = bb_sweep_shift(cube, c2w, sweep, x);
    vec3 o;
    to = x;
    if (!bb_push_out(tex, cube, (w2c * vec4(x - shift, 1.0)).xyz, o)) return false;
    to = (c2w * vec4(o, 1.0)).xyz + shift;
    return true;
}

/* Slide (bb_ref.c bb_slide): the point of the plane through `to` across
 * the push at the rest distance l0 from the vertex below, a, in the
 * direction x - a has along that plane; `to` where there is none. */
vec3 bb_slide(vec3 a, float l0, vec3 x, vec3 to)
{
    vec3 nrm = to - x;
    float pen = length(nrm);
    if (pen < 1e-12) return to;
    nrm *= 1.0 / pen;
    float h = dot(a - to, nrm);
    if (h * h >= l0 * l0) return to;
    vec3 ax = x - a;
    vec3 tang = ax - nrm * dot(ax, nrm);
    float tl = length(tang);
    if (tl < 1e-6 * l0) return to;
    float s = sqrt(l0 * l0 - h * h) / tl;
    return a - h * nrm + s * tang;
}

void bb_push_mesh(sampler2DArray tex, bb_cube cubes[BB_MAX_CUBES], mat4 w2c[BB_MAX_CUBES],
                  mat4 c2w[BB_MAX_CUBES], vec3 sweep[BB_MAX_CUBES], int count, bool paper)
{
    for (int v = BB_N; v < BB_N * BB_M; v++) {
        float l0 = distance(bb_rest[v], bb_rest[v - BB_N]);
        /* Each object's push slides the vertex at its row length, then
         * pushes the slid point again (bb_ref.c bb_push_mesh); one push
         * call site for both. */
        for (int c = 0; c < count; c++) {
            for (int k = 0; k < (paper ? 1 : 2); k++) {
                vec3 to;
                if (!bb_push_target(tex, cubes[c], w2c[c], c2w[c], sweep[c], bb_pos[v], to)) break;
                bb_pos[v] = k == 0 && !paper ? bb_slide(bb_pos[v - BB_N], l0, bb_pos[v], to) : to;
            }
        }
#ifdef BB_GROUND
        float g = terrain_height(bb_pos[v].x, bb_pos[v].z);
        if (paper || bb_pos[v].y >= g) continue;
        bb_pos[v].y = g;
        /* Raised back into an object whose push pointed down: leave sideways
         * (bb_ref.c bb_ground_vertex). */
        for (int c = 0; c < count; c++) {
            vec3 to;
            if (!bb_push_target(tex, cubes[c], w2c[c], c2w[c], sweep[c], bb_pos[v], to)) continue;
            vec3 d = to - bb_pos[v];
            float pen = length(d), hl = length(d.xz);
            if (hl < 1e-6 * max(pen, 1e-12)) continue;
            float s = min(pen * pen / hl, 4.0 * pen);
            bb_pos[v].xz += d.xz / hl * s;
            bb_pos[v].y = max(bb_pos[v].y, terrain_height(bb_pos[v].x, bb_pos[v].z));
        }
#endif
    }
}

/* bb_ref_collide: push-out, then K x (bend limit, one relaxation sweep,
 * push-out), each push with the slide (bb_slide); paper: the push-out
 * alone, then K relaxation sweeps (bb_collide_desc_t.paper).
 * c2w[c] must be inverse(w2c[c]) (computed once on the CPU); sweep[c] as
 * bb_collide_desc_t.sweep (0: the object where it is). */
void bb_collide(sampler2DArray tex, bb_cube cubes[BB_MAX_CUBES], mat4 w2c[BB_MAX_CUBES],
                mat4 c2w[BB_MAX_CUBES], vec3 sweep[BB_MAX_CUBES], int count, float r1, float r2, int iterations,
                bool paper)
{
    /* One call site per step, so the compiler inlines each once: with two
     * push_mesh sites (and two pushes in it) the H100's driver took 1.9 s
     * to build bb_collide.geom, now 0.7 s. Relaxing K times one sweep is
     * relaxing K sweeps. */
    for (int it = 0; it <= iterations; it++) {
        if (it > 0) {
            if (!paper) bb_bend_limit();
            bb_relax_springs(r1, r2, 1);
        }
        if (it == 0 || !paper) bb_push_mesh(tex, cubes, w2c, c2w, sweep, count, paper);
    }
}

/* Eq. 8 with the wind pose w (bb_wind_pose output). */
void bb_recover(vec3 w[BB_N * BB_M], float t)
{
    t = clamp(t, 0.0, 1.0);
    float t3 = t * t * t;
    for (int v = 0; v < BB_N * BB_M; v++) bb_pos[v] = (1.0 - t3) * w[v] + t3 * bb_pos[v];
}

/* ---- wind (bb_ref_wind_vertex / bb_ref_wind_pose) ---- */

struct bb_wind {
    vec2 dir;          /* normalised xz */
    float strength;
    float omega;
    float wavenumber;
};

vec3 bb_wind_vertex(bb_wind wind, vec3 rest, vec3 root, float h, float time)
{
    float ph = wind.wavenumber * (root.x * wind.dir.x + root.z * wind.dir.y);
    float wt = wind.omega * time;
    float s = 0.6 * sin(ph - wt) + 0.3 * sin(1.7 * ph - 2.3 * wt + 1.3) +
              0.1 * sin(2.9 * ph - 5.1 * wt + 0.7);
    float bend = wind.strength * h * h * (0.4 + 0.6 * s);
    return vec3(rest.x + bend * wind.dir.x, rest.y, rest.z + bend * wind.dir.y);
}

void bb_wind_pose(bb_wind wind, float time, out vec3 w[BB_N * BB_M])
{
    vec3 root = mix(bb_rest[0], bb_rest[BB_N - 1], 0.5);
    for (int j = 0; j < BB_M; j++) {
        float h = float(j) / float(BB_M - 1);
        for (int i = 0; i < BB_N; i++) w[j * BB_N + i] = bb_wind_vertex(wind, bb_rest[j * BB_N + i], root, h, time);
    }
}

/* ---- generation rule (bb_layout_sample) ----
 * Layout images are uploaded row 0 first without a flip, so
 * texelFetch(ivec2(tx, tz)) reads core_image px[tz * W + tx]. */
#ifndef BB_NO_GENERATE

struct bb_gen {
    float spacing;
    vec2 origin;
    int cells_per_texel;
    float width;
    float height;
    uint seed;
    uint layers;
};

float bb_hash_float(uint x) { return float(hash_u32(x) >> 8) * (1.0 / 16777216.0); }

int bb_floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

int bb_mod(int a, int b) { return a - b * bb_floor_div(a, b); }

/* bb_layout.c bb_accept_point: candidate h on texel t is kept with the
 * texel's extent as probability; a kept one gets every field but its
 * position (left to the caller). extent, messiness: R8 unorm, direction:
 * RGB8 unorm. */
bool bb_accept_point(sampler2D extent, sampler2D direction, sampler2D messiness, bb_gen d, uint h, ivec2 t,
                     out bb_point p)
{
    p = bb_point(vec3(0.0), 0.0, vec3(0.0), 0.0, vec2(0.0), 0u, 0u, 0.0, 0u, 0u, 0u);
    uint e = uint(round(texelFetch(extent, t, 0).r * 255.0));
    if (!(hash_u32(h ^ 0x5bd1e995u) % 255u < e)) return false;
    p.size.x = d.width * (0.8 + 0.4 * bb_hash_float(h + 3u));
    p.size.y = d.height * (0.6 + 0.8 * bb_hash_float(h + 4u)) * (0.5 + 0.5 * float(e) / 255.0);
    p.angle = 6.2831853 * bb_hash_float(h + 5u);
    p.layer = ((hash_u32(h + 6u) >> 8) * d.layers) >> 24;
    vec3 g = round(texelFetch(direction, t, 0).rgb * 255.0) / 255.0 * 2.0 - 1.0;
    p.growth = g * (1.0 / sqrt(dot(g, g)));
    p.messiness = round(texelFetch(messiness, t, 0).r * 255.0) / 255.0;
    p.seed = h;
    p.state = BB_STATE_IDLE;
    p.recover_time = 0.0;
    return true;
}

bool bb_generate(sampler2D extent, sampler2D direction, sampler2D messiness, bb_gen d, int ix,
                 int iz, out bb_point p)
{
    uint h = hash_u32(uint(ix) * 0x8da6b343u ^ hash_u32(uint(iz) ^ hash_u32(d.seed)));
    ivec2 wh = textureSize(extent, 0);
    int tx = bb_mod(bb_floor_div(ix, d.cells_per_texel), wh.x);
    int tz = bb_mod(bb_floor_div(iz, d.cells_per_texel), wh.y);
    if (!bb_accept_point(extent, direction, messiness, d, h, ivec2(tx, tz), p)) return false;
    p.position.x = d.origin.x + (float(ix) + bb_hash_float(h + 1u)) * d.spacing;
    p.position.y = 0.0;
    p.position.z = d.origin.y + (float(iz) + bb_hash_float(h + 2u)) * d.spacing;
    return true;
}

/* Mirrors bb_gen_tri_t (bb_layout.h; length -> len, the name of a GLSL
 * built-in): one triangle of a mesh terrain in its plane frame; std430, 64
 * bytes. */
struct bb_gen_tri {
    vec3 a;
    float len;
    vec3 u;
    float height;
    vec3 v;
    float foot;
    ivec2 cells;
    int plane;
    int pad;
};

int bb_texel_of(float c, bb_gen d, int side)
{
    return bb_mod(bb_floor_div(int(floor(c / d.spacing)), d.cells_per_texel), side);
}

/* bb_layout_sample_tri: cell (i, j) of triangle tri named t. */
bool bb_generate_tri(sampler2D extent, sampler2D direction, sampler2D messiness, bb_gen d, bb_gen_tri tri,
                     uint t, int i, int j, out bb_point p)
{
    uint h = hash_u32(uint(i) * 0x8da6b343u ^ hash_u32(uint(j) ^ hash_u32(t ^ hash_u32(d.seed))));
    float pu = (float(i) + bb_hash_float(h + 1u)) * d.spacing;
    float pv = (float(j) + bb_hash_float(h + 2u)) * d.spacing;
    p = bb_point(vec3(0.0), 0.0, vec3(0.0), 0.0, vec2(0.0), 0u, 0u, 0.0, 0u, 0u, 0u);
    if (!(tri.height * pu >= tri.foot * pv && tri.height * (tri.len - pu) >= (tri.len - tri.foot) * pv))
        return false;
    vec3 pos = tri.a + pu * tri.u + pv * tri.v;
    float cx = pos.x - d.origin.x, cz = pos.z - d.origin.y;
    float s0 = tri.plane == 0 ? cz : cx, s1 = tri.plane == 1 ? cz : pos.y;
    ivec2 wh = textureSize(extent, 0);
    ivec2 tt = ivec2(bb_texel_of(s0, d, wh.x), bb_texel_of(s1, d, wh.y));
    if (!bb_accept_point(extent, direction, messiness, d, h, tt, p)) return false;
    p.position = pos;
    return true;
}

#endif /* BB_NO_GENERATE */

#endif /* BB_GLSL */
