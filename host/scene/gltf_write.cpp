// glTF 2.0 writer behind scene.h (tinygltf from Debian, route A: header + -ltinygltf).
// One buffer holds all data (the BIN chunk of a .glb, a base64 data URI in a .gltf). Each scene
// mesh becomes one glTF mesh with one TRIANGLES primitive per material (in order of first use;
// a primitive holds the vertices its triangles use, in their original order), so that loading the
// file back (scene_load_gltf) gives the same objects, triangles, nodes, instances, materials,
// cameras, lights and animations. Scene material m >= 1 is glTF material m - 1; material 0 (the
// default) is written as "no material". Textures are PNG images (encoded by tinygltf's stb image
// writer) in the buffer. No C++ exception crosses into C: errors are one line in err.
#include "scene.h"
#include "gltf_util.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace {

using gltf_util::ends_with;
using gltf_util::first_line;
using gltf_util::set_error;

struct write_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string num(uint64_t v) { return std::to_string(v); }

class Writer {
  public:
    Writer(const scene &s, tinygltf::Model &m) : s_(s), m_(m) {}

    void run()
    {
        m_.asset.version = "2.0";
        m_.asset.generator = "saarcor scene_write_gltf";
        m_.buffers.resize(1);
        validate_nodes();
        write_textures();
        write_materials();
        write_meshes();
        write_cameras_and_lights();
        write_nodes();
        write_skins();
        write_animations();
        if (m_.buffers[0].data.empty())
            m_.buffers.clear();
        else if (m_.buffers[0].data.size() > 0xFFFFFFF0ull)
            throw write_error("the scene needs more than 4 GB of buffer data");
    }

  private:
    const scene &s_;
    tinygltf::Model &m_;

    bool used_ext(const char *name) const
    {
        return std::find(m_.extensionsUsed.begin(), m_.extensionsUsed.end(), name) != m_.extensionsUsed.end();
    }
    void use_ext(const char *name)
    {
        if (!used_ext(name))
            m_.extensionsUsed.push_back(name);
    }

    // ---- buffer, views, accessors ------------------------------------------------------------

    int add_view(const void *data, size_t bytes, int target)
    {
        std::vector<unsigned char> &buf = m_.buffers[0].data;
        while (buf.size() % 4)
            buf.push_back(0);
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = buf.size();
        v.byteLength = bytes;
        v.target = target;
        const unsigned char *p = static_cast<const unsigned char *>(data);
        buf.insert(buf.end(), p, p + bytes);
        m_.bufferViews.push_back(v);
        return (int)m_.bufferViews.size() - 1;
    }

    static int type_of(int ncomp)
    {
        switch (ncomp) {
        case 1: return TINYGLTF_TYPE_SCALAR;
        case 2: return TINYGLTF_TYPE_VEC2;
        case 3: return TINYGLTF_TYPE_VEC3;
        case 4: return TINYGLTF_TYPE_VEC4;
        case 16: return TINYGLTF_TYPE_MAT4;
        default: throw write_error("internal: bad component count");
        }
    }

    // Float accessor of v.size() / ncomp elements; min/max when asked (POSITION, key times).
    int add_floats(const std::vector<float> &v, int ncomp, int target, bool minmax)
    {
        tinygltf::Accessor a;
        a.bufferView = add_view(v.data(), v.size() * sizeof(float), target);
        a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        a.count = v.size() / (size_t)ncomp;
        a.type = type_of(ncomp);
        if (minmax && a.count) {
            a.minValues.assign((size_t)ncomp, INFINITY);
            a.maxValues.assign((size_t)ncomp, -INFINITY);
            for (size_t i = 0; i < v.size(); i++) {
                const size_t c = i % (size_t)ncomp;
                a.minValues[c] = std::min(a.minValues[c], (double)v[i]);
                a.maxValues[c] = std::max(a.maxValues[c], (double)v[i]);
            }
        }
        m_.accessors.push_back(a);
        return (int)m_.accessors.size() - 1;
    }

    // Unsigned integer accessor (uint32_t: indices, uint16_t: JOINTS_0) of v.size() / ncomp elements.
    template <typename T> int add_uints(const std::vector<T> &v, int ncomp, int target)
    {
        tinygltf::Accessor a;
        a.bufferView = add_view(v.data(), v.size() * sizeof(T), target);
        a.componentType = sizeof(T) == 2 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        a.count = v.size() / (size_t)ncomp;
        a.type = type_of(ncomp);
        m_.accessors.push_back(a);
        return (int)m_.accessors.size() - 1;
    }

    int add_indices(const std::vector<uint32_t> &v) { return add_uints(v, 1, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER); }

    static bool finite(const float *p, size_t n)
    {
        for (size_t i = 0; i < n; i++)
            if (!std::isfinite(p[i]))
                return false;
        return true;
    }

    // ---- textures and materials ----------------------------------------------------------

    static std::vector<unsigned char> base64_decode(const std::string &s)
    {
        std::vector<unsigned char> out;
        uint32_t acc = 0;
        int bits = 0;
        for (char ch : s) {
            int v;
            if (ch >= 'A' && ch <= 'Z') v = ch - 'A';
            else if (ch >= 'a' && ch <= 'z') v = ch - 'a' + 26;
            else if (ch >= '0' && ch <= '9') v = ch - '0' + 52;
            else if (ch == '+') v = 62;
            else if (ch == '/') v = 63;
            else continue; // '=' padding
            acc = acc << 6 | (uint32_t)v;
            bits += 6;
            if (bits >= 8) {
                bits -= 8;
                out.push_back((unsigned char)(acc >> bits & 0xFF));
            }
        }
        return out;
    }

    // PNG bytes of an RGBA8 image, encoded by tinygltf's image writer (stb_image_write).
    static std::vector<unsigned char> encode_png(const tinygltf::Image &im)
    {
        const std::string base, name = "texture.png";
        std::string uri;
        if (!tinygltf::WriteImageData(&base, &name, &im, true, &uri, nullptr))
            throw write_error("PNG encoding failed");
        const std::string header = "data:image/png;base64,";
        if (uri.compare(0, header.size(), header) != 0)
            throw write_error("PNG encoding gave no data URI");
        return base64_decode(uri.substr(header.size()));
    }

    // Textures: one PNG image each, stored in the buffer (the BIN chunk of a .glb).
    void write_textures()
    {
        if (s_.n_textures == 0)
            return;
        tinygltf::Sampler smp;
        smp.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
        smp.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
        smp.wrapS = smp.wrapT = TINYGLTF_TEXTURE_WRAP_REPEAT;
        m_.samplers.push_back(smp);
        for (uint32_t i = 0; i < s_.n_textures; i++) {
            const scene_texture &t = s_.textures[i];
            if (t.width <= 0 || t.height <= 0 || !t.rgba)
                throw write_error("texture " + num(i) + " has no pixels");
            tinygltf::Image im;
            im.width = t.width;
            im.height = t.height;
            im.component = 4;
            im.bits = 8;
            im.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
            im.image.assign(t.rgba, t.rgba + (size_t)t.width * (size_t)t.height * 4);
            const std::vector<unsigned char> png = encode_png(im);
            im.image.clear();
            im.image.shrink_to_fit();
            im.name = "texture" + num(i);
            im.mimeType = "image/png";
            im.bufferView = add_view(png.data(), png.size(), 0);
            m_.images.push_back(std::move(im));
            tinygltf::Texture tex;
            tex.source = (int)i;
            tex.sampler = 0;
            m_.textures.push_back(tex);
        }
    }

    // A material's texture reference: index, TEXCOORD_n and KHR_texture_transform.
    void texture_info(uint32_t texture, uint32_t texcoord, const scene_uv_map &uv, const std::string &what,
                      tinygltf::TextureInfo &out)
    {
        if (texture == SCENE_NONE)
            return;
        if (texture >= s_.n_textures)
            throw write_error(what + ": texture index out of range");
        out.index = (int)texture;
        out.texCoord = (int)texcoord;
        if (!uv.set)
            return;
        tinygltf::Value::Object o;
        o["offset"] = tinygltf::Value(tinygltf::Value::Array{ tinygltf::Value(uv.offset[0]), tinygltf::Value(uv.offset[1]) });
        o["rotation"] = tinygltf::Value(uv.rotation);
        o["scale"] = tinygltf::Value(tinygltf::Value::Array{ tinygltf::Value(uv.scale[0]), tinygltf::Value(uv.scale[1]) });
        out.extensions["KHR_texture_transform"] = tinygltf::Value(std::move(o));
        use_ext("KHR_texture_transform");
    }

    void write_materials()
    {
        for (uint32_t i = 1; i < s_.n_materials; i++) {
            const scene_material &d = s_.materials[i];
            tinygltf::Material g;
            auto &pbr = g.pbrMetallicRoughness;
            pbr.baseColorFactor.assign(d.base_color, d.base_color + 4);
            pbr.metallicFactor = d.metallic;
            pbr.roughnessFactor = d.roughness;
            texture_info(d.base_color_texture, d.texcoord_set, d.base_uv, "material " + num(i), pbr.baseColorTexture);
            texture_info(d.emissive_texture, d.emissive_texcoord, d.emissive_uv, "material " + num(i), g.emissiveTexture);
            if (d.unlit) {
                g.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
                use_ext("KHR_materials_unlit");
            }
            g.alphaMode = d.alpha == ALPHA_MASK ? "MASK" : d.alpha == ALPHA_BLEND ? "BLEND" : "OPAQUE";
            g.alphaCutoff = d.alpha_cutoff;
            g.doubleSided = d.double_sided != 0;
            const float emax = std::max({ d.emissive[0], d.emissive[1], d.emissive[2] });
            if (emax > 1.0f) { // emissiveFactor is limited to [0, 1]
                g.emissiveFactor = { (double)d.emissive[0] / emax, (double)d.emissive[1] / emax, (double)d.emissive[2] / emax };
                tinygltf::Value::Object o;
                o["emissiveStrength"] = tinygltf::Value((double)emax);
                g.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(std::move(o));
                use_ext("KHR_materials_emissive_strength");
            } else {
                g.emissiveFactor.assign(d.emissive, d.emissive + 3);
            }
            if (d.transmission > 0.0f) {
                tinygltf::Value::Object o;
                o["transmissionFactor"] = tinygltf::Value((double)d.transmission);
                g.extensions["KHR_materials_transmission"] = tinygltf::Value(std::move(o));
                use_ext("KHR_materials_transmission");
            }
            if (d.ior != 1.5f) {
                tinygltf::Value::Object o;
                o["ior"] = tinygltf::Value((double)d.ior);
                g.extensions["KHR_materials_ior"] = tinygltf::Value(std::move(o));
                use_ext("KHR_materials_ior");
            }
            m_.materials.push_back(std::move(g));
        }
    }

    // ---- meshes --------------------------------------------------------------------------

    void write_meshes()
    {
        for (uint32_t mi = 0; mi < s_.n_meshes; mi++)
            m_.meshes.push_back(mesh(mi));
    }

    tinygltf::Mesh mesh(uint32_t mi)
    {
        const scene_mesh &sm = s_.meshes[mi];
        const std::string what = "mesh " + num(mi);
        const uint32_t nv = sm.n_vertices, nt = sm.n_triangles;
        const bool skinned = sm.joints && sm.skin < s_.n_skins; // written in its rest pose with its influences
        const float *pos = sm.n_targets || skinned ? sm.base_positions : sm.positions;
        const float *nrm = skinned && sm.bind_normals ? sm.bind_normals : sm.normals;
        if ((nv && !pos) || (nt && (!sm.indices || !sm.material)) || (sm.n_targets && (!sm.target_deltas || !sm.weights)) ||
            (skinned && !sm.joint_weights))
            throw write_error(what + ": missing arrays");
        if (!finite(pos, 3 * (size_t)nv))
            throw write_error(what + ": non-finite position");
        const uint32_t n_mat = std::max(1u, s_.n_materials);
        for (size_t k = 0; k < 3 * (size_t)nt; k++)
            if (sm.indices[k] >= nv)
                throw write_error(what + ": index out of range");
        for (uint32_t t = 0; t < nt; t++)
            if (sm.material[t] >= n_mat)
                throw write_error(what + ": material index out of range");

        tinygltf::Mesh g;
        g.name = sm.name;
        if (sm.n_targets)
            g.weights.assign(sm.weights, sm.weights + sm.n_targets);
        if (nt == 0) { // keep the mesh index: a points primitive, which the loader skips
            std::vector<float> p(pos, pos + 3 * (size_t)nv);
            if (p.empty())
                p.assign(3, 0.0f);
            tinygltf::Primitive prim;
            prim.mode = TINYGLTF_MODE_POINTS;
            prim.attributes["POSITION"] = add_floats(p, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
            g.primitives.push_back(prim);
            return g;
        }

        std::vector<uint32_t> order; // materials in order of first use
        std::vector<char> seen(n_mat, 0);
        for (uint32_t t = 0; t < nt; t++)
            if (!seen[sm.material[t]]) {
                seen[sm.material[t]] = 1;
                order.push_back(sm.material[t]);
            }
        std::vector<uint32_t> remap(nv);
        for (uint32_t mat : order) {
            std::vector<char> used(nv, 0);
            for (uint32_t t = 0; t < nt; t++)
                if (sm.material[t] == mat)
                    for (int k = 0; k < 3; k++)
                        used[sm.indices[3 * (size_t)t + (size_t)k]] = 1;
            std::vector<uint32_t> verts; // used vertices in their original order
            for (uint32_t v = 0; v < nv; v++)
                if (used[v]) {
                    remap[v] = (uint32_t)verts.size();
                    verts.push_back(v);
                }
            std::vector<uint32_t> idx;
            for (uint32_t t = 0; t < nt; t++)
                if (sm.material[t] == mat)
                    for (int k = 0; k < 3; k++)
                        idx.push_back(remap[sm.indices[3 * (size_t)t + (size_t)k]]);
            auto gather = [&](const auto *src, int ncomp) {
                std::vector<std::remove_const_t<std::remove_pointer_t<decltype(src)>>> out;
                out.reserve(verts.size() * (size_t)ncomp);
                for (uint32_t v : verts)
                    out.insert(out.end(), src + (size_t)v * (size_t)ncomp, src + ((size_t)v + 1) * (size_t)ncomp);
                return out;
            };
            tinygltf::Primitive prim;
            prim.mode = TINYGLTF_MODE_TRIANGLES;
            prim.material = mat == 0 ? -1 : (int)mat - 1;
            prim.attributes["POSITION"] = add_floats(gather(pos, 3), 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
            if (nrm)
                prim.attributes["NORMAL"] = add_floats(gather(nrm, 3), 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
            if (skinned) {
                prim.attributes["JOINTS_0"] = add_uints(gather(sm.joints, 4), 4, TINYGLTF_TARGET_ARRAY_BUFFER);
                prim.attributes["WEIGHTS_0"] = add_floats(gather(sm.joint_weights, 4), 4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
            }
            if (sm.texcoords)
                prim.attributes["TEXCOORD_0"] = add_floats(gather(sm.texcoords, 2), 2, TINYGLTF_TARGET_ARRAY_BUFFER, false);
            if (sm.texcoords1)
                prim.attributes["TEXCOORD_1"] = add_floats(gather(sm.texcoords1, 2), 2, TINYGLTF_TARGET_ARRAY_BUFFER, false);
            if (sm.colours)
                prim.attributes["COLOR_0"] = add_floats(gather(sm.colours, 3), 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
            prim.indices = add_indices(idx);
            for (uint32_t t = 0; t < sm.n_targets; t++) {
                const float *d = sm.target_deltas + (size_t)t * 3 * nv;
                if (!finite(d, 3 * (size_t)nv))
                    throw write_error(what + ": non-finite morph target");
                prim.targets.push_back({ { "POSITION", add_floats(gather(d, 3), 3, TINYGLTF_TARGET_ARRAY_BUFFER, true) } });
            }
            g.primitives.push_back(std::move(prim));
        }
        return g;
    }

    // ---- cameras, lights, nodes --------------------------------------------------------------

    void write_cameras_and_lights()
    {
        for (uint32_t i = 0; i < s_.n_cameras; i++) {
            const scene_camera &c = s_.cameras[i];
            tinygltf::Camera g;
            if (c.kind == CAMERA_ORTHOGRAPHIC) {
                g.type = "orthographic";
                g.orthographic.xmag = c.xmag;
                g.orthographic.ymag = c.ymag;
                g.orthographic.znear = c.znear;
                g.orthographic.zfar = c.zfar;
            } else {
                if (!(c.yfov > 0 && c.yfov < M_PI))
                    throw write_error("camera " + num(i) + ": yfov must be in (0, pi)");
                g.type = "perspective";
                g.perspective.yfov = c.yfov;
                g.perspective.aspectRatio = c.aspect;
                g.perspective.znear = c.znear;
                g.perspective.zfar = c.zfar;
            }
            m_.cameras.push_back(g);
        }
        for (uint32_t i = 0; i < s_.n_lights; i++) {
            const scene_light &l = s_.lights[i];
            tinygltf::Light g;
            g.type = l.kind == LIGHT_DIRECTIONAL ? "directional" : l.kind == LIGHT_SPOT ? "spot" : "point";
            g.color.assign(l.color, l.color + 3);
            g.intensity = l.intensity;
            g.range = l.range;
            g.spot.innerConeAngle = l.inner_cone;
            g.spot.outerConeAngle = l.outer_cone;
            m_.lights.push_back(g);
        }
        if (s_.n_lights)
            use_ext("KHR_lights_punctual");
    }

    void validate_nodes()
    {
        for (uint32_t i = 0; i < s_.n_nodes; i++) {
            const scene_node &n = s_.nodes[i];
            const std::string what = "node " + num(i);
            if (n.parent >= (int)s_.n_nodes || n.parent == (int)i)
                throw write_error(what + ": parent index out of range");
            uint32_t steps = 0;
            for (int p = n.parent; p >= 0; p = s_.nodes[p].parent)
                if (++steps > s_.n_nodes)
                    throw write_error("the node hierarchy has a cycle");
            if (n.mesh != SCENE_NONE && n.mesh >= s_.n_meshes)
                throw write_error(what + ": mesh index out of range");
            if (n.camera != SCENE_NONE && n.camera >= s_.n_cameras)
                throw write_error(what + ": camera index out of range");
            if (n.light != SCENE_NONE && n.light >= s_.n_lights)
                throw write_error(what + ": light index out of range");
        }
        for (uint32_t r = 0; r < s_.n_roots; r++)
            if (s_.roots[r] >= s_.n_nodes || s_.nodes[s_.roots[r]].parent >= 0)
                throw write_error("root " + num(r) + " is not a parentless node");
    }

    void write_nodes()
    {
        m_.nodes.resize(s_.n_nodes);
        for (uint32_t i = 0; i < s_.n_nodes; i++) {
            const scene_node &n = s_.nodes[i];
            tinygltf::Node &g = m_.nodes[i];
            g.name = n.name;
            if (n.has_matrix) {
                g.matrix.assign(16, 0.0);
                for (int r = 0; r < 3; r++)
                    for (int c = 0; c < 4; c++)
                        g.matrix[(size_t)c * 4 + (size_t)r] = n.matrix.m[r][c]; // column-major
                g.matrix[15] = 1.0;
                for (double x : g.matrix)
                    if (!std::isfinite(x))
                        throw write_error("node " + num(i) + ": non-finite matrix");
            } else {
                for (int k = 0; k < 3; k++)
                    if (!std::isfinite(n.translation[k]) || !std::isfinite(n.scale[k]))
                        throw write_error("node " + num(i) + ": non-finite transformation");
                if (n.translation[0] != 0 || n.translation[1] != 0 || n.translation[2] != 0)
                    g.translation.assign(n.translation, n.translation + 3);
                if (n.rotation[0] != 0 || n.rotation[1] != 0 || n.rotation[2] != 0 || n.rotation[3] != 1)
                    g.rotation.assign(n.rotation, n.rotation + 4);
                if (n.scale[0] != 1 || n.scale[1] != 1 || n.scale[2] != 1)
                    g.scale.assign(n.scale, n.scale + 3);
            }
            if (n.mesh != SCENE_NONE)
                g.mesh = (int)n.mesh;
            if (n.mesh != SCENE_NONE && s_.meshes[n.mesh].joints && s_.meshes[n.mesh].skin < s_.n_skins)
                g.skin = (int)s_.meshes[n.mesh].skin;
            if (n.camera != SCENE_NONE)
                g.camera = (int)n.camera;
            if (n.light != SCENE_NONE) {
                tinygltf::Value::Object o;
                o["light"] = tinygltf::Value((int)n.light);
                g.extensions["KHR_lights_punctual"] = tinygltf::Value(std::move(o));
            }
            if (n.weights && n.n_weights)
                g.weights.assign(n.weights, n.weights + n.n_weights);
            if (n.parent >= 0)
                m_.nodes[(size_t)n.parent].children.push_back((int)i);
        }
        tinygltf::Scene sc;
        sc.name = "scene";
        for (uint32_t r = 0; r < s_.n_roots; r++)
            sc.nodes.push_back((int)s_.roots[r]);
        m_.scenes.push_back(sc);
        m_.defaultScene = 0;
    }

    // ---- skins ---------------------------------------------------------------------------

    void write_skins()
    {
        for (uint32_t i = 0; i < s_.n_skins; i++) {
            const scene_skin &k = s_.skins[i];
            tinygltf::Skin g;
            std::vector<float> ibm;
            for (uint32_t j = 0; j < k.n_joints; j++) {
                if (k.joints[j] >= s_.n_nodes)
                    throw write_error("skin " + num(i) + ": joint node out of range");
                g.joints.push_back((int)k.joints[j]);
                for (int c = 0; c < 4; c++) // column-major 4x4
                    for (int r = 0; r < 4; r++)
                        ibm.push_back(r < 3 ? (float)k.inverse_bind[j].m[r][c] : (float)(c == 3));
            }
            if (!finite(ibm.data(), ibm.size()))
                throw write_error("skin " + num(i) + ": non-finite inverse bind matrix");
            if (!ibm.empty())
                g.inverseBindMatrices = add_floats(ibm, 16, -1, false);
            m_.skins.push_back(std::move(g));
        }
    }

    // ---- animations ----------------------------------------------------------------------

    void write_animations()
    {
        for (uint32_t ai = 0; ai < s_.n_animations; ai++) {
            const scene_animation &a = s_.animations[ai];
            tinygltf::Animation g;
            g.name = a.name;
            for (uint32_t ci = 0; ci < a.n_channels; ci++) {
                const scene_channel &c = a.channels[ci];
                const std::string what = "animation " + num(ai) + " channel " + num(ci);
                if (c.node >= s_.n_nodes)
                    throw write_error(what + ": node out of range");
                uint32_t want = c.path == ANIM_ROTATION ? 4 : c.path == ANIM_WEIGHTS ? s_.nodes[c.node].n_weights : 3;
                if (c.components != want || want == 0)
                    throw write_error(what + ": " + num(c.components) + " components, expected " + num(want));
                if (c.n_keys == 0 || !c.times || !c.values)
                    throw write_error(what + ": no keys");
                for (uint32_t k = 1; k < c.n_keys; k++)
                    if (!(c.times[k] > c.times[k - 1]))
                        throw write_error(what + ": key times must increase");
                const size_t nval = (size_t)c.n_keys * c.components * (c.interp == INTERP_CUBICSPLINE ? 3 : 1);
                if (!finite(c.times, c.n_keys) || !finite(c.values, nval))
                    throw write_error(what + ": non-finite key");
                tinygltf::AnimationSampler smp;
                smp.input = add_floats(std::vector<float>(c.times, c.times + c.n_keys), 1, 0, true);
                smp.output = add_floats(std::vector<float>(c.values, c.values + nval),
                                        c.path == ANIM_WEIGHTS ? 1 : (int)c.components, 0, false);
                smp.interpolation = c.interp == INTERP_STEP ? "STEP" : c.interp == INTERP_CUBICSPLINE ? "CUBICSPLINE" : "LINEAR";
                g.samplers.push_back(smp);
                tinygltf::AnimationChannel ch;
                ch.sampler = (int)g.samplers.size() - 1;
                ch.target_node = (int)c.node;
                ch.target_path = c.path == ANIM_TRANSLATION ? "translation"
                                 : c.path == ANIM_ROTATION  ? "rotation"
                                 : c.path == ANIM_SCALE     ? "scale"
                                                            : "weights";
                g.channels.push_back(ch);
            }
            if (g.channels.empty()) {
                std::fprintf(stderr, "saarcor: warning: animation %u has no channels and is not written\n", ai);
                continue;
            }
            m_.animations.push_back(std::move(g));
        }
    }
};



} // namespace

extern "C" int scene_write_gltf(const scene *s, const char *path, char *err, size_t errlen)
{
    const std::string p(path ? path : "");
    try {
        const bool binary = ends_with(p, ".glb");
        if (!binary && !ends_with(p, ".gltf")) {
            set_error(err, errlen, p + ": unknown extension (expected .gltf or .glb)");
            return -1;
        }
        tinygltf::Model model;
        Writer(*s, model).run();
        // tinygltf does not report a .glb that cannot be opened: check first
        std::FILE *f = std::fopen(path, binary ? "wb" : "w");
        if (!f) {
            set_error(err, errlen, p + ": " + std::strerror(errno));
            return -1;
        }
        std::fclose(f);
        tinygltf::TinyGLTF gltf;
        if (!gltf.WriteGltfSceneToFile(&model, p, true, true, !binary, binary)) {
            std::remove(path);
            set_error(err, errlen, p + ": cannot write the file");
            return -1;
        }
        f = std::fopen(path, "rb");
        long size = -1;
        if (f && std::fseek(f, 0, SEEK_END) == 0)
            size = std::ftell(f);
        if (f)
            std::fclose(f);
        if (size <= 0) {
            std::remove(path);
            set_error(err, errlen, p + ": write error");
            return -1;
        }
        return 0;
    } catch (const write_error &x) {
        set_error(err, errlen, p + ": " + x.what());
    } catch (const std::bad_alloc &) {
        set_error(err, errlen, p + ": out of memory");
    } catch (const std::exception &x) {
        set_error(err, errlen, p + ": " + x.what());
    } catch (...) {
        set_error(err, errlen, p + ": unknown error");
    }
    return -1;
}
