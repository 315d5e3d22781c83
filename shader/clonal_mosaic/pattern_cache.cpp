#include "shader/clonal_mosaic/pattern_cache.h"

#include <deque>
#include <filesystem>
#include <map>
#include <mutex>
#include <tuple>

#include "sim/cells_io/cells_file.h"

namespace pelage::shader::clonal_mosaic {

namespace {

namespace fs = std::filesystem;

// What makes a pattern: the file as it is on disk, the mesh, the neighbourhood.
using Key = std::tuple<std::string, uintmax_t, int64_t, uint64_t, int>;

// The last patterns made stay alive after their instances: between two frames no
// instance holds the pattern (a frame's scene goes before the next one's is built).
constexpr size_t kept_alive = 2;

struct Cache {
    std::mutex mutex;
    std::map<Key, std::weak_ptr<const pattern::mosaic::MosaicPattern>> by_key;
    std::deque<std::shared_ptr<const pattern::mosaic::MosaicPattern>> recent;
};

Cache &cache() {
    static Cache c;
    return c;
}

}  // namespace

std::shared_ptr<const pattern::mosaic::MosaicPattern> cached_pattern(
    const std::string &cells_path, sim::TriangleMesh rest, const std::string &mesh_name,
    pattern::mosaic::Neighbourhood neighbourhood) {
    std::error_code ec;
    const fs::path path = fs::absolute(cells_path, ec).lexically_normal();
    const uintmax_t size = fs::file_size(path, ec);
    const int64_t written =
        ec ? 0 : int64_t(fs::last_write_time(path, ec).time_since_epoch().count());
    if (ec)  // unreadable: the pattern's own error says so
        return std::make_shared<const pattern::mosaic::MosaicPattern>(
            cells_path, std::move(rest), mesh_name, neighbourhood);
    const Key key{path.string(), size, written, sim::mesh_hash(rest), int(neighbourhood)};
    Cache &c = cache();
    std::lock_guard<std::mutex> lock(c.mutex);
    if (auto it = c.by_key.find(key); it != c.by_key.end())
        if (auto found = it->second.lock()) return found;
    auto made = std::make_shared<const pattern::mosaic::MosaicPattern>(
        cells_path, std::move(rest), mesh_name, neighbourhood);
    c.by_key[key] = made;
    c.recent.push_back(made);
    if (c.recent.size() > kept_alive) c.recent.pop_front();
    for (auto it = c.by_key.begin(); it != c.by_key.end();)
        it = it->second.expired() ? c.by_key.erase(it) : std::next(it);
    return made;
}

}  // namespace pelage::shader::clonal_mosaic
