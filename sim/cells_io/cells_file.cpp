#include "sim/cells_io/cells_file.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>

#include "sim/core/atomic_file.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_clean.h"

namespace pelage::sim {

static_assert(std::endian::native == std::endian::little,
              ".cells I/O copies little-endian values directly");

namespace {

constexpr char magic[8] = {'P', 'E', 'L', 'C', 'E', 'L', 'L', 'S'};
constexpr size_t header_bytes = 80;
constexpr size_t frame_doubles = 22;
// Bounds that keep every size computation far from overflow.
constexpr uint64_t max_triangles = 1ull << 31, max_cells = 1ull << 32,
                   max_maps = 1ull << 32;
constexpr uint64_t max_params_bytes = 64ull << 20;

uint64_t fnv1a(const uint8_t *p, size_t n, uint64_t h = 0xcbf29ce484222325ull) {
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

class Writer {
  public:
    template <typename T>
    void put(const T &v) {
        const auto *p = reinterpret_cast<const uint8_t *>(&v);
        m_bytes.insert(m_bytes.end(), p, p + sizeof(T));
    }
    template <typename T>
    void put_array(const std::vector<T> &v) {
        const auto *p = reinterpret_cast<const uint8_t *>(v.data());
        m_bytes.insert(m_bytes.end(), p, p + v.size() * sizeof(T));
    }
    void put_bytes(const std::string &s) {
        m_bytes.insert(m_bytes.end(), s.begin(), s.end());
    }
    std::vector<uint8_t> &bytes() { return m_bytes; }

  private:
    std::vector<uint8_t> m_bytes;
};

class Reader {
  public:
    Reader(const std::vector<uint8_t> &b, size_t end, std::string name)
        : m_b(b), m_end(end), m_name(std::move(name)) {}
    [[noreturn]] void fail(const std::string &field, const std::string &msg) const {
        throw InputError(m_name, 0, field, msg);
    }
    void need(size_t n, const char *field) const {
        if (n > m_end - m_pos) fail(field, "truncated");
    }
    template <typename T>
    T get(const char *field) {
        need(sizeof(T), field);
        T v;
        std::memcpy(&v, m_b.data() + m_pos, sizeof(T));
        m_pos += sizeof(T);
        return v;
    }
    template <typename T>
    void get_array(std::vector<T> &v, uint64_t n, const char *field) {
        if (n > (m_end - m_pos) / sizeof(T)) fail(field, "truncated");
        v.resize(n);
        if (n == 0) return;  // memcpy from/to an empty vector's null data() is UB
        std::memcpy(v.data(), m_b.data() + m_pos, n * sizeof(T));
        m_pos += n * sizeof(T);
    }
    std::string get_string(uint64_t n, const char *field) {
        need(n, field);
        std::string s(reinterpret_cast<const char *>(m_b.data() + m_pos), n);
        m_pos += n;
        return s;
    }
    size_t pos() const { return m_pos; }
    void seek(size_t p) { m_pos = p; }

  private:
    const std::vector<uint8_t> &m_b;
    size_t m_end;
    size_t m_pos = 0;
    std::string m_name;
};

}  // namespace

double CellsData::area() const {
    double a = 0;
    for (const auto &f : frames) a += f.area;
    return a;
}

bool CellsData::operator==(const CellsData &o) const {
    return serialize_cells(*this) == serialize_cells(o);
}

uint64_t mesh_hash(const TriangleMesh &mesh) {
    const uint64_t nt = mesh.num_triangles();
    uint64_t h = fnv1a(reinterpret_cast<const uint8_t *>(&nt), sizeof nt);
    h = fnv1a(reinterpret_cast<const uint8_t *>(mesh.positions.data()),
              mesh.positions.size() * sizeof(Vec3d), h);
    return fnv1a(reinterpret_cast<const uint8_t *>(mesh.triangles.data()),
                 mesh.triangles.size() * sizeof(mesh.triangles[0]), h);
}

std::vector<uint8_t> serialize_cells(const CellsData &d) {
    Writer w;
    w.bytes().insert(w.bytes().end(), magic, magic + 8);
    w.put<uint32_t>(cells_file_version);
    w.put<uint32_t>(static_cast<uint32_t>(d.types.size()));
    w.put<uint64_t>(d.mesh_hash);
    w.put<uint64_t>(d.frames.size());
    w.put<uint64_t>(d.x.size());
    w.put<uint64_t>(d.nbr.size());
    w.put<uint64_t>(d.seed);
    w.put<uint64_t>(d.params_json.size());
    const size_t payload_at = w.bytes().size();
    w.put<uint64_t>(0);  // payload_bytes, patched below
    w.put<uint64_t>(0);  // reserved
    // --- payload ---
    w.put_bytes(d.params_json);
    for (const CellsFileType &t : d.types) {
        w.put<uint32_t>(static_cast<uint32_t>(t.name.size()));
        w.put_bytes(t.name);
        for (float c : t.colour) w.put<float>(c);
        w.put<float>(t.eumelanin);
        w.put<float>(t.pheomelanin);
        w.put<double>(t.division_time);
        w.put<double>(t.initial_probability);
    }
    for (const CrpsFrame &f : d.frames) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) w.put<double>(f.rotation.m[i][j]);
        w.put<double>(f.normal.x);
        w.put<double>(f.normal.y);
        w.put<double>(f.normal.z);
        w.put<double>(f.y_offset);
        w.put<double>(f.centre.x);
        w.put<double>(f.centre.y);
        for (const Vec2d &v : f.v) {
            w.put<double>(v.x);
            w.put<double>(v.y);
        }
        w.put<double>(f.area);
    }
    w.put_array(d.nbr_row);
    w.put_array(d.nbr);
    for (const RigidMap2 &F : d.to_master) {
        w.put(F.c);
        w.put(F.s);
        w.put(F.ax);
        w.put(F.ay);
    }
    w.put_array(d.cell_row);
    w.put_array(d.x);
    w.put_array(d.z);
    w.put_array(d.type);
    w.put_array(d.id);
    std::vector<uint32_t> founder = d.founder;
    if (founder.empty()) founder = d.id;  // no lineage known: each cell its own clone
    w.put_array(founder);
    const uint64_t payload = w.bytes().size() - header_bytes;
    std::memcpy(w.bytes().data() + payload_at, &payload, sizeof payload);
    w.put<uint64_t>(fnv1a(w.bytes().data(), w.bytes().size()));
    return std::move(w.bytes());
}

namespace {

// The magic and the version, the first 12 bytes of a file at least `header_bytes` long;
// `r` reads on after them.
uint32_t read_version(Reader &r, const std::vector<uint8_t> &b) {
    if (std::memcmp(b.data(), magic, 8) != 0) r.fail("magic", "not a .cells file");
    r.seek(8);
    const uint32_t version = r.get<uint32_t>("version");
    if (version != cells_file_version && version != 1)
        r.fail("version", "unsupported version " + std::to_string(version) +
                              " (this build reads " + std::to_string(cells_file_version) +
                              ")");
    return version;
}

}  // namespace

CellsData parse_cells(const std::vector<uint8_t> &b, const std::string &name) {
    // --- Header, and sizes against the file size before anything is allocated ---
    if (b.size() < header_bytes + 8)
        throw InputError(name, 0, "header", "truncated: not a .cells file");
    Reader r(b, b.size(), name);
    const uint32_t version = read_version(r, b);
    CellsData d;
    const uint32_t num_types = r.get<uint32_t>("num_types");
    d.mesh_hash = r.get<uint64_t>("mesh_hash");
    const uint64_t nt = r.get<uint64_t>("num_triangles");
    const uint64_t nc = r.get<uint64_t>("num_cells");
    const uint64_t nm = r.get<uint64_t>("num_maps");
    d.seed = r.get<uint64_t>("seed");
    const uint64_t params_bytes = r.get<uint64_t>("params_bytes");
    const uint64_t payload = r.get<uint64_t>("payload_bytes");
    r.get<uint64_t>("reserved");
    if (num_types < 1 || num_types > cells_file_max_types)
        r.fail("num_types", "must be 1 to 8");
    if (nt < 1 || nt > max_triangles) r.fail("num_triangles", "out of range");
    if (nc >= max_cells) r.fail("num_cells", "out of range");
    if (nm > max_maps) r.fail("num_maps", "out of range");
    if (params_bytes > max_params_bytes) r.fail("params_bytes", "out of range");
    if (payload != b.size() - header_bytes - 8)
        r.fail("payload_bytes",
               "file size " + std::to_string(b.size()) +
                   " does not match the header (truncated or padded file)");
    const uint64_t fixed = params_bytes + nt * (frame_doubles * 8 + 8) + 8 +
                           nm * (4 + 32) + nc * (8 + 8 + 1 + 4 + (version >= 2 ? 4 : 0));
    if (fixed > payload)
        r.fail("payload_bytes", "counts in the header exceed the file size");

    // --- Checksum over header and payload ---
    uint64_t stored;
    std::memcpy(&stored, b.data() + b.size() - 8, 8);
    if (fnv1a(b.data(), b.size() - 8) != stored)
        r.fail("checksum", "mismatch: the file is corrupted");

    Reader p(b, b.size() - 8, name);
    p.seek(header_bytes);
    d.params_json = p.get_string(params_bytes, "params");
    for (uint32_t i = 0; i < num_types; ++i) {
        CellsFileType t;
        const uint32_t len = p.get<uint32_t>("types.name");
        if (len < 1 || len > 64)
            p.fail("types[" + std::to_string(i) + "].name", "bad length");
        t.name = p.get_string(len, "types.name");
        for (float &c : t.colour) c = p.get<float>("types.colour");
        t.eumelanin = p.get<float>("types.eumelanin");
        t.pheomelanin = p.get<float>("types.pheomelanin");
        t.division_time = p.get<double>("types.division_time");
        t.initial_probability = p.get<double>("types.initial_probability");
        d.types.push_back(std::move(t));
    }
    std::vector<double> fr;
    p.get_array(fr, nt * frame_doubles, "frames");
    d.frames.resize(nt);
    for (uint64_t t = 0; t < nt; ++t) {
        const double *q = fr.data() + t * frame_doubles;
        CrpsFrame &f = d.frames[t];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) f.rotation.m[i][j] = *q++;
        f.normal = {q[0], q[1], q[2]};
        q += 3;
        f.y_offset = *q++;
        f.centre = {q[0], q[1]};
        q += 2;
        for (auto &v : f.v) {
            v = {q[0], q[1]};
            q += 2;
        }
        f.area = *q;
    }
    p.get_array(d.nbr_row, nt + 1, "nbr_row");
    p.get_array(d.nbr, nm, "nbr");
    std::vector<double> maps;
    p.get_array(maps, nm * 4, "maps");
    d.to_master.resize(nm);
    for (uint64_t k = 0; k < nm; ++k)
        d.to_master[k] = {maps[4 * k], maps[4 * k + 1], maps[4 * k + 2], maps[4 * k + 3]};
    p.get_array(d.cell_row, nt + 1, "cell_row");
    p.get_array(d.x, nc, "x");
    p.get_array(d.z, nc, "z");
    p.get_array(d.type, nc, "type");
    p.get_array(d.id, nc, "id");
    if (version >= 2) p.get_array(d.founder, nc, "founder");
    if (p.pos() != b.size() - 8) p.fail("payload", "trailing bytes after the cells");

    // --- Structure ---
    if (d.nbr_row[0] != 0 || d.nbr_row[nt] != nm)
        p.fail("nbr_row", "does not span the maps");
    if (d.cell_row[0] != 0 || d.cell_row[nt] != nc)
        p.fail("cell_row", "does not span the cells");
    for (uint64_t t = 0; t < nt; ++t) {
        if (d.nbr_row[t] > d.nbr_row[t + 1])
            p.fail("nbr_row", "not monotone at triangle " + std::to_string(t));
        if (d.cell_row[t] > d.cell_row[t + 1])
            p.fail("cell_row", "not monotone at triangle " + std::to_string(t));
    }
    for (TriId j : d.nbr)
        if (j >= nt)
            p.fail("nbr", "triangle index " + std::to_string(j) + " out of range");
    for (uint64_t c = 0; c < nc; ++c) {
        if (d.type[c] >= num_types)
            p.fail("type", "cell " + std::to_string(c) + " has type " +
                               std::to_string(d.type[c]) + " of " +
                               std::to_string(num_types));
        if (!std::isfinite(d.x[c]) || !std::isfinite(d.z[c]))
            p.fail("x", "non-finite cell position");
        // A clone's founder exists before its descendants.
        if (!d.founder.empty() && d.founder[c] > d.id[c])
            p.fail("founder", "cell " + std::to_string(d.id[c]) + " names founder " +
                                  std::to_string(d.founder[c]) + ", created after it");
    }
    return d;
}

void write_cells_file(const std::string &path, const CellsData &data) {
    const std::vector<uint8_t> bytes = serialize_cells(data);
    write_file_atomically(path, [&](std::ostream &out) {
        out.write(reinterpret_cast<const char *>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
    });
}

CellsData read_cells_file(const std::string &path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw InputError(path, 0, "", "cannot open .cells file");
    const std::streamoff size = in.tellg();
    if (size < 0) throw InputError(path, 0, "", "cannot read .cells file");
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    in.seekg(0);
    if (!in.read(reinterpret_cast<char *>(bytes.data()), size))
        throw InputError(path, 0, "", "read failed");
    return parse_cells(bytes, path);
}

std::string read_cells_params(const std::string &path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw InputError(path, 0, "", "cannot open .cells file");
    const std::streamoff size = in.tellg();
    std::vector<uint8_t> head(header_bytes);
    in.seekg(0);
    if (size < std::streamoff(header_bytes + 8) ||
        !in.read(reinterpret_cast<char *>(head.data()), std::streamsize(header_bytes)))
        throw InputError(path, 0, "header", "truncated: not a .cells file");
    Reader r(head, head.size(), path);
    read_version(r, head);
    r.seek(56);  // past num_types, mesh_hash, the three counts and the seed
    const uint64_t params_bytes = r.get<uint64_t>("params_bytes");
    if (params_bytes > max_params_bytes ||
        params_bytes > uint64_t(size) - header_bytes - 8)
        r.fail("params_bytes", "out of range");
    std::string params(size_t(params_bytes), '\0');
    if (!in.read(params.data(), std::streamsize(params_bytes)))
        throw InputError(path, 0, "params", "read failed");
    return params;
}

TriangleMesh surface_mesh(const CellsData &data, const std::string &path) {
    TriangleMesh corners;
    corners.positions.reserve(3 * data.num_triangles());
    for (const CrpsFrame &f : data.frames) {
        const VertId first = static_cast<VertId>(corners.positions.size());
        for (int c = 0; c < 3; ++c)
            corners.positions.push_back(f.rotation.transpose_times(
                {f.v[c].x + f.centre.x, f.y_offset, f.v[c].y + f.centre.y}));
        corners.triangles.push_back({first, first + 1, first + 2});
        corners.source_face.push_back(
            static_cast<uint32_t>(corners.triangles.size() - 1));
    }
    // The corners carried back from the frames differ from the grown surface's only by
    // double rounding, so they are welded at 1e-9 of the size, never at a loaded mesh's
    // 1e-5: the surface may be pelage sim's own copy split at its edge midpoints, whose
    // triangles can be smaller than that, and no triangle may be lost (the cells' frames
    // are this surface's triangles one by one). Its pieces were stitched when it was
    // loaded.
    MeshCleanOptions options;
    options.weld_relative = 1e-9;
    options.stitch_relative = 0;
    options.area_relative = 0;
    TriangleMesh mesh = clean_mesh(corners, path, options);
    if (mesh.num_triangles() != data.num_triangles())
        throw InputError(path, 0, "frames",
                         std::to_string(data.num_triangles() - mesh.num_triangles()) +
                             " of the file's " + std::to_string(data.num_triangles()) +
                             " triangles are degenerate: the file is damaged");
    return mesh;
}

void check_cells_match_mesh(const CellsData &data, const TriangleMesh &mesh,
                            const std::string &path) {
    if (data.num_triangles() != mesh.num_triangles() || data.mesh_hash != mesh_hash(mesh))
        throw InputError(path, 0, "mesh_hash",
                         "made for a different mesh (" +
                             std::to_string(data.num_triangles()) + " triangles, hash " +
                             std::to_string(data.mesh_hash) + "; this mesh has " +
                             std::to_string(mesh.num_triangles()) + " triangles, hash " +
                             std::to_string(mesh_hash(mesh)) + ")");
}

int find_type(const CellsData &d, const std::string &name, int fallback) {
    for (size_t i = 0; i < d.types.size(); ++i)
        if (d.types[i].name == name) return static_cast<int>(i);
    return fallback < static_cast<int>(d.types.size()) ? fallback : -1;
}

}  // namespace pelage::sim
