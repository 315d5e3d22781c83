// Where tests find the project's data, and a per-test scratch directory.
#pragma once

#include <filesystem>
#include <string>

namespace pelage::test {

// scenes/meshes/<name> in the source tree; fails the calling test (not skips) when the
// sample meshes were not fetched: run scenes/fetch_meshes.sh (the quick start does).
std::string sample_mesh(const std::string &name);
std::string source_path(const std::string &relative);

// A fresh, empty directory for this test, removed by the destructor.
class TempDir {
  public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir &) = delete;
    TempDir &operator=(const TempDir &) = delete;
    std::filesystem::path path() const { return m_path; }
    std::string file(const std::string &name) const { return (m_path / name).string(); }
    // Writes `contents` to file(name) and returns its path.
    std::string write(const std::string &name, const std::string &contents) const;

  private:
    std::filesystem::path m_path;
};

// Runs the pelage binary with `args` (shell-quoted by the caller); captures stderr into
// *err when given. Returns the exit code.
int run_pelage(const std::string &args, std::string *out = nullptr, std::string *err = nullptr);

}  // namespace pelage::test
