// Reading Cryptomatte back from an EXR (what a compositor does): the layers and their
// manifests, and the matte of a set of names — per pixel, the coverage summed over the
// ranks whose id is one of theirs (the Cryptomatte specification's decoding).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace pelage::renderer {

struct CryptomatteManifest {
    std::string layer;                    // "CryptoObject"
    std::map<std::string, uint32_t> ids;  // name → id bits
};

// Every Cryptomatte layer the file's header describes. Throws pelage::InputError naming
// the file when it cannot be read or a manifest is not JSON.
std::vector<CryptomatteManifest> read_cryptomatte_manifests(const std::string &path);

// The matte of the names matching `patterns` ('*' matches any run of characters) in
// `layer` ("CryptoType", or "type"), width × height floats in [0, 1]. Throws
// pelage::InputError naming the file and the layer or pattern when there is no such
// layer or a pattern matches no name.
struct Matte {
    int width = 0, height = 0;
    std::vector<float> alpha;
    std::vector<std::string> names;  // the names matched
};
Matte read_cryptomatte_matte(const std::string &path, const std::string &layer,
                             const std::vector<std::string> &patterns);

}  // namespace pelage::renderer
