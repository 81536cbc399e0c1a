// Co-simulation of the RGS's shading datapath against the C model, one stream per unit:
//  shade_rec_decode (rtl/shade_rec_decode.sv): each vertex normal decoded from a compact shading
//    record, against shade_rec_normal (hls/units/shade_rec.c). The bench slices the vertex's 42-bit
//    code out of the record (shade_rec_bits, as the RGS's read of the record would).
//  rgs_frame (rtl/rgs_frame.sv): the frame of each hit the RGS shades (unit direction, unit shading
//    normal facing the ray, entering, t_hat, the hit point), against rgs_surface_frame
//    (hls/units/rgs_geom.c).
//  rgs_light (rtl/rgs_light.sv): one light at one surface (the shadow ray, the Q12 diffuse and
//    highlight weights, the active bit), against rgs_light_packet (hls/units/rgs_light.c) on a
//    packet whose other rays are invalid.
//  rgs_lerp (rtl/rgs_lerp.sv): each component of a hit's interpolated vertex normal or texture
//    coordinates, against rgs_lerp (hls/units/rgs_geom.c).
//  rgs_light_colour, rgs_add_light (rtl/rgs_light_colour.sv, rgs_add_light.sv): each light's Q12
//    colour and each visible light added to a ray's sums, against rgs_light_colour and
//    rgs_add_light (hls/units/rgs_light.c).
//  rgs_spawn (rtl/rgs_spawn.sv): the child rays of each surface (reflection, transmission with
//    refraction and total internal reflection, their Q12 weights and active bits), against
//    rgs_spawn_children (hls/units/rgs_spawn.c) on a packet of that one ray.
//  tex_bilinear (rtl/tex_coords.sv into rtl/tex_fetch.sv): each bilinear texture sample, against rgs_texel_axis and
//    rgs_bilinear_blend (hls/units/rgs_tex.c, the functions rgs_sample_bilinear is made of). The
//    bench is the memory: every texel request must carry the C's address (texture address + y w +
//    x, in the C's order t00, t10, t01, t11) and gets its word back in order, after 1 cycle or, in
//    the gappy epochs, 1 to 4 cycles with gaps.
// Captured transactions (saarcor render --capture-unit-io DIR: DIR/shade_rec.hex, every
// vertex normal decoded (shade_rec_normals, a line per normal): the record's 4 normal words, the
// vertex k, the unit normal; DIR/tex.hex,
// every rgs_sample_bilinear call: s, t, width, height, texel address, the 4 texel words read, the
// axes' x0 x1 fx y0 y1 fy, the sample; DIR/frame.hex, every rgs_surface_frame call: o, d, t, cos_n,
// the object-space normal, the world-to-object 3x3; the outputs; DIR/light.hex, every light at every
// surface of rgs_light_packet: the light record's words 0..12, e, the surface's valid, unlit, P,
// N^, D^, k; the shadow ray, active, diff, spec; DIR/lerp.hex, every rgs_lerp call and component of rgs_lerp_normal: a, b, c, u, v;
// the result; DIR/colour.hex and DIR/accum.hex, every rgs_light_colour and rgs_add_light call;
// DIR/spawn.hex, every rgs_spawn_children call: the material's words 13..15, the ray's weight, e, the
// surface's T_R origin, D^, N^, t_hat, entering, tint, base; both children) come first and are also checked against the recording; then
// random ones: records of random words with one vertex's code set to an edge (the missing normal
// x = -2^20 with any y, the poles and axes +-(2^20 - 1), codes on and beside the fold
// |x| + |y| = 2^20 - 1, small components) or anything; samples at coordinates near 0 and 1, on
// texel centres and edges, large, negative, Inf, NaN or any encoding, on textures of 1 texel, small,
// power-of-two and huge sizes (to 2^31 - 1) at any address (the address sums wrap as the C's),
// with random texels; frames of rays of moderate, tiny, huge, zero or special components, normals
// of any length (zero too) and rotation-like or arbitrary matrices; lights of every type (spot cones
// equal, reversed or special too) at random surfaces, invalid and unlit ones, exponents 0..15;
// interpolations at barycentrics inside the triangle, on its edges, outside or special; colours of
// any sign, zero or special; sums and weights of any 16-bit value (saturating); child rays of
// surfaces with indices of refraction 1, near 1, glass-like, below 1 (total internal reflection
// when leaving), special, entering or leaving, and weights around the spawn threshold.
// Every transaction gets a thread id (its number modulo 64), which must come
// out with its result. The handshakes are exercised: in every other epoch of 1024 cycles the inputs
// have random gaps and the outputs (and the memory's request port) random back pressure. A
// mismatch prints the unit, the transaction, the cycle, the thread, the field and both values (and
// the inputs); exit code 1 on any mismatch, a wrong thread or address, or a result lost or invented.
// usage: tb_shade [-n N] [--seed S] [--capture DIR]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_shade.h"
#include "tb_common.h"

extern "C" {
#include "rgs_ops.h"
#include "shade_rec.h"
}

using namespace cosim;

namespace {

// shade_rec.hex's word order: inputs (the record's normal words, the vertex), then the normal
struct normal_tx { uint32_t rec[SHADE_NORMAL_WORDS], k, n[3]; };
// tex.hex's word order: inputs (s, t, the texture entry), the texels, the axes, the sample
struct tex_tx { uint32_t s, t, width, height, addr, texel[4], axes[6], rgb[3]; };
// frame.hex's word order: inputs (o, d, t, cos_n, n, the 3x3 row by row), then the frame
struct frame_tx { uint32_t o[3], d[3], t, cos_n, n[3], w2o[9], dh[3], nh[3], entering, t_hat, p[3]; };
constexpr std::size_t FRAME_IN = 20;
// light.hex's word order: inputs (the light's words 0..12, e, the surface, k), then the outputs
struct light_tx {
    uint32_t l[13], eps, valid, unlit, p[3], n[3], d[3], k, o[3], sd[3], tmin, tmax, active, diff, spec;
};
constexpr std::size_t LIGHT_IN = 26;
// lerp.hex's word order: a, b, c, u, v, the result
struct lerp_tx { uint32_t a, b, c, u, v, r; };
// colour.hex: the light's words 1..3, its Q12 colour; accum.hex: the sums, diff, spec, the colour;
// the sums after
struct colour_tx { uint32_t c[3], q[3]; };
// spawn.hex: the inputs, then the reflection and the transmission ray (o, d, weight, active)
struct spawn_tx {
    uint32_t eta, shader0, shader1, weight[3], eps, o[3], d[3], n[3], t_hat, entering, tint[3], base[3];
    uint32_t r_o[3], r_d[3], r_w[3], r_active, t_o[3], t_d[3], t_w[3], t_active;
};
constexpr std::size_t SPAWN_IN = 24;
struct accum_tx { uint32_t diffuse[3], highlight[3], diff, spec, colour[3], diffuse_o[3], highlight_o[3]; };
constexpr uint32_t OCT_MASK = (1u << SHADE_OCT_BITS) - 1u;

uint64_t code_of(const normal_tx &x)
{
    const uint32_t at = 2u * SHADE_OCT_BITS * x.k;
    return (uint64_t)shade_rec_bits(x.rec, at, SHADE_OCT_BITS) |
           (uint64_t)shade_rec_bits(x.rec, at + SHADE_OCT_BITS, SHADE_OCT_BITS) << SHADE_OCT_BITS;
}

void model(normal_tx &x)
{
    const f24_vec3 n = shade_rec_normal(x.rec, x.k);
    x.n[0] = n.x, x.n[1] = n.y, x.n[2] = n.z;
}

// the axes and the sample of the texels as the C computes them
void model(tex_tx &x)
{
    uint32_t *a = x.axes;
    rgs_texel_axis(x.s, x.width, &a[0], &a[1], &a[2]);
    rgs_texel_axis(x.t, x.height, &a[3], &a[4], &a[5]);
    rgs_bilinear_blend(x.texel, a[2], a[5], x.rgb);
}

f24_vec3 v3(const uint32_t *w) { return f24_vec3{ w[0], w[1], w[2] }; }
void words3(f24_vec3 v, uint32_t *w) { w[0] = v.x, w[1] = v.y, w[2] = v.z; }

void model(frame_tx &x)
{
    f24_affine m{};
    for (int k = 0; k < 3; k++)
        for (int r = 0; r < 3; r++)
            m.m[k][r] = x.w2o[3 * k + r];
    surface sf{};
    rgs_surface_frame(v3(x.o), v3(x.d), x.t, x.cos_n, v3(x.n), &m, &sf);
    words3(sf.d, x.dh), words3(sf.n, x.nh), words3(sf.p, x.p);
    x.entering = (uint32_t)sf.entering, x.t_hat = sf.t_hat;
}

void model(lerp_tx &x) { x.r = rgs_lerp(x.a, x.b, x.c, x.u, x.v); }
void model(spawn_tx &x)
{
    uint32_t m[16] = {};
    m[13] = x.eta, m[14] = x.shader0, m[15] = x.shader1;
    surface sf{};
    sf.d = v3(x.d), sf.n = v3(x.n), sf.t_hat = x.t_hat, sf.entering = (int)x.entering;
    sf.tr = t_r(v3(x.o), sf.d, sf.n);
    for (int k = 0; k < 3; k++)
        sf.tint[k] = x.tint[k], sf.base[k] = x.base[k];
    rgs_task refl{}, trans{};
    rgs_spawn_children(m, x.weight, x.eps, 0, &sf, &refl, &trans);
    words3(refl.rays.o[0], x.r_o), words3(refl.rays.d[0], x.r_d), words3(trans.rays.o[0], x.t_o),
        words3(trans.rays.d[0], x.t_d);
    for (int k = 0; k < 3; k++)
        x.r_w[k] = refl.weight[0][k], x.t_w[k] = trans.weight[0][k];
    x.r_active = refl.rays.active & 1u, x.t_active = trans.rays.active & 1u;
}
void model(colour_tx &x)
{
    const uint32_t l[4] = { 0, x.c[0], x.c[1], x.c[2] };
    rgs_light_colour(l, x.q);
}
void model(accum_tx &x)
{
    std::memcpy(x.diffuse_o, x.diffuse, sizeof x.diffuse), std::memcpy(x.highlight_o, x.highlight, sizeof x.highlight);
    rgs_add_light(x.diffuse_o, x.highlight_o, x.diff, x.spec, x.colour);
}

// rgs_light_packet on a packet of this surface and three invalid ones
void model(light_tx &x)
{
    surface sf[TRACE_PACKET] = {};
    sf[0].valid = (int)x.valid, sf[0].unlit = (int)x.unlit;
    sf[0].p = v3(x.p), sf[0].n = v3(x.n), sf[0].d = v3(x.d);
    const uint32_t k_of[TRACE_PACKET] = { x.k, 0, 0, 0 };
    uint32_t l[16] = {};
    std::memcpy(l, x.l, sizeof x.l);
    ray_packet sh;
    uint32_t diff[TRACE_PACKET], spec[TRACE_PACKET];
    rgs_light_packet(l, sf, x.eps, &sh, diff, spec, k_of);
    words3(sh.o[0], x.o), words3(sh.d[0], x.sd);
    x.tmin = sh.tmin[0], x.tmax = sh.tmax[0], x.active = sh.active & 1u, x.diff = diff[0], x.spec = spec[0];
}

// the word address of texel j (t00, t10, t01, t11) of a modelled sample
uint32_t texel_addr(const tex_tx &x, int j)
{
    return x.addr + x.axes[j < 2 ? 3 : 4] * x.width + x.axes[j & 1];
}

// an octahedral component: an edge or anything
int32_t rnd_oct()
{
    const int32_t one = SHADE_OCT_ONE;
    switch (rnd() % 8) {
    case 0: return (int32_t)(rnd() % 5) - 2;
    case 1: return one - (int32_t)(rnd() % 3);
    case 2: return -one + (int32_t)(rnd() % 3);
    case 3: return -one - 1; // -2^20: the missing normal's x
    default: return (int32_t)(rnd() & OCT_MASK) - (1 << (SHADE_OCT_BITS - 1));
    }
}

uint32_t rnd32() { return rnd() << 16 ^ rnd(); }

normal_tx random_normal()
{
    normal_tx x{};
    for (auto &w : x.rec)
        w = rnd32();
    x.k = rnd() % 3;
    int32_t cx = rnd_oct(), cy = rnd_oct();
    if (rnd() % 4 == 0) { // on or beside the fold |x| + |y| = 2^20 - 1
        const int32_t ax = (int32_t)(rnd() % (uint32_t)SHADE_OCT_ONE), ay = SHADE_OCT_ONE - ax + (int32_t)(rnd() % 3) - 1;
        cx = (rnd() & 1u) ? -ax : ax;
        cy = ay > SHADE_OCT_ONE ? SHADE_OCT_ONE : (rnd() & 1u) ? -ay : ay;
    }
    // the code into the record's bits 42k .. 42k + 41 (bits 126, 127 stay what they were: unread)
    const uint64_t code = ((uint64_t)((uint32_t)cy & OCT_MASK) << SHADE_OCT_BITS) | ((uint32_t)cx & OCT_MASK);
    for (uint32_t b = 0; b < 2u * SHADE_OCT_BITS; b++) {
        const uint32_t bit = 2u * SHADE_OCT_BITS * x.k + b;
        x.rec[bit / 32] = (x.rec[bit / 32] & ~(1u << bit % 32)) | (uint32_t)(code >> b & 1u) << bit % 32;
    }
    model(x);
    return x;
}

uint32_t rnd_size()
{
    switch (rnd() % 6) {
    case 0: return 1 + rnd() % 3;
    case 1: return 1u << rnd() % 13;
    case 2: return 1 + rnd32() % 0x7FFFFFFFu;
    default: return 1 + rnd() % 300;
    }
}

// a texture coordinate over n texels: moderate, on a texel centre or edge, huge, special or anything
uint32_t rnd_coord(uint32_t n)
{
    switch (rnd() % 10) {
    case 0: return rnd_f24();
    case 1: return rnd32() & F24_MASK;
    case 2: case 3: { // (k + 1/2) / n or k / n, k possibly outside 0..n
        const int32_t k = (int32_t)(rnd() % (2 * (n % 4096) + 3)) - (int32_t)(n % 4096) - 1;
        const f24_t num = (rnd() & 1u) ? f24_add(f24_from_i32(k), f24_div(F24_ONE, f24_from_i32(2))) : f24_from_i32(k);
        return f24_div(num, f24_from_i32((int32_t)n));
    }
    default: // [-4, 4)
        return f24_div(f24_from_i32((int32_t)(rnd() % 65536) - 32768), f24_from_i32(8192));
    }
}

tex_tx random_tex()
{
    tex_tx x{};
    x.width = rnd_size(), x.height = rnd_size();
    x.s = rnd_coord(x.width), x.t = rnd_coord(x.height);
    x.addr = rnd() % 4 ? rnd() % 0x1000000u : rnd32();
    for (auto &w : x.texel)
        w = rnd() % 8 ? rnd32() : (rnd() & 1u) ? 0xFFFFFFFFu : 0u;
    model(x);
    return x;
}

// a moderate value of magnitude up to 2^scale, or now and then a special one or any encoding
uint32_t moderate(int scale)
{
    if (rnd() % 16 == 0)
        return rnd_f24();
    const uint32_t e = (uint32_t)(F24_BIAS - scale + (int)(rnd() % (uint32_t)(2 * scale + 1)));
    return ((rnd() & 1u) ? F24_SIGN_BIT : 0u) | e << F24_MAN_BITS | (rnd() & F24_FRAC_MASK);
}

frame_tx random_frame()
{
    frame_tx x{};
    const uint32_t kind = rnd() % 8; // 0: zero normal, 1: any encodings, else moderate
    for (int k = 0; k < 3; k++) {
        x.o[k] = kind == 1 ? rnd32() & F24_MASK : moderate(8);
        x.d[k] = kind == 1 ? rnd32() & F24_MASK : moderate(4);
        x.n[k] = kind == 0 ? ((rnd() & 1u) ? F24_SIGN_BIT : 0u) : kind == 1 ? rnd32() & F24_MASK : moderate(3);
    }
    x.t = kind == 1 ? rnd32() & F24_MASK : moderate(6);
    x.cos_n = moderate(1);
    for (auto &w : x.w2o)
        w = kind == 1 ? rnd32() & F24_MASK : moderate(2);
    model(x);
    return x;
}

light_tx random_light()
{
    light_tx x{};
    const uint32_t types[] = { 0, 1, 2, 2, 3 };
    x.l[0] = rnd() % 16 ? types[rnd() % 5] : rnd32();
    for (int k = 0; k < 3; k++) {
        x.l[1 + k] = moderate(1);             // the colour: not this unit's
        x.l[4 + k] = moderate(6), x.l[7 + k] = moderate(0);
        x.p[k] = moderate(6), x.n[k] = moderate(0), x.d[k] = moderate(0);
    }
    x.l[10] = moderate(2);
    // the cone: inner > outer mostly, equal, reversed, or anything
    const uint32_t cin = f24_div(f24_from_i32((int32_t)(rnd() % 4096)), f24_from_i32(4096));
    const uint32_t cout = f24_div(f24_from_i32((int32_t)(rnd() % 4096) - 2048), f24_from_i32(4096));
    switch (rnd() % 8) {
    case 0: x.l[11] = x.l[12] = cin; break;
    case 1: x.l[11] = cout, x.l[12] = cin; break;
    case 2: x.l[11] = rnd_f24(), x.l[12] = rnd_f24(); break;
    default: x.l[11] = cin, x.l[12] = cout;
    }
    x.eps = moderate(3);
    x.valid = rnd() % 8 != 0, x.unlit = rnd() % 8 == 0, x.k = rnd() % 16;
    model(x);
    return x;
}

// a barycentric: in [0, 1] mostly, 0 or 1 exactly, slightly outside, or anything
uint32_t rnd_bary()
{
    switch (rnd() % 8) {
    case 0: return rnd() & 1u ? F24_ONE : (rnd() & 1u) ? F24_SIGN_BIT : 0u;
    case 1: return moderate(1);
    case 2: return rnd_f24();
    default: return f24_div(f24_from_i32((int32_t)(rnd() % 65537)), f24_from_i32(65536));
    }
}

lerp_tx random_lerp()
{
    lerp_tx x{ moderate(2), moderate(2), moderate(2), rnd_bary(), rnd_bary(), 0 };
    model(x);
    return x;
}

spawn_tx random_spawn()
{
    spawn_tx x{};
    const uint32_t etas[] = { F24_ONE, f24_div(f24_from_i32(3), f24_from_i32(2)), f24_div(f24_from_i32(2), f24_from_i32(3)),
                              f24_div(f24_from_i32(4097), f24_from_i32(4096)), f24_from_i32(4) };
    x.eta = rnd() % 8 ? etas[rnd() % 5] : rnd() % 2 ? moderate(1) : rnd_f24();
    x.shader0 = rnd32(), x.shader1 = rnd32();
    const uint32_t top = rnd() % 4 ? 4097 : 65536;
    for (int k = 0; k < 3; k++) {
        x.weight[k] = rnd() % top, x.tint[k] = rnd() % top, x.base[k] = rnd() % top;
        x.o[k] = moderate(6), x.d[k] = moderate(0), x.n[k] = moderate(0);
    }
    if (rnd() % 2) { // a unit direction and normal as rgs_surface_frame leaves them
        const f24_t dl = f24_div(F24_ONE, f24_sqrt(rgs_dot3(v3(x.d), v3(x.d))));
        const f24_t nl = f24_div(F24_ONE, f24_sqrt(rgs_dot3(v3(x.n), v3(x.n))));
        for (int k = 0; k < 3; k++)
            x.d[k] = f24_mul(x.d[k], dl), x.n[k] = f24_mul(x.n[k], nl);
    }
    x.eps = moderate(3), x.t_hat = moderate(6), x.entering = rnd() % 2;
    model(x);
    return x;
}

colour_tx random_colour()
{
    colour_tx x{};
    for (auto &c : x.c)
        c = rnd() % 8 ? moderate(4) & ~(rnd() % 4 ? F24_SIGN_BIT : 0u) : rnd() % 2 ? 0u : rnd_f24();
    model(x);
    return x;
}

accum_tx random_accum()
{
    accum_tx x{};
    const uint32_t top = rnd() % 4 ? 8192 : 65536; // mostly moderate, now and then up to saturation
    for (int k = 0; k < 3; k++)
        x.diffuse[k] = rnd() % top, x.highlight[k] = rnd() % top, x.colour[k] = rnd() % 4097;
    x.diff = rnd() % top, x.spec = rnd() % top;
    model(x);
    return x;
}

uint64_t g_mismatches = 0;

// field by field: the first 10 mismatches print the unit, transaction, cycle, thread, fields, inputs
void report(const char *unit, std::size_t t, const char *against, const char *const field[], const uint32_t *want,
            const uint32_t *got, std::size_t n, const uint32_t *in, std::size_t n_in, uint32_t tid)
{
    const bool tid_ok = tid == t % 64;
    if (tid_ok && !std::memcmp(want, got, n * sizeof(uint32_t)))
        return;
    if (g_mismatches++ >= 10)
        return;
    std::printf("MISMATCH %s transaction %zu at cycle %llu, thread %zu, against %s:\n", unit, t,
                (unsigned long long)g_cycle, t % 64, against);
    if (!tid_ok)
        std::printf("  %-8s expected %zu rtl %u\n", "thread", t % 64, tid);
    for (std::size_t c = 0; c < n; c++)
        if (want[c] != got[c])
            std::printf("  %-8s expected %06x rtl %06x\n", field[c], want[c], got[c]);
    print_words("inputs", in, n_in);
}

const char *const NORMAL_FIELD[] = { "n.x", "n.y", "n.z" };
const char *const FRAME_FIELD[] = { "d^.x", "d^.y", "d^.z", "n^.x", "n^.y", "n^.z", "entering", "t_hat", "p.x", "p.y", "p.z" };
const char *const LIGHT_FIELD[] = { "o.x", "o.y", "o.z", "d.x", "d.y", "d.z", "tmin", "tmax", "active", "diff", "spec" };
const char *const LERP_FIELD[] = { "r" };
const char *const COLOUR_FIELD[] = { "r", "g", "b" };
const char *const SPAWN_FIELD[] = { "refl.o.x", "refl.o.y", "refl.o.z", "refl.d.x", "refl.d.y", "refl.d.z", "refl.w.r",
                                    "refl.w.g", "refl.w.b", "refl.active", "trans.o.x", "trans.o.y", "trans.o.z",
                                    "trans.d.x", "trans.d.y", "trans.d.z", "trans.w.r", "trans.w.g", "trans.w.b",
                                    "trans.active" };
const char *const ACCUM_FIELD[] = { "diffuse.r", "diffuse.g", "diffuse.b", "highlight.r", "highlight.g", "highlight.b" };
const char *const TEX_FIELD[] = { "x0", "x1", "fx", "y0", "y1", "fy", "r", "g", "b" };

template <typename T> bool load(const std::string &dir, const char *file, std::vector<T> &out, const char *why)
{
    bool present;
    if (!read_capture("tb_shade", dir + "/" + file, out, present))
        return false;
    if (!present || out.empty()) {
        std::printf("tb_shade: %s lacks %s vectors (%s)\n", dir.c_str(), file, why);
        return false;
    }
    return true;
}

template <typename T> const uint32_t *words_of(const T &x) { return reinterpret_cast<const uint32_t *>(&x); }

// a unit's stream: the transactions (in_words inputs, the outputs from word out_at on), those
// accepted and not yet handed over (in order)
template <typename T> struct stream {
    const char *unit;
    const char *const *field;
    std::size_t in_words, out_at;
    std::vector<T> tx;
    std::size_t captured = 0, next = 0;
    std::deque<std::size_t> in_flight;
    uint64_t checked = 0, vs_capture = 0, invented = 0, latency = 0, first_in = 0;

    bool offer(bool calm) const { return next < tx.size() && (calm || rnd() % 4 != 0); }
    // a cycle's handshake inputs: the next transaction offered (set puts its inputs on the ports,
    // its number modulo 64 is the thread id), ready for the output; in the gappy epochs (!calm)
    // with random gaps and back pressure
    template <typename P, typename Set> void drive(bool calm, P &valid, P &tid, P &ready, Set set) const
    {
        valid = offer(calm);
        if (valid) {
            set(tx[next]);
            tid = (P)(next % 64);
        }
        ready = calm || rnd() % 4 != 0;
    }
    void accept()
    {
        if (next == 0)
            first_in = g_cycle;
        in_flight.push_back(next++);
    }
    // the transaction a result belongs to, or SIZE_MAX for a result nobody asked for
    std::size_t hand_over()
    {
        if (in_flight.empty()) {
            invented++;
            return SIZE_MAX;
        }
        const std::size_t t = in_flight.front();
        in_flight.pop_front();
        if (!latency)
            latency = g_cycle - first_in;
        checked++;
        return t;
    }
    bool done() const { return next == tx.size() && in_flight.empty(); }
    // valid_o && ready_i: got holds the unit's outputs, tid its thread; compared with the C model's
    // and, for a captured transaction, with the recording's
    void result(const uint32_t *got, uint32_t tid)
    {
        const std::size_t t = hand_over();
        if (t == SIZE_MAX)
            return;
        T want = tx[t];
        model(want);
        const std::size_t n_out = sizeof(T) / sizeof(uint32_t) - out_at;
        report(unit, t, "C model", field, words_of(want) + out_at, got, n_out, words_of(want), in_words, tid);
        if (t < captured)
            report(unit, t, "capture", field, words_of(tx[t]) + out_at, got, n_out, words_of(want), in_words, tid),
                vs_capture++;
    }
};

} // namespace

int main(int argc, char **argv)
{
    std::size_t n = 100000;
    std::string capture;
    if (!parse_args(argc, argv, "tb_shade", n, capture))
        return 2;
    stream<normal_tx> nd{ "shade_rec_decode", NORMAL_FIELD, SHADE_NORMAL_WORDS + 1, SHADE_NORMAL_WORDS + 1 };
    stream<tex_tx> tx{ "tex_bilinear", TEX_FIELD, 9, 9 };
    stream<frame_tx> fr{ "rgs_frame", FRAME_FIELD, FRAME_IN, FRAME_IN };
    stream<light_tx> li{ "rgs_light", LIGHT_FIELD, LIGHT_IN, LIGHT_IN };
    stream<lerp_tx> le{ "rgs_lerp", LERP_FIELD, 5, 5 };
    stream<colour_tx> co{ "rgs_light_colour", COLOUR_FIELD, 3, 3 };
    stream<accum_tx> ac{ "rgs_add_light", ACCUM_FIELD, 11, 11 };
    stream<spawn_tx> sp{ "rgs_spawn", SPAWN_FIELD, SPAWN_IN, SPAWN_IN };
    if (!capture.empty()) {
        bool present; // a scene without vertex normals or textures records no normal or sample
        if (!read_capture("tb_shade", capture + "/shade_rec.hex", nd.tx, present) ||
            !read_capture("tb_shade", capture + "/tex.hex", tx.tx, present))
            return 2;
        if (!load(capture, "frame.hex", fr.tx, "no surface shaded?"))
            return 2;
        if (!load(capture, "light.hex", li.tx, "no surface lit?") ||
            !read_capture("tb_shade", capture + "/lerp.hex", le.tx, present))
            return 2;
        if (!load(capture, "colour.hex", co.tx, "no light?") || !read_capture("tb_shade", capture + "/accum.hex", ac.tx, present))
            return 2;
        if (!read_capture("tb_shade", capture + "/spawn.hex", sp.tx, present))
            return 2;
        le.captured = le.tx.size(), co.captured = co.tx.size(), ac.captured = ac.tx.size(), sp.captured = sp.tx.size();
        nd.captured = nd.tx.size(), tx.captured = tx.tx.size(), fr.captured = fr.tx.size(), li.captured = li.tx.size();
    }
    for (std::size_t i = 0; i < n; i++)
        nd.tx.push_back(random_normal()), tx.tx.push_back(random_tex()), fr.tx.push_back(random_frame()), li.tx.push_back(random_light()), le.tx.push_back(random_lerp()), co.tx.push_back(random_colour()),
            ac.tx.push_back(random_accum()), sp.tx.push_back(random_spawn());
    std::size_t missing = 0, folded = 0, wrapped = 0;
    for (const auto &x : nd.tx) {
        const uint64_t c = code_of(x);
        const int32_t cx = (int32_t)((uint32_t)c << 11) >> 11, cy = (int32_t)((uint32_t)(c >> SHADE_OCT_BITS) << 11) >> 11;
        missing += cx < -SHADE_OCT_ONE;
        folded += cx >= -SHADE_OCT_ONE && std::abs(cx) + std::abs(cy) > SHADE_OCT_ONE;
    }
    for (const auto &x : tx.tx) // the right or lower neighbour wrapped to 0
        wrapped += x.axes[1] == 0 || x.axes[4] == 0;

    VerilatedContext ctx;
    Vtb_shade top{ &ctx };
    top.rst_ni = 0, top.clk_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    // the memory: requests taken (sample, texel) in order; responses due at a cycle, in order
    std::size_t requests = 0;
    struct response { uint64_t due; uint32_t word; };
    std::deque<response> rsp;
    uint64_t bad_addr = 0, idle = 0;
    std::size_t lit = 0, spots = 0;
    for (const auto &x : li.tx)
        lit += x.diff != 0, spots += x.l[0] == 2 && x.diff != 0;
    for (; (!nd.done() || !tx.done() || !fr.done() || !li.done() || !le.done() || !co.done() || !ac.done() ||
                !sp.done()) && idle < 1000;
         g_cycle++) {
        const bool calm = (g_cycle / 1024) % 2 == 0;
        top.clk_i = 0;
        nd.drive(calm, top.n_valid_i, top.n_tid_i, top.n_ready_i, [&](const normal_tx &x) {
            top.n_code_i = code_of(x);
        });
        tx.drive(calm, top.t_valid_i, top.t_tid_i, top.t_ready_i, [&](const tex_tx &x) {
            top.t_s_i = x.s, top.t_t_i = x.t, top.t_width_i = x.width, top.t_height_i = x.height, top.t_addr_i = x.addr;
        });
        fr.drive(calm, top.f_valid_i, top.f_tid_i, top.f_ready_i, [&](const frame_tx &x) {
            for (int k = 0; k < 3; k++)
                put(top.f_o_i, k, x.o[k]), put(top.f_d_i, k, x.d[k]), put(top.f_n_i, k, x.n[k]);
            for (int k = 0; k < 9; k++)
                put(top.f_w2o_i, k, x.w2o[k]);
            top.f_t_i = x.t, top.f_cos_n_i = x.cos_n;
        });
        li.drive(calm, top.l_valid_i, top.l_tid_i, top.l_ready_i, [&](const light_tx &x) {
            top.l_type_i = x.l[0];
            for (int k = 0; k < 3; k++)
                put(top.l_lpos_i, k, x.l[4 + k]), put(top.l_ldir_i, k, x.l[7 + k]), put(top.l_p_i, k, x.p[k]),
                    put(top.l_n_i, k, x.n[k]), put(top.l_d_i, k, x.d[k]);
            top.l_cos_in_i = x.l[11], top.l_cos_out_i = x.l[12], top.l_eps_i = x.eps;
            top.l_sf_valid_i = x.valid, top.l_unlit_i = x.unlit, top.l_k_i = x.k;
        });
        le.drive(calm, top.e_valid_i, top.e_tid_i, top.e_ready_i, [&](const lerp_tx &x) {
            top.e_a_i = x.a, top.e_b_i = x.b, top.e_c_i = x.c, top.e_u_i = x.u, top.e_v_i = x.v;
        });
        co.drive(calm, top.c_valid_i, top.c_tid_i, top.c_ready_i, [&](const colour_tx &x) {
            for (int k = 0; k < 3; k++)
                put(top.c_colour_i, k, x.c[k]);
        });
        ac.drive(calm, top.a_valid_i, top.a_tid_i, top.a_ready_i, [&](const accum_tx &x) {
            top.a_diffuse_i = top.a_highlight_i = top.a_colour_i = 0;
            for (int k = 0; k < 3; k++)
                top.a_diffuse_i |= (uint64_t)x.diffuse[k] << 16 * k, top.a_highlight_i |= (uint64_t)x.highlight[k] << 16 * k,
                    top.a_colour_i |= (uint64_t)x.colour[k] << 16 * k;
            top.a_diff_i = x.diff, top.a_spec_i = x.spec;
        });
        sp.drive(calm, top.s_valid_i, top.s_tid_i, top.s_ready_i, [&](const spawn_tx &x) {
            top.s_eta_i = x.eta, top.s_kr_i = x.shader0 >> 13 & 0x1FFFu, top.s_kt_i = x.shader1 & 0x1FFFu;
            top.s_weight_i = top.s_tint_i = top.s_base_i = 0;
            for (int k = 0; k < 3; k++) {
                top.s_weight_i |= (uint64_t)x.weight[k] << 16 * k, top.s_tint_i |= (uint64_t)x.tint[k] << 16 * k,
                    top.s_base_i |= (uint64_t)x.base[k] << 16 * k;
                put(top.s_o_i, k, x.o[k]), put(top.s_d_i, k, x.d[k]), put(top.s_n_i, k, x.n[k]);
            }
            top.s_eps_i = x.eps, top.s_t_hat_i = x.t_hat, top.s_entering_i = x.entering;
        });
        top.t_req_ready_i = calm || rnd() % 4 != 0;
        top.t_rsp_valid_i = !rsp.empty() && rsp.front().due <= g_cycle;
        top.t_rsp_data_i = top.t_rsp_valid_i ? rsp.front().word : 0;
        top.eval();
        bool any = false;
        if (top.n_valid_o && top.n_ready_i) {
            const uint32_t got[3] = { get(top.n_o, 0), get(top.n_o, 1), get(top.n_o, 2) };
            nd.result(got, top.n_tid_o);
            any = true;
        }
        if (top.f_valid_o && top.f_ready_i) {
            uint32_t got[11];
            for (int k = 0; k < 3; k++)
                got[k] = get(top.f_d_o, k), got[3 + k] = get(top.f_n_o, k), got[8 + k] = get(top.f_p_o, k);
            got[6] = top.f_entering_o, got[7] = top.f_t_hat_o;
            fr.result(got, top.f_tid_o);
            any = true;
        }
        if (top.l_valid_o && top.l_ready_i) {
            uint32_t got[11];
            for (int k = 0; k < 3; k++)
                got[k] = get(top.l_o_o, k), got[3 + k] = get(top.l_d_o, k);
            got[6] = top.l_tmin_o, got[7] = top.l_tmax_o, got[8] = top.l_active_o, got[9] = top.l_diff_o,
            got[10] = top.l_spec_o;
            li.result(got, top.l_tid_o);
            any = true;
        }
        if (top.e_valid_o && top.e_ready_i) {
            const uint32_t got = top.e_r_o;
            le.result(&got, top.e_tid_o);
            any = true;
        }
        if (top.s_valid_o && top.s_ready_i) {
            uint32_t got[20];
            for (int k = 0; k < 3; k++) {
                got[k] = get(top.s_r_o_o, k), got[3 + k] = get(top.s_r_d_o, k);
                got[6 + k] = (uint32_t)(top.s_r_w_o >> 16 * k & 0xFFFFu);
                got[10 + k] = get(top.s_t_o_o, k), got[13 + k] = get(top.s_t_d_o, k);
                got[16 + k] = (uint32_t)(top.s_t_w_o >> 16 * k & 0xFFFFu);
            }
            got[9] = top.s_r_active_o, got[19] = top.s_t_active_o;
            sp.result(got, top.s_tid_o);
            any = true;
        }
        if (top.c_valid_o && top.c_ready_i) {
            uint32_t got[3];
            for (int k = 0; k < 3; k++)
                got[k] = (uint32_t)(top.c_q_o >> 16 * k & 0xFFFFu);
            co.result(got, top.c_tid_o);
            any = true;
        }
        if (top.a_valid_o && top.a_ready_i) {
            uint32_t got[6];
            for (int k = 0; k < 3; k++)
                got[k] = (uint32_t)(top.a_diffuse_o >> 16 * k & 0xFFFFu), got[3 + k] = (uint32_t)(top.a_highlight_o >> 16 * k & 0xFFFFu);
            ac.result(got, top.a_tid_o);
            any = true;
        }
        if (top.t_valid_o && top.t_ready_i) {
            // the RTL's axes are inside: its outputs are the C's axes (checked against the recording's)
            // and its sample
            uint32_t got[9] = {};
            if (!tx.in_flight.empty()) {
                tex_tx c = tx.tx[tx.in_flight.front()];
                model(c);
                std::memcpy(got, c.axes, sizeof c.axes);
            }
            for (int k = 0; k < 3; k++)
                got[6 + k] = (uint32_t)(top.t_rgb_o >> (16 * k) & 0xFFFFu);
            tx.result(got, top.t_tid_o);
            any = true;
        }
        if (top.t_rsp_valid_i && top.t_rsp_ready_o)
            rsp.pop_front();
        if (top.t_req_valid_o && top.t_req_ready_i) {
            // the request's sample: the (requests / 4)th accepted, in order
            const std::size_t s = requests / 4;
            const int j = (int)(requests % 4);
            requests++;
            if (s >= tx.next) {
                bad_addr++;
                std::printf("MISMATCH tex_bilinear request %zu at cycle %llu: no sample to read for\n", requests - 1,
                            (unsigned long long)g_cycle);
            } else {
                tex_tx want = tx.tx[s];
                model(want);
                const uint32_t a = texel_addr(want, j);
                if (top.t_req_addr_o != a && bad_addr++ < 10)
                    std::printf("MISMATCH tex_bilinear transaction %zu at cycle %llu, thread %zu: texel %d address "
                                "expected %08x rtl %08x\n",
                                s, (unsigned long long)g_cycle, s % 64, j, a, top.t_req_addr_o);
                const uint64_t after = calm ? 1 : 1 + rnd() % 4;
                const uint64_t due = std::max<uint64_t>(g_cycle + after, rsp.empty() ? 0 : rsp.back().due);
                rsp.push_back({ due, want.texel[j] });
            }
        }
        if (top.n_valid_i && top.n_ready_o)
            nd.accept();
        if (top.t_valid_i && top.t_ready_o)
            tx.accept();
        if (top.f_valid_i && top.f_ready_o)
            fr.accept();
        if (top.l_valid_i && top.l_ready_o)
            li.accept();
        if (top.e_valid_i && top.e_ready_o)
            le.accept();
        if (top.c_valid_i && top.c_ready_o)
            co.accept();
        if (top.a_valid_i && top.a_ready_o)
            ac.accept();
        if (top.s_valid_i && top.s_ready_o)
            sp.accept();
        idle = any ? 0 : idle + 1;
        top.clk_i = 1;
        top.eval();
    }
    const bool lost = !nd.done() || !tx.done() || !fr.done() || !li.done() || !le.done() || !co.done() || !ac.done() || !sp.done();
    std::printf("tb_shade: shade_rec_decode %llu normals checked (%zu captured, %llu also against the capture; %zu missing, "
                "%zu folded), latency %llu cycles\n",
                (unsigned long long)nd.checked, nd.captured, (unsigned long long)nd.vs_capture, missing, folded,
                (unsigned long long)nd.latency);
    std::printf("tb_shade: tex_bilinear %llu samples checked (%zu captured, %llu also against the capture; %zu with a "
                "neighbour wrapped to 0), %zu texel reads, latency %llu cycles\n",
                (unsigned long long)tx.checked, tx.captured, (unsigned long long)tx.vs_capture, wrapped, requests,
                (unsigned long long)tx.latency);
    std::printf("tb_shade: rgs_frame %llu frames checked (%zu captured, %llu also against the capture), latency %llu "
                "cycles\n",
                (unsigned long long)fr.checked, fr.captured, (unsigned long long)fr.vs_capture,
                (unsigned long long)fr.latency);
    std::printf("tb_shade: rgs_light %llu light-surface pairs checked (%zu captured, %llu also against the capture; %zu "
                "lit, %zu by a spot), latency %llu cycles\n",
                (unsigned long long)li.checked, li.captured, (unsigned long long)li.vs_capture, lit, spots,
                (unsigned long long)li.latency);
    std::printf("tb_shade: rgs_lerp %llu components checked (%zu captured, %llu also against the capture), latency %llu "
                "cycles\n",
                (unsigned long long)le.checked, le.captured, (unsigned long long)le.vs_capture,
                (unsigned long long)le.latency);
    std::printf("tb_shade: rgs_light_colour %llu colours (%zu captured, %llu also against the capture), latency %llu cycles; "
                "rgs_add_light %llu accumulations (%zu captured, %llu also against the capture), latency %llu cycles\n",
                (unsigned long long)co.checked, co.captured, (unsigned long long)co.vs_capture,
                (unsigned long long)co.latency, (unsigned long long)ac.checked, ac.captured,
                (unsigned long long)ac.vs_capture, (unsigned long long)ac.latency);
    std::size_t tir = 0, refracted = 0;
    for (const auto &x : sp.tx)
        tir += x.eta != F24_ONE && x.t_o[0] == x.r_o[0] && x.t_d[0] == x.r_d[0],
            refracted += x.eta != F24_ONE && x.t_d[0] != x.d[0];
    std::printf("tb_shade: rgs_spawn %llu surfaces checked (%zu captured, %llu also against the capture; %zu refracted, %zu "
                "totally reflected), latency %llu cycles\n",
                (unsigned long long)sp.checked, sp.captured, (unsigned long long)sp.vs_capture, refracted, tir,
                (unsigned long long)sp.latency);
    const bool invented = nd.invented || tx.invented || fr.invented || li.invented || le.invented || co.invented ||
                          ac.invented || sp.invented;
    std::printf("tb_shade: %llu cycles, %llu mismatches, %llu wrong addresses%s%s\n", (unsigned long long)g_cycle,
                (unsigned long long)g_mismatches, (unsigned long long)bad_addr, lost ? ", RESULTS LOST" : "",
                invented ? ", RESULTS INVENTED" : "");
    return g_mismatches || bad_addr || lost || invented ? 1 : 0;
}
