#include "tests/test_paths.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

namespace pelage::test {

std::string source_path(const std::string &relative) {
    return (std::filesystem::path(PELAGE_SOURCE_DIR) / relative).string();
}

std::string sample_mesh(const std::string &name) {
    const std::string p = source_path("scenes/meshes/" + name);
    if (!std::filesystem::exists(p))
        ADD_FAILURE() << p << " is missing: run scenes/fetch_meshes.sh";
    return p;
}

TempDir::TempDir() {
    const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device rd;
    m_path = std::filesystem::temp_directory_path() /
             ("pelage_test_" + std::string(info ? info->name() : "x") + "_" + std::to_string(rd()));
    std::filesystem::create_directories(m_path);
}

TempDir::~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(m_path, ec);
}

std::string TempDir::write(const std::string &name, const std::string &contents) const {
    const std::string p = file(name);
    std::ofstream(p, std::ios::binary) << contents;
    return p;
}

namespace {
std::string slurp(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}
}  // namespace

int run_pelage(const std::string &args, std::string *out, std::string *err) {
    TempDir tmp;
    const std::string cmd = std::string(PELAGE_BINARY) + " " + args + " >" + tmp.file("out") +
                            " 2>" + tmp.file("err");
    const int status = std::system(cmd.c_str());
    if (out) *out = slurp(tmp.file("out"));
    if (err) *err = slurp(tmp.file("err"));
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace pelage::test
