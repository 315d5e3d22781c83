// An XXH3-64 digest of inputs fed piece by piece: what identifies a mesh's or a scene's
// content (a cached pattern's mesh_xxh3, a render's settings hash).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace pelage {

class ContentHash {
  public:
    ContentHash();
    ~ContentHash();
    void add(const std::string &text);  // its bytes and a terminating NUL
    // The file's name and content; a missing file adds its name only.
    void add_file(const std::string &path);
    uint64_t digest() const;
    std::string hex() const;  // 16 lower-case hex digits

  private:
    struct State;
    std::unique_ptr<State> m_state;
};

}  // namespace pelage
