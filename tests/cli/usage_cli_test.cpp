// The `pelage` command line itself: --version, the usage without a command, a mistyped
// command's "did you mean", and the defaults in --help.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

TEST(UsageCli, VersionIsOneLine) {
    std::string out, err;
    ASSERT_EQ(run_pelage("--version", &out, &err), 0) << err;
    EXPECT_EQ(out.rfind("pelage ", 0), 0u) << out;
    EXPECT_EQ(out.find('\n'), out.size() - 1) << out;
    EXPECT_EQ(err, "");
}

TEST(UsageCli, NoCommandPrintsTheCommandsAndExits2) {
    std::string out, err;
    EXPECT_EQ(run_pelage("", &out, &err), 2);
    for (const char *command : {"sim", "render", "shaders", "bench"})
        EXPECT_NE(err.find("\n  " + std::string(command) + " "), std::string::npos)
            << command << " not listed in:\n"
            << err;
    EXPECT_EQ(out, "");
    EXPECT_EQ(run_pelage("bench", &out, &err), 2);
    EXPECT_NE(err.find("\n  render "), std::string::npos) << err;
}

TEST(UsageCli, MistypedCommandSuggestsTheClosest) {
    std::string out, err;
    EXPECT_EQ(run_pelage("rendr scene.json", &out, &err), 2);
    EXPECT_EQ(err, "pelage: unknown command \"rendr\"; did you mean \"render\"?\n");
    EXPECT_EQ(out, "");
    EXPECT_EQ(run_pelage("bench rendr", &out, &err), 2);
    EXPECT_EQ(err, "pelage bench: unknown command \"rendr\"; did you mean \"render\"?\n");
    // Nothing close: the commands are listed instead.
    EXPECT_EQ(run_pelage("frobnicate", &out, &err), 2);
    EXPECT_NE(
        err.find("unknown command \"frobnicate\" (commands: look, explore, crps, sim,"),
        std::string::npos)
        << err;
}

// The --help line of `option`, with its continuation line when the type is long.
std::string help_entry(const std::string &help, const std::string &option) {
    std::istringstream in(help);
    std::string line, entry;
    while (std::getline(in, line)) {
        if (!entry.empty()) return line.rfind("    ", 0) == 0 ? entry + line : entry;
        if (line.find("  " + option + " ") != std::string::npos) entry = line;
    }
    return entry;
}

TEST(UsageCli, HelpShowsDefaults) {
    std::string out, err;
    ASSERT_EQ(run_pelage("sim --help", &out, &err), 0) << err;
    EXPECT_NE(help_entry(out, "--seed").find("=1 "), std::string::npos) << out;
    EXPECT_NE(help_entry(out, "--threads").find("=0"), std::string::npos) << out;
    // --initial-cells 0 means "the preset's count": no default shown.
    EXPECT_EQ(help_entry(out, "--initial-cells").find('='), std::string::npos) << out;
    ASSERT_EQ(run_pelage("render --help", &out, &err), 0) << err;
    EXPECT_NE(help_entry(out, "--step").find("=1"), std::string::npos) << out;
    // --spp takes 1 and up; its stored 0 means "film.spp" and is not shown.
    EXPECT_EQ(help_entry(out, "--spp").find("=0"), std::string::npos) << out;
}

}  // namespace
}  // namespace pelage::test
