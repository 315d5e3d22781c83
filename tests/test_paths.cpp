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
             ("pelage_test_" + std::string(info ? info->name() : "x") + "_" +
              std::to_string(rd()));
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

std::string slurp(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string two_type_preset(const TempDir &tmp, int initial_cells, double f_probability) {
    return tmp.write("two_types.json",
                     R"({"name": "t", "types": [
        {"name": "F", "colour": [0.1, 0.05, 0.02], "eumelanin": 0.8, "division_time": "never",
         "initial_probability": )" +
                         std::to_string(f_probability) +
                         R"(},
        {"name": "B", "colour": [0.9, 0.6, 0.3], "pheomelanin": 0.5, "division_time": "never",
         "initial_probability": )" +
                         std::to_string(1 - f_probability) +
                         R"(}],
        "adhesion": [[0.5, 0.0], [0.0, 0.5]],
        "simulation": {"initial_cells": )" +
                         std::to_string(initial_cells) +
                         R"(, "initial_relax_steps": 10,
                       "w_r": 2.0, "w_d": 0.1, "rho": 5, "end_time": 1, "relax": "global"}})");
}

std::string simulate_two_type_cells(const TempDir &tmp, const std::string &mesh,
                                    int initial_cells, double f_probability,
                                    uint64_t seed) {
    const std::string preset = two_type_preset(tmp, initial_cells, f_probability);
    const std::string cells = tmp.file("mosaic.cells");
    std::string err;
    EXPECT_EQ(run_pelage("sim --mesh " + mesh + " --preset " + preset + " -o " + cells +
                             " --seed " + std::to_string(seed),
                         nullptr, &err),
              0)
        << err;
    return cells;
}

int run_pelage(const std::string &args, std::string *out, std::string *err) {
    TempDir tmp;
    const std::string cmd = std::string(PELAGE_BINARY) + " " + args + " >" +
                            tmp.file("out") + " 2>" + tmp.file("err");
    const int status = std::system(cmd.c_str());
    if (out) *out = slurp(tmp.file("out"));
    if (err) *err = slurp(tmp.file("err"));
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace pelage::test
