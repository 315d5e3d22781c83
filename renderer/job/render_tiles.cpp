#include "renderer/job/render_tiles.h"

#include <climits>
#include <cstddef>

#include "sim/core/input_error.h"

namespace pelage::renderer {

std::string TileSpec::label() const {
    return std::to_string(index) + "/" + std::to_string(count);
}

namespace {

// Digits only, no sign or space, within an int.
bool read_count(const std::string &s, size_t begin, size_t end, int *value) {
    if (begin >= end) return false;
    long long v = 0;
    for (size_t i = begin; i < end; ++i) {
        if (s[i] < '0' || s[i] > '9') return false;
        v = 10 * v + (s[i] - '0');
        if (v > INT_MAX) return false;
    }
    *value = int(v);
    return true;
}

}  // namespace

TileSpec parse_tile(const std::string &text, const std::string &flag) {
    const size_t slash = text.find('/');
    TileSpec t;
    if (slash == std::string::npos || !read_count(text, 0, slash, &t.index) ||
        !read_count(text, slash + 1, text.size(), &t.count))
        throw InputError("", 0, flag,
                         "\"" + text + "\": expected TILE/TILES, e.g. 3/16 (1-based)");
    if (t.count < 1 || t.index < 1 || t.index > t.count)
        throw InputError("", 0, flag,
                         "\"" + text + "\": the tile is 1 to " + std::to_string(t.count) +
                             " (1-based; Slurm's 0-based task id + 1)");
    return t;
}

void tile_rows(const TileSpec &tile, int height, int *y0, int *y1,
               const std::string &flag) {
    if (tile.count > height)
        throw InputError(
            "", 0, flag,
            tile.label() + ": " + std::to_string(tile.count) +
                " tiles need an image at least that many rows high (it has " +
                std::to_string(height) + ")");
    *y0 = int((long long)(tile.index - 1) * height / tile.count);
    *y1 = int((long long)tile.index * height / tile.count);
}

std::vector<float> tile_pixels(const std::vector<float> &pixels, int height, int y0,
                               int y1) {
    const size_t row = pixels.size() / size_t(height);
    return std::vector<float>(pixels.begin() + ptrdiff_t(row * size_t(y0)),
                              pixels.begin() + ptrdiff_t(row * size_t(y1)));
}

void describe_tile(const TileSpec &tile, int width, int height, int y0, int y1,
                   uint64_t samples, int spp, ImageMetadata *meta) {
    meta->x = 0;
    meta->y = y0;
    meta->full_width = width;
    meta->full_height = height;
    meta->spp = spp;
    meta->mean_spp = double(samples) / (double(width) * (y1 - y0));
    meta->strings.push_back({tile_attribute, tile.label()});
    meta->strings.push_back({tile_samples_attribute, std::to_string(samples)});
}

}  // namespace pelage::renderer
