// Replays fuzz inputs without libFuzzer, so the normal (GCC) build and CI run every seed,
// every corpus file and every crash reproducer ever found as a regular test:
//   fuzz_replay_<target> DIR_OR_FILE...
// Files are replayed in sorted order; a crash or sanitizer report fails the test, and the
// name of the file being replayed is printed first so the failure is easy to reproduce.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv) {
    namespace fs = std::filesystem;
    std::vector<fs::path> files;
    for (int a = 1; a < argc; ++a) {
        const fs::path p(argv[a]);
        if (fs::is_directory(p)) {
            for (const auto &e : fs::recursive_directory_iterator(p))
                if (e.is_regular_file()) files.push_back(e.path());
        } else if (fs::is_regular_file(p)) {
            files.push_back(p);
        } else {
            std::fprintf(stderr, "fuzz replay: %s: no such file or directory\n", argv[a]);
            return 2;
        }
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) {
        std::fprintf(stderr, "fuzz replay: no inputs (an empty corpus tests nothing)\n");
        return 2;
    }
    for (const fs::path &f : files) {
        std::fprintf(stderr, "replay %s\n", f.c_str());
        std::ifstream in(f, std::ios::binary);
        const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                      std::istreambuf_iterator<char>());
        LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t *>(bytes.data()),
                               bytes.size());
    }
    std::printf("fuzz replay: %zu inputs, no failure\n", files.size());
    return 0;
}
