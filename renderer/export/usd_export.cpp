#include "renderer/export/usd_export.h"

#include <cstring>
#include <functional>
#include <set>
#include <stdexcept>

#include "renderer/export/usda_writer.h"

namespace pelage::renderer {
namespace {

template <class T>
struct Span {
    const T *data = nullptr;
    size_t elements = 0;  // numbers, not tuples
    bool operator==(const Span &o) const {
        return elements == o.elements &&
               (elements == 0 || std::memcmp(data, o.data, elements * sizeof(T)) == 0);
    }
};

template <class T>
Span<T> span_of(const std::vector<T> &v) {
    return {v.data(), v.size()};
}

// One attribute over the frames: its single value when every frame has the same, else
// time samples.
class FrameAttributes {
  public:
    FrameAttributes(UsdaWriter &w, const UsdStageInfo &info, size_t frames)
        : m_w(w), m_info(info), m_frames(frames) {}

    void floats(std::string_view decl, int tuple, std::string_view interp,
                const std::function<Span<float>(size_t)> &get) {
        if (constant(get)) {
            const Span<float> s = get(0);
            m_w.array(decl, s.data, s.elements / size_t(tuple), tuple, interp);
            return;
        }
        m_w.begin_time_samples(decl, interp);
        for (size_t f = 0; f < m_frames; ++f) {
            const Span<float> s = get(f);
            m_w.sample(m_info.times[f], s.data, s.elements / size_t(tuple), tuple);
        }
        m_w.end_time_samples();
    }
    void ints(std::string_view decl, std::string_view interp,
              const std::function<Span<int32_t>(size_t)> &get) {
        if (constant(get)) {
            const Span<int32_t> s = get(0);
            m_w.array(decl, s.data, s.elements, interp);
            return;
        }
        m_w.begin_time_samples(decl, interp);
        for (size_t f = 0; f < m_frames; ++f) {
            const Span<int32_t> s = get(f);
            m_w.sample(m_info.times[f], s.data, s.elements);
        }
        m_w.end_time_samples();
    }
    // The object's transform, as USD's row-vector matrix (translation in the last row).
    void transform(const std::function<const Affine &(size_t)> &get) {
        auto to_usd = [](const Affine &a, double m[16]) {
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) m[4 * r + c] = a.m[c][r];
            for (int r = 0; r < 3; ++r) m[4 * r + 3] = 0;
            for (int c = 0; c < 3; ++c) m[12 + c] = a.m[c][3];
            m[15] = 1;
        };
        bool same = true;
        for (size_t f = 1; f < m_frames; ++f)
            same = same && std::memcmp(&get(f), &get(0), sizeof(Affine)) == 0;
        double m[16];
        if (same) {
            to_usd(get(0), m);
            m_w.matrix("matrix4d xformOp:transform", m);
        } else {
            m_w.begin_time_samples("matrix4d xformOp:transform");
            for (size_t f = 0; f < m_frames; ++f) {
                to_usd(get(f), m);
                m_w.sample_matrix(m_info.times[f], m);
            }
            m_w.end_time_samples();
        }
        m_w.line("uniform token[] xformOpOrder = [\"xformOp:transform\"]");
    }

  private:
    template <class T>
    bool constant(const std::function<Span<T>(size_t)> &get) const {
        for (size_t f = 1; f < m_frames; ++f)
            if (!(get(f) == get(0))) return false;
        return true;
    }
    UsdaWriter &m_w;
    const UsdStageInfo &m_info;
    size_t m_frames;
};

std::string quoted(const std::string &s) {
    std::string q = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') q += '\\';
        q += c;
    }
    return q + "\"";
}

void check_frames(const std::vector<CoatFrame> &frames, const UsdStageInfo &info) {
    if (frames.empty()) throw std::invalid_argument("no frame to export");
    if (frames.size() > 1 && info.times.size() != frames.size())
        throw std::invalid_argument("one time code per frame is needed");
    const CoatFrame &a = frames[0];
    for (const CoatFrame &b : frames) {
        if (b.skins.size() != a.skins.size() || b.grooms.size() != a.grooms.size())
            throw std::invalid_argument("the frames export different objects");
        for (size_t k = 0; k < a.skins.size(); ++k)
            if (b.skins[k].name != a.skins[k].name ||
                b.skins[k].indices != a.skins[k].indices)
                throw std::invalid_argument("object \"" + a.skins[k].name +
                                            "\" changes its triangles between frames");
        for (size_t k = 0; k < a.grooms.size(); ++k)
            if (b.grooms[k].skin != a.grooms[k].skin ||
                b.grooms[k].cubic != a.grooms[k].cubic ||
                b.grooms[k].points_per_strand != a.grooms[k].points_per_strand)
                throw std::invalid_argument("the fur of \"" +
                                            a.skins[a.grooms[k].skin].name +
                                            "\" changes its kind between frames");
    }
}

void write_material(UsdaWriter &w, const std::string &path, const CoatSkin &skin) {
    w.begin_prim("Material", "pattern");
    w.line("token outputs:surface.connect = <" + path +
           "/pattern/surface.outputs:surface>");
    w.begin_prim("Shader", "surface");
    w.line("uniform token info:id = \"UsdPreviewSurface\"");
    w.line("color3f inputs:diffuseColor.connect = <" + path +
           "/pattern/texture.outputs:rgb>");
    w.line("float inputs:roughness = 0.6");
    w.line("token outputs:surface");
    w.end_prim();
    w.begin_prim("Shader", "texture");
    w.line("uniform token info:id = \"UsdUVTexture\"");
    w.line("asset inputs:file = @" + skin.texture + "@");
    w.line("token inputs:sourceColorSpace = \"sRGB\"");
    w.line("float2 inputs:st.connect = <" + path + "/pattern/st.outputs:result>");
    w.line("float3 outputs:rgb");
    w.end_prim();
    w.begin_prim("Shader", "st");
    w.line("uniform token info:id = \"UsdPrimvarReader_float2\"");
    w.line("string inputs:varname = \"st\"");
    w.line("float2 outputs:result");
    w.end_prim();
    w.end_prim();
}

}  // namespace

void write_coat_usda(std::ostream &out, const std::vector<CoatFrame> &frames,
                     const UsdStageInfo &info) {
    check_frames(frames, info);
    const size_t nf = frames.size();
    UsdaWriter w(out);
    w.line("#usda 1.0");
    w.line("(");
    {
        std::vector<std::string> meta = {"defaultPrim = \"coat\""};
        if (!info.doc.empty()) meta.push_back("doc = " + quoted(info.doc));
        char buf[64];
        std::snprintf(buf, sizeof buf, "metersPerUnit = %.17g", info.meters_per_unit);
        meta.push_back(buf);
        std::snprintf(buf, sizeof buf, "timeCodesPerSecond = %.17g", info.fps);
        meta.push_back(buf);
        if (nf > 1) {
            std::snprintf(buf, sizeof buf, "startTimeCode = %.17g", info.times.front());
            meta.push_back(buf);
            std::snprintf(buf, sizeof buf, "endTimeCode = %.17g", info.times.back());
            meta.push_back(buf);
        }
        meta.push_back(std::string("upAxis = \"") + info.up_axis + "\"");
        for (const std::string &m : meta) w.line("    " + m);
    }
    w.line(")");
    w.line("");
    w.begin_prim("Xform", "coat", {"kind = \"assembly\""});
    FrameAttributes attr(w, info, nf);
    std::set<std::string> used;
    const CoatFrame &first = frames[0];
    for (size_t k = 0; k < first.skins.size(); ++k) {
        const CoatSkin &skin = first.skins[k];
        std::string name = usd_identifier(skin.name);
        while (!used.insert(name).second) name += "_";
        const std::string path = "/coat/" + name;
        w.begin_prim("Xform", name);
        attr.transform(
            [&](size_t f) -> const Affine & { return frames[f].skins[k].to_world; });

        std::vector<std::string> skin_meta;
        if (!skin.texture.empty())
            skin_meta.push_back("prepend apiSchemas = [\"MaterialBindingAPI\"]");
        w.begin_prim("Mesh", "skin", skin_meta);
        w.line("uniform token subdivisionScheme = \"none\"");
        w.line("uniform token orientation = \"rightHanded\"");
        const std::vector<int32_t> counts(skin.num_triangles(), 3);
        w.array("int[] faceVertexCounts", counts.data(), counts.size());
        w.array("int[] faceVertexIndices",
                reinterpret_cast<const int32_t *>(skin.indices.data()),
                skin.indices.size());
        auto sk = [&](size_t f) -> const CoatSkin & { return frames[f].skins[k]; };
        attr.floats("point3f[] points", 3, {},
                    [&](size_t f) { return span_of(sk(f).points); });
        if (!skin.normals.empty())
            attr.floats("normal3f[] normals", 3, "faceVarying",
                        [&](size_t f) { return span_of(sk(f).normals); });
        if (!skin.uvs.empty())
            attr.floats("texCoord2f[] primvars:st", 2, "faceVarying",
                        [&](size_t f) { return span_of(sk(f).uvs); });
        attr.floats("color3f[] primvars:displayColor", 3, "uniform",
                    [&](size_t f) { return span_of(sk(f).face_colour); });
        attr.ints("int[] primvars:cell_type", "uniform",
                  [&](size_t f) { return span_of(sk(f).face_cell_type); });
        attr.ints("int[] primvars:cell_id", "uniform",
                  [&](size_t f) { return span_of(sk(f).face_cell_id); });
        if (!skin.texture.empty())
            w.line("rel material:binding = <" + path + "/pattern>");
        w.end_prim();
        if (!skin.texture.empty()) write_material(w, path, skin);

        for (size_t g = 0; g < first.grooms.size(); ++g) {
            if (first.grooms[g].skin != k) continue;
            const CoatGroom &groom = first.grooms[g];
            auto gr = [&](size_t f) -> const CoatGroom & { return frames[f].grooms[g]; };
            // Root UVs and strand ids per frame, kept alive while they are written.
            std::vector<std::vector<float>> uvs(nf);
            std::vector<std::vector<int32_t>> counts_of(nf), ids(nf);
            for (size_t f = 0; f < nf; ++f) {
                uvs[f] = root_uvs(frames[f].skins[k], gr(f));
                counts_of[f].assign(gr(f).size(), int32_t(gr(f).points_per_strand));
                ids[f].resize(gr(f).size());
                for (size_t s = 0; s < ids[f].size(); ++s) ids[f][s] = int32_t(s);
            }
            w.begin_prim("BasisCurves", groom.cubic ? "fur" : "fur_ribbons");
            if (groom.cubic) {
                w.line("uniform token type = \"cubic\"");
                w.line("uniform token basis = \"bspline\"");
            } else {
                w.line("uniform token type = \"linear\"");
            }
            w.line("uniform token wrap = \"nonperiodic\"");
            attr.ints("int[] curveVertexCounts", {},
                      [&](size_t f) { return span_of(counts_of[f]); });
            attr.floats("point3f[] points", 3, {},
                        [&](size_t f) { return span_of(gr(f).points); });
            attr.floats("float[] widths", 1, "vertex",
                        [&](size_t f) { return span_of(gr(f).widths); });
            attr.floats("color3f[] primvars:displayColor", 3, "uniform",
                        [&](size_t f) { return span_of(gr(f).colour); });
            attr.ints("int[] primvars:cell_type", "uniform",
                      [&](size_t f) { return span_of(gr(f).cell_type); });
            attr.ints("int[] primvars:cell_id", "uniform",
                      [&](size_t f) { return span_of(gr(f).cell_id); });
            if (!uvs[0].empty())
                attr.floats("texCoord2f[] primvars:root_uv", 2, "uniform",
                            [&](size_t f) { return span_of(uvs[f]); });
            // Unreal's groom importer reads these names (its groom_* attributes).
            attr.floats("color3f[] primvars:groom_color", 3, "uniform",
                        [&](size_t f) { return span_of(gr(f).colour); });
            attr.floats("float[] primvars:groom_width", 1, "vertex",
                        [&](size_t f) { return span_of(gr(f).widths); });
            if (!uvs[0].empty())
                attr.floats("float2[] primvars:groom_root_uv", 2, "uniform",
                            [&](size_t f) { return span_of(uvs[f]); });
            attr.ints("int[] primvars:groom_id", "uniform",
                      [&](size_t f) { return span_of(ids[f]); });
            w.end_prim();
        }
        w.end_prim();
    }
    w.end_prim();
}

}  // namespace pelage::renderer
