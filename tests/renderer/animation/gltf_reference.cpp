#include "tests/renderer/animation/gltf_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using json = nlohmann::json;
using Mat4 = std::array<double, 16>;
using Vec3 = GltfReference::Vec3;

std::string base64_decode(const std::string &s) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+') return 62;
        if (c == '/') return 63;
        return -1;
    };
    std::string out;
    uint32_t bits = 0;
    int n = 0;
    for (char c : s) {
        const int v = value(c);
        if (v < 0) continue;  // '=' padding
        bits = bits << 6 | uint32_t(v);
        if ((n += 6) >= 8) {
            n -= 8;
            out.push_back(char((bits >> n) & 0xff));
        }
    }
    return out;
}

Mat4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Mat4 mul(const Mat4 &a, const Mat4 &b) {
    Mat4 r{};
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row)
            for (int k = 0; k < 4; ++k) r[c * 4 + row] += a[k * 4 + row] * b[c * 4 + k];
    return r;
}

Vec3 point(const Mat4 &m, const Vec3 &p) {
    Vec3 r;
    for (int row = 0; row < 3; ++row)
        r[row] = m[row] * p[0] + m[4 + row] * p[1] + m[8 + row] * p[2] + m[12 + row];
    return r;
}

// T · R · S (§3.5.3), the rotation a unit quaternion (x, y, z, w).
Mat4 trs(const std::array<double, 3> &t, std::array<double, 4> q,
         const std::array<double, 3> &s) {
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double &c : q) c /= n;
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    Mat4 m = identity();
    const double r[3][3] = {
        {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
        {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
        {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    for (int row = 0; row < 3; ++row)
        for (int c = 0; c < 3; ++c) m[c * 4 + row] = r[row][c] * s[size_t(c)];
    for (int row = 0; row < 3; ++row) m[12 + row] = t[size_t(row)];
    return m;
}

template <size_t N>
std::array<double, N> array_of(const json &j, std::array<double, N> fallback) {
    if (!j.is_array()) return fallback;
    std::array<double, N> a{};
    for (size_t i = 0; i < N; ++i) a[i] = j[i].get<double>();
    return a;
}

}  // namespace

GltfReference::GltfReference(const std::string &path) {
    const std::string bytes = slurp(path);
    if (bytes.size() >= 20 && bytes.compare(0, 4, "glTF") == 0) {
        // §4.4: a 12-byte header, then chunks of (length, type, data); JSON, then BIN.
        auto u32 = [&](size_t at) {
            uint32_t v;
            std::memcpy(&v, bytes.data() + at, 4);
            return v;
        };
        size_t at = 12;
        while (at + 8 <= bytes.size()) {
            const uint32_t length = u32(at), type = u32(at + 4);
            const std::string data = bytes.substr(at + 8, length);
            if (type == 0x4E4F534A) m_doc = json::parse(data);  // "JSON"
            if (type == 0x004E4942) m_buffers.push_back(data);  // "BIN\0"
            at += 8 + length;
        }
    } else {
        m_doc = json::parse(bytes);
        for (const json &b : m_doc["buffers"]) {
            const std::string uri = b["uri"];
            const auto comma = uri.find(',');
            if (uri.rfind("data:", 0) == 0)
                m_buffers.push_back(base64_decode(uri.substr(comma + 1)));
            else
                m_buffers.push_back(
                    slurp((std::filesystem::path(path).parent_path() / uri).string()));
        }
    }
}

std::vector<double> GltfReference::accessor(int index, int *components) const {
    const json &a = m_doc["accessors"][size_t(index)];
    if (a.contains("sparse")) throw std::runtime_error("sparse accessors not read");
    static const std::map<std::string, int> sizes = {
        {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT4", 16}};
    const int n = sizes.at(a["type"].get<std::string>());
    *components = n;
    const int type = a["componentType"];
    const int bytes = type == 5126 || type == 5125   ? 4
                      : type == 5123 || type == 5122 ? 2
                                                     : 1;
    const json &view = m_doc["bufferViews"][a["bufferView"].get<size_t>()];
    const std::string &buffer = m_buffers[view["buffer"].get<size_t>()];
    const size_t stride = view.value("byteStride", size_t(n * bytes));
    const size_t base =
        view.value("byteOffset", size_t(0)) + a.value("byteOffset", size_t(0));
    const bool normalized = a.value("normalized", false);
    const size_t count = a["count"];
    std::vector<double> out;
    for (size_t e = 0; e < count; ++e)
        for (int c = 0; c < n; ++c) {
            const char *p = buffer.data() + base + e * stride + size_t(c * bytes);
            double v = 0;
            if (type == 5126) {
                float f;
                std::memcpy(&f, p, 4);
                v = f;
            } else if (type == 5125) {
                uint32_t u;
                std::memcpy(&u, p, 4);
                v = u;
            } else if (type == 5123) {
                uint16_t u;
                std::memcpy(&u, p, 2);
                v = normalized ? u / 65535.0 : u;
            } else if (type == 5121) {
                v = normalized ? uint8_t(*p) / 255.0 : uint8_t(*p);
            } else {
                throw std::runtime_error("component type not read");
            }
            out.push_back(v);
        }
    return out;
}

int GltfReference::animation(const std::string &name) const {
    const json &anims = m_doc["animations"];
    for (size_t i = 0; i < anims.size(); ++i)
        if (anims[i].value("name", "") == name) return int(i);
    return -1;
}

// The node's local matrix: its TRS with the animated paths sampled (§3.11: linear,
// spherical linear for rotations, clamped to the first and last keys), or its matrix.
Mat4 GltfReference::local(int node, int animation, double seconds) const {
    const json &n = m_doc["nodes"][size_t(node)];
    if (n.contains("matrix")) {
        Mat4 m;
        for (size_t i = 0; i < 16; ++i) m[i] = n["matrix"][i];
        return m;
    }
    auto t = array_of<3>(n.value("translation", json()), {0, 0, 0});
    auto r = array_of<4>(n.value("rotation", json()), {0, 0, 0, 1});
    auto s = array_of<3>(n.value("scale", json()), {1, 1, 1});
    if (animation >= 0) {
        const json &anim = m_doc["animations"][size_t(animation)];
        for (const json &ch : anim["channels"]) {
            if (ch["target"].value("node", -1) != node) continue;
            const std::string what = ch["target"]["path"];
            const json &sampler = anim["samplers"][ch["sampler"].get<size_t>()];
            int nc, oc;
            const std::vector<double> in = accessor(sampler["input"], &nc);
            const std::vector<double> out = accessor(sampler["output"], &oc);
            const bool step = sampler.value("interpolation", "LINEAR") == "STEP";
            size_t i0 = 0, i1 = 0;
            double f = 0;
            if (seconds >= in.back()) {
                i0 = i1 = in.size() - 1;
            } else if (seconds > in.front()) {
                i1 = size_t(std::upper_bound(in.begin(), in.end(), seconds) - in.begin());
                i0 = i1 - 1;
                f = step ? 0 : (seconds - in[i0]) / (in[i1] - in[i0]);
            }
            auto value = [&](size_t k, size_t c) { return out[k * size_t(oc) + c]; };
            if (what == "rotation") {
                std::array<double, 4> a, b;
                for (size_t c = 0; c < 4; ++c) a[c] = value(i0, c), b[c] = value(i1, c);
                // Unit quaternions: stored floats are not quite, and two keys a fraction
                // of a degree apart can have a dot product above 1.
                for (auto *q : {&a, &b}) {
                    const double n = std::sqrt((*q)[0] * (*q)[0] + (*q)[1] * (*q)[1] +
                                               (*q)[2] * (*q)[2] + (*q)[3] * (*q)[3]);
                    for (double &c : *q) c /= n;
                }
                double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
                if (d < 0) {
                    for (double &c : b) c = -c;
                    d = -d;
                }
                const double theta = std::acos(std::min(d, 1.0));
                for (size_t c = 0; c < 4; ++c)
                    r[c] = theta < 1e-9 ? a[c]
                                        : (std::sin((1 - f) * theta) * a[c] +
                                           std::sin(f * theta) * b[c]) /
                                              std::sin(theta);
            } else if (what == "translation" || what == "scale") {
                auto &dst = what == "translation" ? t : s;
                for (size_t c = 0; c < 3; ++c)
                    dst[c] = (1 - f) * value(i0, c) + f * value(i1, c);
            }
        }
    }
    return trs(t, r, s);
}

std::vector<std::array<Vec3, 3>> GltfReference::triangles(int animation,
                                                          double seconds) const {
    const json &nodes = m_doc["nodes"];
    // Global matrices of every node reachable from the scene's roots.
    std::vector<Mat4> global(nodes.size(), identity());
    std::vector<int> preorder;
    auto walk = [&](auto &&self, int node, const Mat4 &parent) -> void {
        global[size_t(node)] = mul(parent, local(node, animation, seconds));
        preorder.push_back(node);
        for (const json &c : nodes[size_t(node)].value("children", json::array()))
            self(self, c.get<int>(), global[size_t(node)]);
    };
    const json &scene = m_doc["scenes"][m_doc.value("scene", size_t(0))];
    for (const json &root : scene["nodes"]) walk(walk, root.get<int>(), identity());

    std::vector<std::array<Vec3, 3>> out;
    for (int node : preorder) {
        const json &n = nodes[size_t(node)];
        if (!n.contains("mesh")) continue;
        const json &mesh = m_doc["meshes"][n["mesh"].get<size_t>()];
        // Morph weights: the animated node's, its own, or the mesh's defaults.
        std::vector<double> weights = n.contains("weights")
                                          ? n["weights"].get<std::vector<double>>()
                                          : mesh.value("weights", std::vector<double>());
        if (animation >= 0) {
            const json &anim = m_doc["animations"][size_t(animation)];
            for (const json &ch : anim["channels"]) {
                if (ch["target"].value("node", -1) != node ||
                    ch["target"]["path"] != "weights")
                    continue;
                const json &sampler = anim["samplers"][ch["sampler"].get<size_t>()];
                int nc, oc;
                const std::vector<double> in = accessor(sampler["input"], &nc);
                const std::vector<double> out_w = accessor(sampler["output"], &oc);
                const size_t k = out_w.size() / in.size();  // targets per key
                size_t i0 = 0, i1 = 0;
                double f = 0;
                if (seconds >= in.back()) {
                    i0 = i1 = in.size() - 1;
                } else if (seconds > in.front()) {
                    i1 = size_t(std::upper_bound(in.begin(), in.end(), seconds) -
                                in.begin());
                    i0 = i1 - 1;
                    f = (seconds - in[i0]) / (in[i1] - in[i0]);
                }
                weights.assign(k, 0);
                for (size_t c = 0; c < k; ++c)
                    weights[c] = (1 - f) * out_w[i0 * k + c] + f * out_w[i1 * k + c];
            }
        }
        // Joint matrices: G_joint · IBM (§3.7.3.1).
        std::vector<Mat4> joint;
        if (n.contains("skin")) {
            const json &skin = m_doc["skins"][n["skin"].get<size_t>()];
            int c;
            const std::vector<double> ibm = accessor(skin["inverseBindMatrices"], &c);
            for (size_t j = 0; j < skin["joints"].size(); ++j) {
                Mat4 m;
                for (size_t i = 0; i < 16; ++i) m[i] = ibm[16 * j + i];
                joint.push_back(mul(global[skin["joints"][j].get<size_t>()], m));
            }
        }
        for (const json &prim : mesh["primitives"]) {
            int c;
            const std::vector<double> pos = accessor(prim["attributes"]["POSITION"], &c);
            std::vector<Vec3> v(pos.size() / 3);
            for (size_t i = 0; i < v.size(); ++i)
                v[i] = {pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]};
            const json targets = prim.value("targets", json::array());
            for (size_t k = 0; k < targets.size() && k < weights.size(); ++k) {
                const std::vector<double> d = accessor(targets[k]["POSITION"], &c);
                for (size_t i = 0; i < v.size(); ++i)
                    for (size_t a = 0; a < 3; ++a) v[i][a] += weights[k] * d[3 * i + a];
            }
            if (!joint.empty()) {
                int jc, wc;
                const std::vector<double> js =
                    accessor(prim["attributes"]["JOINTS_0"], &jc);
                const std::vector<double> ws =
                    accessor(prim["attributes"]["WEIGHTS_0"], &wc);
                for (size_t i = 0; i < v.size(); ++i) {
                    Vec3 sum{0, 0, 0};
                    for (size_t k = 0; k < 4; ++k) {
                        const Vec3 p = point(joint[size_t(js[4 * i + k])], v[i]);
                        for (size_t a = 0; a < 3; ++a) sum[a] += ws[4 * i + k] * p[a];
                    }
                    v[i] = sum;
                }
            } else {
                for (Vec3 &p : v) p = point(global[size_t(node)], p);
            }
            const std::vector<double> idx = accessor(prim["indices"], &c);
            for (size_t t = 0; t + 2 < idx.size(); t += 3)
                out.push_back(
                    {v[size_t(idx[t])], v[size_t(idx[t + 1])], v[size_t(idx[t + 2])]});
        }
    }
    return out;
}

}  // namespace pelage::test
