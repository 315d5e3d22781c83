// Cryptomatte ID mattes (Friedman and Jones 2015, "Fully Automatic ID Mattes with
// Support for Motion Blur and Transparency", SIGGRAPH poster; Psyop's Cryptomatte
// specification 1.2): each name (an object, a cell type, a cell) hashes to a float id;
// every pixel keeps the ids its samples saw with the share of the pixel's samples each
// covered, so a compositor rebuilds an antialiased matte of any set of names from the
// file alone.
//
// Accumulation keys are the renderer's own integers (the object's index, and the
// plugin's id in the object's matte layer); names are asked for, and hashed, only for
// the keys the finished image shows.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace pelage::renderer {

// MurmurHash3_x86_32 (Appleby), as the specification hashes names.
uint32_t murmur3_32(std::string_view data, uint32_t seed = 0);

// A name's id bits: its MurmurHash3 with the float exponent kept off 0 and 255, so the
// id is a normal finite float (the specification's uint32_to_float32 conversion).
uint32_t cryptomatte_hash(std::string_view name);
float cryptomatte_id(uint32_t hash);

// The metadata key of a layer: the first 7 hex digits of its name's MurmurHash3.
std::string cryptomatte_key(std::string_view layer_name);

// Per pixel and layer, up to `slots` (key, weight) pairs summed over samples. A sample
// whose key finds every slot taken by other keys is not counted in that layer (its
// share is lost from the matte, never given to another id).
class CryptomatteFilm {
  public:
    static constexpr uint64_t no_key = ~uint64_t(0);

    CryptomatteFilm(int width, int height, int layers, int slots);

    int layers() const { return m_layers; }
    int slots() const { return m_slots; }

    // Single writer per pixel (its tile's thread).
    void add(int x, int y, int layer, uint64_t key, float weight) {
        const size_t base =
            (size_t(y) * m_width + x) * m_layers * m_slots + size_t(layer) * m_slots;
        uint64_t *k = &m_keys[base];
        float *w = &m_weights[base];
        for (int s = 0; s < m_slots; ++s) {
            if (k[s] == key) {
                w[s] += weight;
                return;
            }
            if (k[s] == no_key) {
                k[s] = key;
                w[s] = weight;
                return;
            }
        }
    }

    struct Entry {
        uint64_t key;
        float weight;
    };
    // The pixel's entries in `layer`, heaviest first (ties: smaller key first, so the
    // order never depends on the order samples arrived in).
    std::vector<Entry> ranked(int x, int y, int layer) const;

  private:
    int m_width, m_height, m_layers, m_slots;
    std::vector<uint64_t> m_keys;
    std::vector<float> m_weights;
};

// One Cryptomatte layer as written: its name ("CryptoObject"), its channels
// (<name>00.R, .G, .B, .A, <name>01.R, ...: ranked id/coverage pairs) as planar float
// images, and the manifest of the names it shows.
struct CryptomatteLayer {
    std::string name;
    std::vector<std::string> channels;
    std::vector<std::vector<float>> planes;  // one per channel, width × height
    std::string manifest;                    // JSON {"name": "hex id", ...}
};

// Resolves `layer` of `film` into `ranks` ranked pairs. `coverage_of(x, y)` is the
// pixel's total sample weight (coverage is the share of it); `name_of(key)` names a
// key. Ids that collide (two names, one hash) are reported through `warn`.
CryptomatteLayer resolve_cryptomatte(
    const CryptomatteFilm &film, int layer, const std::string &name, int ranks, int width,
    int height, const std::function<float(int, int)> &total_weight,
    const std::function<std::string(uint64_t)> &name_of,
    const std::function<void(const std::string &)> &warn);

// "type" → "CryptoType": the layer name compositors list.
std::string cryptomatte_layer_name(const std::string &matte);

}  // namespace pelage::renderer
