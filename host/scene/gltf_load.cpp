// glTF 2.0 loader behind scene.h (tinygltf from Debian, route A: header + -ltinygltf).
// Every accessor read is bounds-checked; malformed files give one-line errors, unsupported
// features (Draco, meshopt, KTX2, points and lines) one-line warnings, never a crash.
#include "scene.h"
#include "gltf_util.h"
#include "huge_pages.h"

#include <tiny_gltf.h>
#include <algorithm>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace {

using gltf_util::ends_with;
using gltf_util::first_line;
using gltf_util::set_error;

struct load_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Room in v for `extra` more elements before a loop of push_backs: one allocation instead of the
// doublings' copies (the gallery's 1.5 M indices; every copy touches fresh pages), and at least
// doubling, so that a mesh of many primitives still grows in amortized O(1).
template <class V> void reserve_more(V &v, size_t extra)
{
    if (v.capacity() - v.size() < extra)
        v.reserve(std::max(v.size() + extra, 2 * v.capacity()));
}

// The extensions the loader implements: a file may require them.
const char *const implemented_extensions[] = { "KHR_lights_punctual",     "KHR_materials_transmission",
                                               "KHR_materials_ior",       "KHR_materials_emissive_strength",
                                               "KHR_mesh_quantization",   "EXT_mesh_gpu_instancing",
                                               "KHR_texture_transform",   "KHR_materials_unlit" };

template <size_t N> bool listed(const char *const (&list)[N], const std::string &name)
{
    for (const char *x : list)
        if (name == x)
            return true;
    return false;
}

// The glTF specification: a loader must refuse a file that requires an extension it lacks.
void check_required(const std::vector<std::string> &required)
{
    for (const std::string &e : required)
        if (!listed(implemented_extensions, e))
            throw load_error("requires extension " + e + ", which saarcor does not implement");
}


template <typename T> T *alloc_array(size_t n)
{
    if (n == 0)
        return nullptr;
    T *p = static_cast<T *>(std::calloc(n, sizeof(T)));
    if (!p)
        throw std::bad_alloc();
    return p;
}

// The scene's copy of v (malloc'd, as scene_free frees it), in huge pages where large.
template <class V> typename V::value_type *copy_array(const V &v)
{
    using T = typename V::value_type;
    if (v.empty())
        return nullptr;
    T *p = static_cast<T *>(huge_pages_malloc(v.size() * sizeof(T)));
    if (!p)
        throw std::bad_alloc();
    std::memcpy(p, v.data(), v.size() * sizeof(T));
    return p;
}

// A mesh array while it grows: one malloc'd block (huge_pages_realloc: large ones in huge pages)
// that the scene takes over when the mesh is done (release(); scene_free frees it) instead of a
// copy. The loader runs on one thread before any other work, and its fresh pages are most of its
// time: each first touch of a 4 KB page is a costly trap on this project's VM (the gallery's load
// took 8,800 of them). T is a plain number type.
template <class T> class mesh_array {
  public:
    using value_type = T;
    mesh_array() = default;
    mesh_array(const mesh_array &o) { append(o.p_, o.n_); }
    mesh_array(mesh_array &&o) noexcept : p_(o.p_), n_(o.n_), cap_(o.cap_) { o.p_ = nullptr, o.n_ = o.cap_ = 0; }
    mesh_array &operator=(mesh_array o) noexcept
    {
        std::swap(p_, o.p_), std::swap(n_, o.n_), std::swap(cap_, o.cap_);
        return *this;
    }
    ~mesh_array() { std::free(p_); }
    size_t size() const { return n_; }
    size_t capacity() const { return cap_; }
    bool empty() const { return n_ == 0; }
    T *data() { return p_; }
    const T *data() const { return p_; }
    T &operator[](size_t i) { return p_[i]; }
    const T &operator[](size_t i) const { return p_[i]; }
    const T *begin() const { return p_; }
    const T *end() const { return p_ + n_; }
    void reserve(size_t c)
    {
        if (c <= cap_)
            return;
        T *q = c <= SIZE_MAX / sizeof(T) ? static_cast<T *>(huge_pages_realloc(p_, c * sizeof(T))) : nullptr;
        if (!q)
            throw std::bad_alloc();
        p_ = q, cap_ = c;
    }
    void resize(size_t n, T v = T())
    {
        grow(n);
        for (size_t i = n_; i < n; i++)
            p_[i] = v;
        n_ = n;
    }
    void push_back(T v)
    {
        grow(n_ + 1);
        p_[n_++] = v;
    }
    void append(const void *v, size_t n) // n elements' bytes: v need not be aligned
    {
        grow(n_ + n);
        if (n)
            std::memcpy(p_ + n_, v, n * sizeof(T));
        n_ += n;
    }
    // The block, for the scene to own (nullptr if empty); the array is empty after.
    T *release()
    {
        T *p = n_ ? p_ : nullptr;
        if (!n_)
            std::free(p_);
        p_ = nullptr, n_ = cap_ = 0;
        return p;
    }

  private:
    void grow(size_t n) // at least doubling, as std::vector: amortized O(1) push_back
    {
        if (n > cap_)
            reserve(std::max(n, 2 * cap_));
    }
    T *p_ = nullptr;
    size_t n_ = 0, cap_ = 0;
};

class Loader {
  public:
    Loader(const tinygltf::Model &m, const std::string &path, scene *out) : m_(m), path_(path), s_(out) {}

    void run()
    {
        check_extensions();
        note_ignored_textures();
        load_materials();
        load_textures();
        load_meshes();
        load_cameras_and_lights();
        load_nodes();
        load_skins();
        load_animations();
        load_roots();
        keep_ignored();
        if (scene_evaluate(s_, 0.0, 0) != 0)
            throw std::bad_alloc();
    }

  private:
    const tinygltf::Model &m_;
    std::string path_;
    scene *s_;
    std::vector<uint32_t> image_to_texture_;
    std::vector<std::string> ignored_;
    size_t instance_rows_ = 0; // EXT_mesh_gpu_instancing rows of all nodes so far

    void warn(const std::string &msg)
    {
        std::fprintf(stderr, "saarcor: warning: %s: %s\n", path_.c_str(), msg.c_str());
        s_->warnings++;
    }

    [[noreturn]] void fail(const std::string &msg) { throw load_error(msg); }

    // A feature of the file that changes its appearance and is not implemented: one warning and
    // one entry of scene.ignored however often it occurs.
    void ignore(const std::string &feature)
    {
        for (const std::string &f : ignored_)
            if (f == feature)
                return;
        ignored_.push_back(feature);
        warn(feature + " is not supported and is ignored");
    }

    void keep_ignored()
    {
        s_->ignored = alloc_array<char[64]>(ignored_.size());
        for (const std::string &f : ignored_)
            std::snprintf(s_->ignored[s_->n_ignored++], sizeof s_->ignored[0], "%s", f.c_str());
    }

    void check_extensions()
    {
        check_required(m_.extensionsRequired); // scene_load_gltf checked the JSON already: a safety net
        for (const std::string &e : m_.extensionsUsed) {
            if (!listed(implemented_extensions, e))
                ignore(e);
        }
    }

    // The material textures the shader does not sample.
    void note_ignored_textures()
    {
        for (const tinygltf::Material &g : m_.materials) {
            if (g.normalTexture.index >= 0)
                ignore("normalTexture");
            if (g.occlusionTexture.index >= 0)
                ignore("occlusionTexture");
            if (g.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0)
                ignore("metallicRoughnessTexture");
        }
    }

    // ---- accessors ----------------------------------------------------------------------

    const tinygltf::Accessor &accessor(int index, const char *what)
    {
        if (index < 0 || (size_t)index >= m_.accessors.size())
            fail(std::string(what) + ": accessor index " + std::to_string(index) + " out of range");
        return m_.accessors[(size_t)index];
    }

    static int components(int type)
    {
        switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
        }
    }

    static double read_component(const unsigned char *p, int ctype, bool normalized)
    {
        switch (ctype) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
        case TINYGLTF_COMPONENT_TYPE_BYTE: { double v = (signed char)p[0]; return normalized ? std::fmax(v / 127.0, -1.0) : v; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); return normalized ? v / 65535.0 : v; }
        case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t v; std::memcpy(&v, p, 2); return normalized ? std::fmax(v / 32767.0, -1.0) : v; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); return v; }
        default: return NAN;
        }
    }

    // The first of `count` elements of `ncomp` components in a buffer view and their stride,
    // bounds-checked: every read of an accessor's elements goes through here.
    struct view_span {
        const unsigned char *base;
        size_t stride;
    };
    view_span view(int view_index, size_t offset, size_t count, int ctype, int ncomp, const std::string &what)
    {
        if (view_index < 0 || (size_t)view_index >= m_.bufferViews.size())
            fail(what + ": buffer view out of range");
        const tinygltf::BufferView &bv = m_.bufferViews[(size_t)view_index];
        if (bv.buffer < 0 || (size_t)bv.buffer >= m_.buffers.size())
            fail(what + ": buffer out of range");
        const std::vector<unsigned char> &data = m_.buffers[(size_t)bv.buffer].data;
        const int csize = tinygltf::GetComponentSizeInBytes((uint32_t)ctype);
        if (csize <= 0)
            fail(what + ": bad component type " + std::to_string(ctype));
        const size_t elem = (size_t)csize * (size_t)ncomp;
        const size_t stride = bv.byteStride ? bv.byteStride : elem;
        if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
            fail(what + ": buffer view exceeds its buffer");
        if (count && (offset > bv.byteLength || (count - 1) > (bv.byteLength - offset) / stride ||
                      (count - 1) * stride + elem > bv.byteLength - offset))
            fail(what + ": accessor exceeds its buffer view");
        return { data.data() + bv.byteOffset + offset, stride };
    }

    // Reads `count` elements of `ncomp` components from a buffer view, bounds-checked.
    void read_view(int view_index, size_t offset, size_t count, int ctype, int ncomp, bool normalized,
                   const std::string &what, double *out)
    {
        const view_span v = view(view_index, offset, count, ctype, ncomp, what);
        const int csize = tinygltf::GetComponentSizeInBytes((uint32_t)ctype);
        for (size_t i = 0; i < count; i++)
            for (int c = 0; c < ncomp; c++)
                out[i * (size_t)ncomp + (size_t)c] = read_component(v.base + i * v.stride + (size_t)c * (size_t)csize, ctype, normalized);
    }

    // Accessor `index` as read() checks it: its components per element.
    int checked_components(const tinygltf::Accessor &a, int want_type, const std::string &what)
    {
        const int nc = components(a.type);
        if (a.type != want_type || nc == 0)
            fail(what + ": accessor has the wrong type");
        if (a.count > (1u << 28))
            fail(what + ": accessor too large");
        return nc;
    }

    // The elements of accessor a, if they are stored one after the other without sparse
    // substitution, as components of type ctype (nullptr if not, or if a is not of that type):
    // such accessors (most files' positions, normals and indices) are read straight from the
    // buffer, with read()'s checks and values, without its vector of doubles.
    const unsigned char *packed(const tinygltf::Accessor &a, int want_type, int ctype, const std::string &what)
    {
        const int nc = checked_components(a, want_type, what);
        if (a.componentType != ctype || a.sparse.isSparse || a.bufferView < 0)
            return nullptr;
        const view_span v = view(a.bufferView, a.byteOffset, a.count, a.componentType, nc, what);
        const size_t elem = (size_t)tinygltf::GetComponentSizeInBytes((uint32_t)ctype) * (size_t)nc;
        return v.stride == elem ? v.base : nullptr;
    }

    // Accessor `index`'s components appended to dst as floats, (float) of read()'s values; returns
    // how many. Packed floats are copied as they are, the same bits (a float converts to double
    // and back exactly).
    size_t append_floats(int index, int want_type, const std::string &what, mesh_array<float> &dst)
    {
        const tinygltf::Accessor &a = accessor(index, what.c_str());
        if (const unsigned char *p = packed(a, want_type, TINYGLTF_COMPONENT_TYPE_FLOAT, what)) {
            const size_t n = (size_t)a.count * (size_t)components(want_type);
            reserve_more(dst, n);
            dst.append(p, n);
            return n;
        }
        const std::vector<double> v = read(index, want_type, what);
        reserve_more(dst, v.size());
        for (double x : v)
            dst.push_back((float)x);
        return v.size();
    }

    // Accessor as doubles, ncomp per element, with sparse substitution applied.
    std::vector<double> read(int index, int want_type, const std::string &what)
    {
        const tinygltf::Accessor &a = accessor(index, what.c_str());
        const int nc = checked_components(a, want_type, what);
        std::vector<double> v((size_t)a.count * (size_t)nc, 0.0);
        if (a.bufferView >= 0)
            read_view(a.bufferView, a.byteOffset, a.count, a.componentType, nc, a.normalized, what, v.data());
        if (a.sparse.isSparse) {
            const size_t n = (size_t)a.sparse.count;
            if (n > a.count)
                fail(what + ": sparse count exceeds accessor count");
            std::vector<double> idx(n), val(n * (size_t)nc);
            read_view(a.sparse.indices.bufferView, a.sparse.indices.byteOffset, n, a.sparse.indices.componentType, 1,
                      false, what + " (sparse indices)", idx.data());
            read_view(a.sparse.values.bufferView, a.sparse.values.byteOffset, n, a.componentType, nc, a.normalized,
                      what + " (sparse values)", val.data());
            for (size_t i = 0; i < n; i++) {
                if (!(idx[i] >= 0 && idx[i] < (double)a.count))
                    fail(what + ": sparse index out of range");
                for (int c = 0; c < nc; c++)
                    v[(size_t)idx[i] * (size_t)nc + (size_t)c] = val[i * (size_t)nc + (size_t)c];
            }
        }
        return v;
    }

    // The same, failing on NaN/Inf (positions, transforms, key times).
    std::vector<double> read_finite(int index, int want_type, const std::string &what)
    {
        std::vector<double> v = read(index, want_type, what);
        require_finite(v.data(), v.size(), want_type, what);
        return v;
    }

    // Fails on the first NaN/Inf of v[0..n), components of elements of type want_type.
    template <class T> void require_finite(const T *v, size_t n, int want_type, const std::string &what)
    {
        for (size_t i = 0; i < n; i++)
            if (!std::isfinite(v[i]))
                fail(what + ": non-finite value at element " + std::to_string(i / (size_t)components(want_type)));
    }

    // ---- materials and textures ---------------------------------------------------------

    void load_materials()
    {
        s_->n_materials = (uint32_t)m_.materials.size() + 1;
        s_->materials = alloc_array<scene_material>(s_->n_materials);
        for (uint32_t i = 0; i < s_->n_materials; i++) {
            scene_material &d = s_->materials[i];
            d = scene_material{};
            for (int c = 0; c < 4; c++)
                d.base_color[c] = c < 3 ? 0.8f : 1.0f;
            d.base_color_texture = d.emissive_texture = SCENE_NONE;
            d.alpha_cutoff = 0.5f;
            d.metallic = 0.0f;
            d.roughness = 1.0f;
            d.ior = 1.5f;
            if (i == 0)
                continue;
            const tinygltf::Material &g = m_.materials[i - 1];
            const auto &pbr = g.pbrMetallicRoughness;
            for (int c = 0; c < 4 && c < (int)pbr.baseColorFactor.size(); c++)
                d.base_color[c] = (float)pbr.baseColorFactor[(size_t)c];
            d.metallic = (float)pbr.metallicFactor;
            d.roughness = (float)pbr.roughnessFactor;
            const std::string what = "material " + std::to_string(i - 1);
            d.base_color_texture = (uint32_t)pbr.baseColorTexture.index; // resolved in load_textures
            d.texcoord_set = texture_mapping(pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions,
                                             what + " base colour texture", d.base_uv);
            d.emissive_texture = (uint32_t)g.emissiveTexture.index;
            d.emissive_texcoord = texture_mapping(g.emissiveTexture.texCoord, g.emissiveTexture.extensions,
                                                  what + " emissive texture", d.emissive_uv);
            d.unlit = g.extensions.count("KHR_materials_unlit") != 0;
            d.alpha = g.alphaMode == "MASK" ? ALPHA_MASK : g.alphaMode == "BLEND" ? ALPHA_BLEND : ALPHA_OPAQUE;
            d.alpha_cutoff = (float)g.alphaCutoff;
            for (int c = 0; c < 3 && c < (int)g.emissiveFactor.size(); c++)
                d.emissive[c] = (float)g.emissiveFactor[(size_t)c];
            d.double_sided = g.doubleSided;
            auto es = g.extensions.find("KHR_materials_emissive_strength");
            if (es != g.extensions.end() && es->second.Has("emissiveStrength"))
                for (float &e : d.emissive)
                    e *= (float)es->second.Get("emissiveStrength").GetNumberAsDouble();
            auto tr = g.extensions.find("KHR_materials_transmission");
            if (tr != g.extensions.end() && tr->second.Has("transmissionFactor"))
                d.transmission = (float)tr->second.Get("transmissionFactor").GetNumberAsDouble();
            auto ior = g.extensions.find("KHR_materials_ior");
            if (ior != g.extensions.end() && ior->second.Has("ior"))
                d.ior = (float)ior->second.Get("ior").GetNumberAsDouble();
        }
    }

    static double number(const tinygltf::Value &v, const char *key, int i, double fallback)
    {
        if (!v.Has(key))
            return fallback;
        const tinygltf::Value &x = i < 0 ? v.Get(key) : v.Get(key).Get(i);
        return x.IsNumber() ? x.GetNumberAsDouble() : fallback;
    }

    // The TEXCOORD_n set (0 or 1) and KHR_texture_transform of a texture reference (whose
    // texCoord overrides the reference's).
    uint32_t texture_mapping(int texcoord, const tinygltf::ExtensionMap &ext, const std::string &what, scene_uv_map &uv)
    {
        auto tt = ext.find("KHR_texture_transform");
        if (tt != ext.end()) {
            const tinygltf::Value &v = tt->second;
            uv = scene_uv_map{ 1, { number(v, "offset", 0, 0), number(v, "offset", 1, 0) }, number(v, "rotation", -1, 0),
                               { number(v, "scale", 0, 1), number(v, "scale", 1, 1) } };
            texcoord = (int)number(v, "texCoord", -1, texcoord);
        }
        if (texcoord < 0 || texcoord > 1) {
            warn(what + " uses TEXCOORD_" + std::to_string(texcoord) + ": only TEXCOORD_0 and TEXCOORD_1 are loaded");
            return 0;
        }
        return (uint32_t)texcoord;
    }

    // The scene texture of glTF texture index ti (SCENE_NONE if none or unusable).
    uint32_t resolve_texture(uint32_t ti)
    {
        if (ti >= m_.textures.size())
            return SCENE_NONE;
        const int src = m_.textures[ti].source;
        if (src >= 0 && (size_t)src < image_to_texture_.size())
            return image_to_texture_[(size_t)src];
        warn("texture " + std::to_string(ti) + " has no usable image (KTX2/BasisU?) and is skipped");
        return SCENE_NONE;
    }

    void load_textures()
    {
        image_to_texture_.assign(m_.images.size(), SCENE_NONE);
        std::vector<scene_texture> tex;
        for (size_t i = 0; i < m_.images.size(); i++) {
            const tinygltf::Image &im = m_.images[i];
            const size_t n = (size_t)im.width * (size_t)im.height;
            const int bytes = im.bits == 16 ? 2 : 1;
            if (im.width <= 0 || im.height <= 0 || im.component < 1 || im.component > 4 ||
                im.image.size() < n * (size_t)im.component * (size_t)bytes) {
                warn("image " + std::to_string(i) + " could not be decoded and is skipped");
                continue;
            }
            scene_texture t{ im.width, im.height, alloc_array<uint8_t>(n * 4) };
            for (size_t p = 0; p < n; p++)
                for (int c = 0; c < 4; c++) {
                    const int src = im.component >= 3 ? (c < im.component ? c : -1) : (c < 3 ? 0 : (im.component == 2 ? 1 : -1));
                    const size_t at = (p * (size_t)im.component + (size_t)(src < 0 ? 0 : src)) * (size_t)bytes;
                    const uint8_t v = bytes == 2 ? im.image[at + 1] : im.image[at]; // little-endian high byte
                    t.rgba[p * 4 + (size_t)c] = src < 0 ? 255 : v;
                }
            image_to_texture_[i] = (uint32_t)tex.size();
            tex.push_back(t);
        }
        s_->n_textures = (uint32_t)tex.size();
        s_->textures = copy_array(tex);
        for (uint32_t i = 1; i < s_->n_materials; i++) {
            scene_material &d = s_->materials[i];
            d.base_color_texture = resolve_texture(d.base_color_texture);
            d.emissive_texture = resolve_texture(d.emissive_texture);
        }
    }

    // ---- meshes --------------------------------------------------------------------------

    struct mesh_build {
        mesh_array<float> pos, nrm, uv, uv1, rgb;
        mesh_array<uint32_t> idx, mat;
        mesh_array<uint16_t> joints;  // 4 per vertex (JOINTS_0)
        mesh_array<float> weights;    // 4 per vertex (WEIGHTS_0)
        bool any_normals = false, any_uv = false, any_uv1 = false, any_rgb = false, any_skin = false;
        uint32_t n_targets = 0;
        std::vector<std::pair<uint32_t, std::vector<std::vector<double>>>> prim_targets; // first vertex, deltas
    };

    static mesh_array<uint32_t> triangulate(const mesh_array<uint32_t> &v, int mode)
    {
        if (mode == TINYGLTF_MODE_TRIANGLES)
            return v;
        mesh_array<uint32_t> t;
        for (size_t i = 2; i < v.size(); i++) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
                for (size_t k : { i - 2 + i % 2, i - 1 - i % 2, i }) // odd i: i - 1, i - 2, i; even: i - 2, i - 1, i
                    t.push_back(v[k]);
            else
                for (size_t k : { (size_t)0, i - 1, i })
                    t.push_back(v[k]);
        }
        return t;
    }

    // JOINTS_0 / WEIGHTS_0 of a primitive (zero weights where absent: such vertices are not
    // skinned). The joints are checked against the skin in load_skins, which knows it.
    void add_influences(mesh_build &b, const tinygltf::Primitive &p, size_t nv, const std::string &what)
    {
        auto j = p.attributes.find("JOINTS_0"), w = p.attributes.find("WEIGHTS_0");
        if (j == p.attributes.end() || w == p.attributes.end()) {
            if (b.any_skin) { // empty until a primitive has influences, as fill()'s attributes
                b.joints.resize(b.pos.size() / 3 * 4, 0);
                b.weights.resize(b.pos.size() / 3 * 4, 0.0f);
            }
            return;
        }
        if (p.attributes.count("JOINTS_1"))
            warn(what + ": JOINTS_1/WEIGHTS_1 (more than 4 influences per vertex) are ignored");
        const int jt = accessor(j->second, (what + " JOINTS_0").c_str()).componentType;
        if (jt != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && jt != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
            fail(what + ": JOINTS_0 must be unsigned bytes or shorts");
        const std::vector<double> jv = read_finite(j->second, TINYGLTF_TYPE_VEC4, what + " JOINTS_0");
        const std::vector<double> wv = read_finite(w->second, TINYGLTF_TYPE_VEC4, what + " WEIGHTS_0");
        if (jv.size() != nv * 4 || wv.size() != nv * 4)
            fail(what + ": JOINTS_0/WEIGHTS_0 count differs from POSITION count");
        b.joints.resize((b.pos.size() / 3 - nv) * 4, 0);
        b.weights.resize((b.pos.size() / 3 - nv) * 4, 0.0f);
        for (size_t i = 0; i < jv.size(); i++) {
            b.joints.push_back((uint16_t)jv[i]);
            b.weights.push_back((float)std::fmax(wv[i], 0.0)); // negative weights are invalid glTF
        }
        b.any_skin = true;
    }

    void add_primitive(mesh_build &b, const tinygltf::Primitive &p, const std::string &what)
    {
        if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            p.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            ignore(p.mode == TINYGLTF_MODE_POINTS ? "points"
                   : p.mode >= TINYGLTF_MODE_LINE && p.mode <= TINYGLTF_MODE_LINE_STRIP ? "lines"
                   : "primitive mode " + std::to_string(p.mode));
            return;
        }
        if (p.extensions.count("KHR_draco_mesh_compression")) {
            warn(what + ": Draco-compressed primitive skipped");
            return;
        }
        auto pos_it = p.attributes.find("POSITION");
        if (pos_it == p.attributes.end())
            fail(what + ": primitive has no POSITION");
        const size_t at = b.pos.size(); // a float is finite iff the double it came from is
        const size_t nv = append_floats(pos_it->second, TINYGLTF_TYPE_VEC3, what + " POSITION", b.pos) / 3;
        require_finite(b.pos.data() + at, 3 * nv, TINYGLTF_TYPE_VEC3, what + " POSITION");
        const uint32_t base = (uint32_t)(at / 3);
        if (at / 3 + nv > (1u << 30))
            fail(what + ": too many vertices");
        // An attribute's array stays empty until a primitive has it (then the earlier vertices
        // get the default): a mesh without texture coordinates fills none.
        auto fill = [&](const char *name, int type, int nc, mesh_array<float> &dst, bool &any) {
            auto it = p.attributes.find(name);
            if (it == p.attributes.end()) {
                if (any)
                    dst.resize((size_t)(base + nv) * (size_t)nc, 0.0f);
                return;
            }
            dst.resize((size_t)base * (size_t)nc, 0.0f);
            if (append_floats(it->second, type, what + " " + name, dst) != nv * (size_t)nc)
                fail(what + ": " + name + " count differs from POSITION count");
            size_t bad = 0;
            for (size_t i = (size_t)base * (size_t)nc; i < dst.size(); i++) {
                bad += !std::isfinite(dst[i]);
                dst[i] = std::isfinite(dst[i]) ? dst[i] : 0.0f; // zero normal: shade with the geometric one
            }
            if (bad)
                warn(what + ": " + std::to_string(bad) + " non-finite " + name + " components replaced by 0");
            any = true;
        };
        fill("NORMAL", TINYGLTF_TYPE_VEC3, 3, b.nrm, b.any_normals);
        fill("TEXCOORD_0", TINYGLTF_TYPE_VEC2, 2, b.uv, b.any_uv);
        fill("TEXCOORD_1", TINYGLTF_TYPE_VEC2, 2, b.uv1, b.any_uv1);
        add_colours(b, p, nv, what);
        add_influences(b, p, nv, what);

        // A triangle list's indices go straight into b.idx, the base added as they are read (one
        // pass over fresh memory); a strip's or a fan's into a list of their own, triangulated.
        const bool list = p.mode == TINYGLTF_MODE_TRIANGLES;
        const size_t start = b.idx.size();
        mesh_array<uint32_t> strip;
        mesh_array<uint32_t> &idx = list ? b.idx : strip;
        const size_t first = idx.size();
        const uint32_t off = list ? base : 0;
        if (p.indices >= 0) {
            const tinygltf::Accessor &a = accessor(p.indices, (what + " indices").c_str());
            if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                fail(what + ": indices must be unsigned integers");
            auto put = [&](size_t i, double x) { // indexed stores: push_back's checks cost as much as the rest
                if (!(x >= 0 && x < (double)nv))
                    fail(what + ": vertex index " + std::to_string((long long)x) + " out of range (" +
                         std::to_string(nv) + " vertices)");
                idx[first + i] = off + (uint32_t)x;
            };
            reserve_more(idx, a.count);
            if (const unsigned char *q = packed(a, TINYGLTF_TYPE_SCALAR, a.componentType, what + " indices")) {
                const size_t csize = (size_t)tinygltf::GetComponentSizeInBytes((uint32_t)a.componentType);
                idx.resize(first + a.count);
                for (size_t i = 0; i < a.count; i++) // integers: finite
                    put(i, read_component(q + i * csize, a.componentType, a.normalized));
            } else {
                const std::vector<double> v = read_finite(p.indices, TINYGLTF_TYPE_SCALAR, what + " indices");
                idx.resize(first + v.size());
                for (size_t i = 0; i < v.size(); i++)
                    put(i, v[i]);
            }
        } else {
            reserve_more(idx, nv);
            for (uint32_t i = 0; i < nv; i++)
                idx.push_back(off + i);
        }
        if (!list) {
            strip = triangulate(strip, p.mode);
            reserve_more(b.idx, strip.size());
            for (uint32_t i : strip)
                b.idx.push_back(base + i);
        }
        const size_t n_idx = b.idx.size() - start;
        if (n_idx % 3)
            fail(what + ": index count is not a multiple of 3");
        const uint32_t material = p.material >= 0 && (size_t)p.material < m_.materials.size() ? (uint32_t)p.material + 1 : 0;
        b.mat.resize(b.mat.size() + n_idx / 3, material);

        std::vector<std::vector<double>> deltas;
        for (size_t t = 0; t < p.targets.size(); t++) {
            auto it = p.targets[t].find("POSITION");
            std::vector<double> d = it == p.targets[t].end() ? std::vector<double>(nv * 3, 0.0)
                                                            : read_finite(it->second, TINYGLTF_TYPE_VEC3, what + " morph target");
            if (d.size() != nv * 3)
                fail(what + ": morph target count differs from POSITION count");
            deltas.push_back(std::move(d));
        }
        b.n_targets = std::max(b.n_targets, (uint32_t)deltas.size());
        b.prim_targets.emplace_back(base, std::move(deltas));
    }

    // COLOR_0 (RGB or RGBA, float or normalized integers) as RGB clamped to [0, 1]; white for a
    // primitive without it, as the specification's default.
    void add_colours(mesh_build &b, const tinygltf::Primitive &p, size_t nv, const std::string &what)
    {
        auto it = p.attributes.find("COLOR_0");
        if (it == p.attributes.end()) {
            if (b.any_rgb) // empty until a primitive has colours, as fill()'s attributes
                b.rgb.resize(b.pos.size(), 1.0f);
            return;
        }
        b.rgb.resize((b.pos.size() / 3 - nv) * 3, 1.0f);
        const int type = accessor(it->second, (what + " COLOR_0").c_str()).type;
        if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4)
            fail(what + ": COLOR_0 must be VEC3 or VEC4");
        const int nc = components(type);
        const std::vector<double> v = read(it->second, type, what + " COLOR_0");
        if (v.size() != nv * (size_t)nc)
            fail(what + ": COLOR_0 count differs from POSITION count");
        for (size_t i = 0; i < nv; i++)
            for (int c = 0; c < 3; c++) {
                const double x = v[i * (size_t)nc + (size_t)c];
                b.rgb.push_back(x > 0 ? (x < 1 ? (float)x : 1.0f) : 0.0f); // NaN -> 0
            }
        b.any_rgb = true;
    }

    void load_meshes()
    {
        s_->n_meshes = (uint32_t)m_.meshes.size();
        s_->meshes = alloc_array<scene_mesh>(s_->n_meshes);
        for (size_t mi = 0; mi < m_.meshes.size(); mi++) {
            const tinygltf::Mesh &gm = m_.meshes[mi];
            mesh_build b;
            for (size_t pi = 0; pi < gm.primitives.size(); pi++)
                add_primitive(b, gm.primitives[pi], "mesh " + std::to_string(mi) + " primitive " + std::to_string(pi));
            scene_mesh &sm = s_->meshes[mi];
            std::snprintf(sm.name, sizeof sm.name, "%s", gm.name.empty() ? ("mesh" + std::to_string(mi)).c_str() : gm.name.c_str());
            const size_t n_pos = b.pos.size();
            sm.n_vertices = (uint32_t)(n_pos / 3);
            sm.n_triangles = (uint32_t)(b.idx.size() / 3);
            sm.skin = SCENE_NONE; // set by load_skins for a mesh a skinned node shows
            if (b.any_skin) { // the copies first: the scene takes the arrays themselves
                sm.bind_normals = b.any_normals ? copy_array(b.nrm) : nullptr;
                sm.base_positions = copy_array(b.pos);
                sm.joints = b.joints.release();
                sm.joint_weights = b.weights.release();
            }
            if (b.n_targets && !sm.base_positions)
                sm.base_positions = copy_array(b.pos);
            sm.positions = b.pos.release();
            sm.normals = b.any_normals ? b.nrm.release() : nullptr;
            sm.texcoords = b.any_uv ? b.uv.release() : nullptr;
            sm.texcoords1 = b.any_uv1 ? b.uv1.release() : nullptr;
            sm.colours = b.any_rgb ? b.rgb.release() : nullptr;
            sm.indices = b.idx.release();
            sm.material = b.mat.release();
            if (b.n_targets == 0)
                continue;
            sm.n_targets = b.n_targets;
            sm.target_deltas = alloc_array<float>((size_t)b.n_targets * n_pos);
            for (auto &pt : b.prim_targets)
                for (size_t t = 0; t < pt.second.size(); t++)
                    for (size_t k = 0; k < pt.second[t].size(); k++)
                        sm.target_deltas[t * n_pos + (size_t)pt.first * 3 + k] = (float)pt.second[t][k];
            sm.weights = alloc_array<float>(b.n_targets);
            for (uint32_t t = 0; t < b.n_targets && t < gm.weights.size(); t++)
                sm.weights[t] = (float)gm.weights[t];
            // positions reflect the default weights
            for (size_t v = 0; v < n_pos; v++) {
                double p = sm.positions[v];
                for (uint32_t t = 0; t < b.n_targets; t++)
                    p += (double)sm.weights[t] * sm.target_deltas[t * n_pos + v];
                sm.positions[v] = (float)p;
            }
        }
    }

    // ---- cameras, lights, nodes ------------------------------------------------------------

    void load_cameras_and_lights()
    {
        s_->n_cameras = (uint32_t)m_.cameras.size();
        s_->cameras = alloc_array<scene_camera>(s_->n_cameras);
        for (size_t i = 0; i < m_.cameras.size(); i++) {
            const tinygltf::Camera &c = m_.cameras[i];
            scene_camera &d = s_->cameras[i];
            d.node = SCENE_NONE;
            d.world = affine_identity();
            if (c.type == "orthographic") {
                d.kind = CAMERA_ORTHOGRAPHIC;
                d.xmag = c.orthographic.xmag;
                d.ymag = c.orthographic.ymag;
                d.znear = c.orthographic.znear;
                d.zfar = c.orthographic.zfar;
            } else {
                d.kind = CAMERA_PERSPECTIVE;
                d.yfov = c.perspective.yfov;
                d.aspect = c.perspective.aspectRatio;
                d.znear = c.perspective.znear;
                d.zfar = c.perspective.zfar;
                if (!(d.yfov > 0 && d.yfov < M_PI))
                    fail("camera " + std::to_string(i) + ": yfov must be in (0, pi)");
            }
        }
        s_->n_lights = (uint32_t)m_.lights.size();
        s_->lights = alloc_array<scene_light>(s_->n_lights);
        for (size_t i = 0; i < m_.lights.size(); i++) {
            const tinygltf::Light &l = m_.lights[i];
            scene_light &d = s_->lights[i];
            d.kind = l.type == "directional" ? LIGHT_DIRECTIONAL : l.type == "spot" ? LIGHT_SPOT : LIGHT_POINT;
            for (int c = 0; c < 3; c++)
                d.color[c] = c < (int)l.color.size() ? (float)l.color[(size_t)c] : 1.0f;
            d.intensity = (float)l.intensity;
            d.range = (float)l.range;
            d.inner_cone = (float)l.spot.innerConeAngle;
            d.outer_cone = (float)l.spot.outerConeAngle;
            d.node = SCENE_NONE;
            d.direction[2] = -1;
        }
    }

    static bool all_finite(const std::vector<double> &v)
    {
        for (double x : v)
            if (!std::isfinite(x))
                return false;
        return true;
    }

    // EXT_mesh_gpu_instancing: one instance per row of the TRANSLATION, ROTATION and SCALE
    // accessors (each optional, all of one count), a transformation in the node's local space.
    void load_gpu_instances(const tinygltf::Node &g, scene_node &d, const std::string &what)
    {
        auto ext = g.extensions.find("EXT_mesh_gpu_instancing");
        if (ext == g.extensions.end() || d.mesh == SCENE_NONE || !ext->second.Get("attributes").IsObject())
            return;
        const tinygltf::Value &attributes = ext->second.Get("attributes");
        static const char *const names[3] = { "TRANSLATION", "ROTATION", "SCALE" };
        int index[3] = { -1, -1, -1 };
        size_t rows = 0;
        for (int k = 0; k < 3; k++) {
            if (!attributes.Has(names[k]))
                continue;
            index[k] = attributes.Get(names[k]).GetNumberAsInt();
            const size_t count = accessor(index[k], (what + " " + names[k]).c_str()).count;
            if (rows && count != rows)
                fail(what + ": EXT_mesh_gpu_instancing attributes differ in count");
            rows = count;
        }
        // rows may share one accessor between nodes: bound the total before reading any
        if (rows > SCENE_MAX_INSTANCES - instance_rows_)
            fail(what + ": more than " + std::to_string(SCENE_MAX_INSTANCES) + " instances (EXT_mesh_gpu_instancing)");
        instance_rows_ += rows;
        std::vector<double> trs[3];
        for (int k = 0; k < 3; k++)
            if (index[k] >= 0)
                trs[k] = read_finite(index[k], k == 1 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, what + " " + names[k]);
        d.rows = alloc_array<affine>(rows);
        d.n_rows = (uint32_t)rows;
        for (size_t r = 0; r < rows; r++) {
            const double t0[3] = { 0, 0, 0 }, q0[4] = { 0, 0, 0, 1 }, s0[3] = { 1, 1, 1 };
            d.rows[r] = affine_from_trs(trs[0].empty() ? t0 : &trs[0][3 * r], trs[1].empty() ? q0 : &trs[1][4 * r],
                                        trs[2].empty() ? s0 : &trs[2][3 * r]);
        }
    }

    void load_nodes()
    {
        s_->n_nodes = (uint32_t)m_.nodes.size();
        s_->nodes = alloc_array<scene_node>(s_->n_nodes);
        for (uint32_t i = 0; i < s_->n_nodes; i++)
            s_->nodes[i].parent = -1;
        for (size_t i = 0; i < m_.nodes.size(); i++) {
            const tinygltf::Node &g = m_.nodes[i];
            scene_node &d = s_->nodes[i];
            const std::string what = "node " + std::to_string(i);
            std::snprintf(d.name, sizeof d.name, "%s", g.name.c_str());
            d.mesh = g.mesh >= 0 && (size_t)g.mesh < m_.meshes.size() ? (uint32_t)g.mesh : SCENE_NONE;
            if (g.mesh >= 0 && d.mesh == SCENE_NONE)
                fail(what + ": mesh index out of range");
            d.camera = g.camera >= 0 && (size_t)g.camera < m_.cameras.size() ? (uint32_t)g.camera : SCENE_NONE;
            d.light = SCENE_NONE;
            auto lx = g.extensions.find("KHR_lights_punctual");
            if (lx != g.extensions.end() && lx->second.Has("light")) {
                const int li = lx->second.Get("light").GetNumberAsInt();
                if (li < 0 || (size_t)li >= m_.lights.size())
                    fail(what + ": light index out of range");
                d.light = (uint32_t)li;
                s_->lights[li].node = (uint32_t)i;
            }
            if (d.camera != SCENE_NONE)
                s_->cameras[d.camera].node = (uint32_t)i;
            load_gpu_instances(g, d, what);
            if (!all_finite(g.matrix) || !all_finite(g.translation) || !all_finite(g.rotation) || !all_finite(g.scale))
                fail(what + ": non-finite transformation");
            d.has_matrix = g.matrix.size() == 16;
            if (d.has_matrix)
                for (int r = 0; r < 3; r++)
                    for (int c = 0; c < 4; c++)
                        d.matrix.m[r][c] = g.matrix[(size_t)c * 4 + (size_t)r]; // column-major
            for (int k = 0; k < 3; k++) {
                d.translation[k] = g.translation.size() == 3 ? g.translation[(size_t)k] : 0.0;
                d.scale[k] = g.scale.size() == 3 ? g.scale[(size_t)k] : 1.0;
            }
            for (int k = 0; k < 4; k++)
                d.rotation[k] = g.rotation.size() == 4 ? g.rotation[(size_t)k] : (k == 3 ? 1.0 : 0.0);
            const uint32_t nt = d.mesh != SCENE_NONE ? s_->meshes[d.mesh].n_targets : 0;
            if (nt) {
                d.n_weights = nt;
                d.weights = alloc_array<double>(nt);
                for (uint32_t t = 0; t < nt; t++)
                    d.weights[t] = t < g.weights.size() ? g.weights[t] : s_->meshes[d.mesh].weights[t];
            }
            for (int c : g.children) {
                if (c < 0 || (size_t)c >= m_.nodes.size())
                    fail(what + ": child index out of range");
                if (s_->nodes[c].parent >= 0 || (size_t)c == i)
                    fail("node " + std::to_string(c) + " has more than one parent (the node graph must be a tree)");
                s_->nodes[c].parent = (int)i;
            }
        }
        for (uint32_t i = 0; i < s_->n_nodes; i++) { // cycles: a walk up must end within n steps
            uint32_t steps = 0;
            for (int p = s_->nodes[i].parent; p >= 0; p = s_->nodes[p].parent)
                if (++steps > s_->n_nodes)
                    fail("the node hierarchy has a cycle");
        }
    }

    // ---- skins ---------------------------------------------------------------------------

    void load_skins()
    {
        s_->skins = alloc_array<scene_skin>(m_.skins.size());
        s_->n_skins = (uint32_t)m_.skins.size(); // zeroed: scene_free frees what a failure leaves
        for (size_t i = 0; i < m_.skins.size(); i++)
            load_skin(m_.skins[i], "skin " + std::to_string(i), s_->skins[i]);
        for (size_t i = 0; i < m_.nodes.size(); i++)
            attach_skin((uint32_t)i, m_.nodes[i].skin);
        for (size_t i = 0; i < m_.nodes.size(); i++) {
            const uint32_t mesh = s_->nodes[i].mesh;
            if (m_.nodes[i].skin < 0 && mesh != SCENE_NONE && s_->meshes[mesh].skin != SCENE_NONE)
                warn("node " + std::to_string(i) + ": shows skinned mesh '" + s_->meshes[mesh].name +
                     "' without a skin: drawn skinned");
        }
        for (uint32_t i = 0; i < s_->n_meshes; i++)
            check_influences(s_->meshes[i], "mesh " + std::to_string(i));
    }

    void load_skin(const tinygltf::Skin &g, const std::string &what, scene_skin &d)
    {
        d.joints = alloc_array<uint32_t>(g.joints.size());
        d.inverse_bind = alloc_array<affine>(g.joints.size());
        d.n_joints = (uint32_t)g.joints.size();
        std::vector<double> ibm;
        if (g.inverseBindMatrices >= 0)
            ibm = read_finite(g.inverseBindMatrices, TINYGLTF_TYPE_MAT4, what + " inverseBindMatrices");
        if (!ibm.empty() && ibm.size() != g.joints.size() * 16)
            fail(what + ": inverseBindMatrices count differs from the joint count");
        for (size_t j = 0; j < g.joints.size(); j++) {
            if (g.joints[j] < 0 || (size_t)g.joints[j] >= m_.nodes.size())
                fail(what + ": joint node index out of range");
            d.joints[j] = (uint32_t)g.joints[j];
            d.inverse_bind[j] = affine_identity();
            for (int r = 0; r < 3 && !ibm.empty(); r++)
                for (int c = 0; c < 4; c++)
                    d.inverse_bind[j].m[r][c] = ibm[j * 16 + (size_t)c * 4 + (size_t)r]; // column-major
        }
    }

    // The skin of node i goes to its mesh: the scene model keeps one deformed copy of a mesh.
    void attach_skin(uint32_t i, int skin)
    {
        const std::string what = "node " + std::to_string(i);
        if (skin < 0)
            return;
        if ((size_t)skin >= m_.skins.size())
            fail(what + ": skin index out of range");
        if (s_->nodes[i].mesh == SCENE_NONE)
            return;
        scene_mesh &m = s_->meshes[s_->nodes[i].mesh];
        if (!m.joints)
            warn(what + ": skin " + std::to_string(skin) + " on a mesh without JOINTS_0/WEIGHTS_0, drawn unskinned");
        else if (m.skin != SCENE_NONE && m.skin != (uint32_t)skin)
            warn(what + ": mesh '" + m.name + "' is shown with several skins: every instance is drawn with skin " +
                 std::to_string(m.skin));
        else
            m.skin = (uint32_t)skin;
    }

    // Influences of a skinned mesh name joints of its skin; a mesh no skinned node shows drops them.
    void check_influences(scene_mesh &m, const std::string &what)
    {
        if (!m.joints)
            return;
        if (m.skin == SCENE_NONE) {
            std::free(m.joints);
            std::free(m.joint_weights);
            std::free(m.bind_normals);
            m.joints = nullptr;
            m.joint_weights = nullptr;
            m.bind_normals = nullptr;
            if (m.n_targets == 0) {
                std::free(m.base_positions);
                m.base_positions = nullptr;
            }
            return;
        }
        const uint32_t n = s_->skins[m.skin].n_joints;
        for (size_t k = 0; k < 4 * (size_t)m.n_vertices; k++)
            if (m.joint_weights[k] > 0 && m.joints[k] >= n)
                fail(what + ": JOINTS_0 names joint " + std::to_string(m.joints[k]) + " of a skin of " +
                     std::to_string(n) + " joints");
    }

    // ---- animations ----------------------------------------------------------------------

    void load_animations()
    {
        s_->n_animations = (uint32_t)m_.animations.size();
        s_->animations = alloc_array<scene_animation>(s_->n_animations);
        for (size_t ai = 0; ai < m_.animations.size(); ai++) {
            const tinygltf::Animation &ga = m_.animations[ai];
            scene_animation &a = s_->animations[ai];
            std::snprintf(a.name, sizeof a.name, "%s", ga.name.c_str());
            // channels go straight into the scene, which owns their keys from then on: a later
            // channel that fails leaves nothing behind that scene_free would not free
            a.channels = alloc_array<scene_channel>(ga.channels.size());
            for (size_t ci = 0; ci < ga.channels.size(); ci++) {
                const tinygltf::AnimationChannel &gc = ga.channels[ci];
                const std::string what = "animation " + std::to_string(ai) + " channel " + std::to_string(ci);
                if (gc.target_node < 0 || (size_t)gc.target_node >= m_.nodes.size())
                    fail(what + ": target node out of range");
                if (gc.sampler < 0 || (size_t)gc.sampler >= ga.samplers.size())
                    fail(what + ": sampler out of range");
                const tinygltf::AnimationSampler &gs = ga.samplers[(size_t)gc.sampler];
                scene_channel c{};
                c.node = (uint32_t)gc.target_node;
                int type = TINYGLTF_TYPE_VEC3;
                if (gc.target_path == "translation") c.path = ANIM_TRANSLATION, c.components = 3;
                else if (gc.target_path == "rotation") c.path = ANIM_ROTATION, c.components = 4, type = TINYGLTF_TYPE_VEC4;
                else if (gc.target_path == "scale") c.path = ANIM_SCALE, c.components = 3;
                else if (gc.target_path == "weights") {
                    c.path = ANIM_WEIGHTS;
                    c.components = s_->nodes[c.node].n_weights;
                    type = TINYGLTF_TYPE_SCALAR;
                    if (c.components == 0) {
                        warn(what + ": weights channel on a node without morph targets, skipped");
                        continue;
                    }
                } else {
                    warn(what + ": target path '" + gc.target_path + "' is not supported, skipped");
                    continue;
                }
                c.interp = gs.interpolation == "STEP" ? INTERP_STEP : gs.interpolation == "CUBICSPLINE" ? INTERP_CUBICSPLINE : INTERP_LINEAR;
                const std::vector<double> t = read_finite(gs.input, TINYGLTF_TYPE_SCALAR, what + " input");
                const std::vector<double> v = read_finite(gs.output, type, what + " output");
                const size_t per_key = (size_t)c.components * (c.interp == INTERP_CUBICSPLINE ? 3 : 1);
                if (t.empty() || v.size() != t.size() * per_key)
                    fail(what + ": output count does not match input count");
                for (size_t k = 1; k < t.size(); k++)
                    if (!(t[k] > t[k - 1]))
                        fail(what + ": key times must increase");
                c.n_keys = (uint32_t)t.size();
                scene_channel &dst = a.channels[a.n_channels++] = c;
                dst.times = alloc_array<float>(t.size());
                dst.values = alloc_array<float>(v.size());
                for (size_t k = 0; k < t.size(); k++)
                    dst.times[k] = (float)t[k];
                for (size_t k = 0; k < v.size(); k++)
                    dst.values[k] = (float)v[k];
                a.duration = std::max(a.duration, dst.times[dst.n_keys - 1]);
            }
        }
    }

    void load_roots()
    {
        std::vector<uint32_t> roots;
        if (!m_.scenes.empty()) {
            const size_t si = m_.defaultScene >= 0 && (size_t)m_.defaultScene < m_.scenes.size() ? (size_t)m_.defaultScene : 0;
            for (int n : m_.scenes[si].nodes) {
                if (n < 0 || (size_t)n >= m_.nodes.size())
                    fail("scene " + std::to_string(si) + ": node index out of range");
                if (s_->nodes[n].parent >= 0)
                    fail("scene " + std::to_string(si) + ": root node " + std::to_string(n) + " has a parent");
                roots.push_back((uint32_t)n);
            }
        } else {
            for (uint32_t i = 0; i < s_->n_nodes; i++)
                if (s_->nodes[i].parent < 0)
                    roots.push_back(i);
        }
        s_->n_roots = (uint32_t)roots.size();
        s_->roots = copy_array(roots);
    }
};



// Files a glTF may read: the file itself and files inside its own directory. tinygltf reads the
// main file and every external buffer and image through these callbacks; a reference that
// resolves (after "..", absolute paths and symlinks, realpath) outside the directory is refused,
// so a hostile scene cannot make the loader read /etc/passwd or a sibling project's files.
struct sandbox {
    std::string dir;  // realpath of the glTF's directory, with a trailing '/'
    std::string self; // realpath of the glTF file
    std::string base; // the directory as tinygltf joins it with a URI (its GetBaseDir)
    std::string refused;
};

std::string real_path(const std::string &p)
{
    char *r = realpath(p.c_str(), nullptr);
    std::string out = r ? r : "";
    std::free(r);
    return out;
}

bool sandboxed_read(std::vector<unsigned char> *out, std::string *err, const std::string &file, void *user)
{
    sandbox *sb = static_cast<sandbox *>(user);
    const std::string real = real_path(file);
    if (!real.empty() && real != sb->self && real.compare(0, sb->dir.size(), sb->dir) != 0) {
        sb->refused = file;
        if (err)
            *err += "refers to '" + file + "' outside its directory (refused)\n";
        return false;
    }
    struct stat st; // the file's buffer in huge pages: reserved and advised before the read writes it
    if (stat(file.c_str(), &st) == 0 && st.st_size > 0 && (uint64_t)st.st_size < (uint64_t)out->max_size()) {
        out->reserve((size_t)st.st_size);
        huge_pages_advise(out->data(), out->capacity());
    }
    return tinygltf::ReadWholeFile(out, err, file, nullptr);
}

// tinygltf joins an absolute URI to the directory ("dir" + "/" + "/abs/x.bin"): refuse it by name.
bool sandboxed_exists(const std::string &file, void *user)
{
    sandbox *sb = static_cast<sandbox *>(user);
    const std::string joined = sb->base.empty() ? "" : sb->base + "/";
    if (file.size() > joined.size() && file.compare(0, joined.size(), joined) == 0 && file[joined.size()] == '/') {
        sb->refused = file.substr(joined.size());
        return false;
    }
    return tinygltf::FileExists(file, nullptr);
}

// Texture dimensions from a PNG (IHDR) or JPEG (SOFn) header, read before anything is decoded.
bool image_header_size(const unsigned char *b, int n, uint32_t *w, uint32_t *h)
{
    auto be = [b](int at, int bytes) {
        uint32_t v = 0;
        for (int i = 0; i < bytes; i++)
            v = v << 8 | b[at + i];
        return v;
    };
    if (n >= 24 && std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0 && std::memcmp(b + 12, "IHDR", 4) == 0) {
        *w = be(16, 4), *h = be(20, 4);
        return true;
    }
    if (n < 4 || b[0] != 0xFF || b[1] != 0xD8)
        return false;
    for (int at = 2; at + 9 <= n && b[at] == 0xFF;) { // JPEG segments up to the frame header
        const int marker = b[at + 1];
        if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
            *h = be(at + 5, 2), *w = be(at + 7, 2);
            return true;
        }
        at += 2 + (int)be(at + 2, 2);
    }
    return false;
}

// Decodes an image (tinygltf's stb_image) only if its header announces at most
// SCENE_MAX_TEXTURE_SIDE texels a side: a few bytes of PNG must not allocate gigabytes.
bool bounded_image_loader(tinygltf::Image *image, const int index, std::string *err, std::string *warn, int req_w,
                          int req_h, const unsigned char *bytes, int size, void *user)
{
    uint32_t w = 0, h = 0;
    if (image_header_size(bytes, size, &w, &h) && (w > SCENE_MAX_TEXTURE_SIDE || h > SCENE_MAX_TEXTURE_SIDE)) {
        if (err)
            *err += "image " + std::to_string(index) + " is " + std::to_string(w) + "x" + std::to_string(h) +
                    " texels, more than " + std::to_string(SCENE_MAX_TEXTURE_SIDE) + " a side (not decoded)\n";
        return false;
    }
    return tinygltf::LoadImageData(image, index, err, warn, req_w, req_h, bytes, size, user);
}

// Just enough JSON to read the top-level "extensionsRequired" before tinygltf decodes anything:
// it fails on Draco or KTX2 data with messages that do not name the extension. Malformed JSON
// gives nothing here; tinygltf then reports it.
class required_scan {
  public:
    explicit required_scan(const std::string &text) : t_(text) {}

    std::vector<std::string> run()
    {
        std::vector<std::string> out;
        if (!eat('{') || eat('}'))
            return out;
        do {
            std::string key;
            if (!string(&key) || !eat(':'))
                return {};
            if (key != "extensionsRequired" ? !value(0) : !names(&out))
                return {};
        } while (eat(','));
        return out;
    }

  private:
    const std::string &t_;
    size_t i_ = 0;

    bool next_is(char c)
    {
        while (i_ < t_.size() && std::isspace((unsigned char)t_[i_]))
            i_++;
        return i_ < t_.size() && t_[i_] == c;
    }

    bool eat(char c) { return next_is(c) && ++i_; }

    bool string(std::string *out)
    {
        if (!eat('"'))
            return false;
        for (; i_ < t_.size() && t_[i_] != '"'; i_++) {
            if (t_[i_] == '\\')
                i_++; // an escaped character is taken as it is: extension names have none
            if (out && i_ < t_.size())
                out->push_back(t_[i_]);
        }
        return eat('"');
    }

    bool names(std::vector<std::string> *out)
    {
        if (!eat('['))
            return false;
        if (eat(']'))
            return true;
        do {
            out->emplace_back();
            if (!string(&out->back()))
                return false;
        } while (eat(','));
        return eat(']');
    }

    // Skips one value; nesting is bounded so that a hostile file cannot exhaust the stack.
    bool value(int depth)
    {
        if (depth > 256)
            return false;
        if (next_is('"'))
            return string(nullptr);
        const bool object = eat('{');
        if (object || eat('[')) {
            const char close = object ? '}' : ']';
            if (eat(close))
                return true;
            do
                if ((object && !(string(nullptr) && eat(':'))) || !value(depth + 1))
                    return false;
            while (eat(','));
            return eat(close);
        }
        const size_t start = i_; // number, true, false or null
        while (i_ < t_.size() && (std::isalnum((unsigned char)t_[i_]) || std::strchr("+-.", t_[i_])))
            i_++;
        return i_ > start;
    }
};

// The extensionsRequired of a .gltf, or of the JSON chunk of a .glb (empty if unreadable).
std::vector<std::string> required_extensions(const std::string &path)
{
    std::ifstream f(path, std::ios::binary);
    std::string text;
    if (ends_with(path, ".glb")) {
        unsigned char head[20];
        if (!f.read(reinterpret_cast<char *>(head), sizeof head) || std::memcmp(head + 16, "JSON", 4) != 0)
            return {};
        const uint32_t n = head[12] | head[13] << 8 | head[14] << 16 | (uint32_t)head[15] << 24;
        f.seekg(0, std::ios::end);
        if (!f || (uint64_t)n + sizeof head > (uint64_t)f.tellg()) // a truncated file: tinygltf says so
            return {};
        text.resize(n);
        f.seekg(sizeof head);
        f.read(&text[0], n);
    } else {
        text.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
    }
    return required_scan(text).run();
}

// No '~' or $VARIABLE expansion of URIs (tinygltf's default runs wordexp on them).
std::string no_expansion(const std::string &path, void *) { return path; }

} // namespace

extern "C" int scene_load_gltf(const char *path, scene *out, char *err, size_t errlen)
{
    std::memset(out, 0, sizeof *out);
    try {
        tinygltf::TinyGLTF loader;
        tinygltf::Model model;
        std::string e, w;
        const std::string p(path);
        const size_t slash = p.rfind('/');
        sandbox sb{ real_path(slash == std::string::npos ? "." : p.substr(0, slash + 1)), real_path(p),
                    slash == std::string::npos ? "" : p.substr(0, slash), "" };
        if (sb.dir.empty() || sb.dir.back() != '/')
            sb.dir += '/';
        check_required(required_extensions(p));
        loader.SetImageLoader(bounded_image_loader, nullptr);
        loader.SetFsCallbacks({ sandboxed_exists, no_expansion, sandboxed_read, tinygltf::WriteWholeFile, &sb });
        const bool ok = ends_with(p, ".glb") ? loader.LoadBinaryFromFile(&model, &e, &w, p)
                                             : loader.LoadASCIIFromFile(&model, &e, &w, p);
        if (!ok && !sb.refused.empty()) {
            set_error(err, errlen, p + ": refers to '" + sb.refused + "' outside its directory (refused)");
            return -1;
        }
        if (!ok) {
            set_error(err, errlen, p + ": " + (e.empty() ? "cannot load glTF" : first_line(e)));
            return -1;
        }
        if (!w.empty())
            std::fprintf(stderr, "saarcor: warning: %s: %s\n", path, first_line(w).c_str());
        Loader(model, p, out).run();
        return 0;
    } catch (const load_error &x) {
        set_error(err, errlen, std::string(path) + ": " + x.what());
    } catch (const std::bad_alloc &) {
        set_error(err, errlen, std::string(path) + ": out of memory");
    } catch (const std::exception &x) {
        set_error(err, errlen, std::string(path) + ": " + x.what());
    }
    scene_free(out);
    return -1;
}
