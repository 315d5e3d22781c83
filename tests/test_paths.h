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

// A small two-type preset file (F dark, B light, no division: the cells are the initial
// ones) written into `tmp` as two_types.json; returns its path.
std::string two_type_preset(const TempDir &tmp, int initial_cells,
                            double f_probability = 0.3);

// `pelage sim` of a small two-type mosaic (F dark 10 %..40 %, B light) on `mesh`, as a
// user would run it; returns the .cells path inside `tmp`. F is type 0 with colour (0.1,
// 0.05, 0.02) and eumelanin 0.8, B type 1 with (0.9, 0.6, 0.3) and pheomelanin 0.5.
std::string simulate_two_type_cells(const TempDir &tmp, const std::string &mesh,
                                    int initial_cells, double f_probability = 0.3,
                                    uint64_t seed = 2);

// The whole file as bytes (empty when it cannot be read).
std::string slurp(const std::string &path);

// Runs the pelage binary with `args` (shell-quoted by the caller); captures stderr into
// *err when given. Returns the exit code.
int run_pelage(const std::string &args, std::string *out = nullptr,
               std::string *err = nullptr);

// `timeout --preserve-status -s INT N ` for a command that a test interrupts with Ctrl-C
// once it is rendering: N = 3 s, or 30 s under ThreadSanitizer, where loading the scene
// alone takes seconds and an earlier signal would arrive before the handler.
inline std::string interrupt_after() {
#if defined(__SANITIZE_THREAD__)
    return "timeout --preserve-status -s INT 30 ";
#else
    return "timeout --preserve-status -s INT 3 ";
#endif
}

}  // namespace pelage::test
