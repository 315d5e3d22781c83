// `pelage shaders NAME` prints that plugin's own parameter table, row by row, and
// nothing else; an unknown NAME is exit 2 naming it and what is installed.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "renderer/core/install_layout.h"
#include "renderer/plugins/plugin_loader.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

renderer::LoadedPlugin load(const std::string &name) {
    return renderer::open_plugin(renderer::package_lib_dir() + "/shaders/" + name +
                                 ".so");
}

std::vector<std::string> lines_of(const std::string &text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

// The printed line for the table entry `name`: the one whose first word is the name.
std::string row_of(const std::vector<std::string> &lines, const std::string &name) {
    for (const std::string &l : lines) {
        std::istringstream words(l);
        std::string first;
        words >> first;
        if (first == name) return l;
    }
    return "";
}

TEST(ShadersCli, NamePrintsThatPluginsTable) {
    for (const char *name : {"worley", "perlin", "clonal_mosaic", "texture", "diffuse"}) {
        std::string out, err;
        ASSERT_EQ(run_pelage(std::string("shaders ") + name, &out, &err), 0) << err;
        const std::vector<std::string> lines = lines_of(out);
        ASSERT_FALSE(lines.empty());
        EXPECT_EQ(lines[0].rfind(std::string(name) + " - ", 0), 0u) << out;
        const renderer::LoadedPlugin p = load(name);
        size_t entries = 0;
        for (const PelageParamSpec *s = p.desc->params; s->name; ++s, ++entries) {
            const std::string row = row_of(lines, s->name);
            ASSERT_FALSE(row.empty()) << name << ": no row for " << s->name << "\n"
                                      << out;
            EXPECT_NE(row.find(renderer::param_type_name(s->type)), std::string::npos)
                << row;
            EXPECT_NE(row.find(s->doc), std::string::npos) << row;
        }
        // The header, a row per entry, and the summary, file and AOV lines.
        EXPECT_EQ(lines.size(), entries + 4) << out;
        if (p.desc->aov_names) {
            for (const char *const *a = p.desc->aov_names; *a; ++a) {
                EXPECT_NE(out.find(std::string("shader.") + *a), std::string::npos);
            }
        }
    }
}

TEST(ShadersCli, WorleyTableHasDefaultsAndRanges) {
    std::string out;
    ASSERT_EQ(run_pelage("shaders worley", &out), 0);
    const std::vector<std::string> lines = lines_of(out);
    EXPECT_NE(row_of(lines, "parameter").find("range"), std::string::npos) << out;
    const std::string frequency = row_of(lines, "frequency");
    EXPECT_NE(frequency.find(" 20 "), std::string::npos) << frequency;
    EXPECT_NE(frequency.find("[1e-06, 1e+06]"), std::string::npos) << frequency;
    const std::string spot = row_of(lines, "spot_colour");
    EXPECT_NE(spot.find("[0.08, 0.04, 0.02]"), std::string::npos) << spot;
    EXPECT_NE(spot.find("[0, 1]"), std::string::npos) << spot;
    EXPECT_NE(out.find("AOVs: shader.f1, shader.f2, shader.feature"), std::string::npos);
    // Only worley: no other plugin's summary.
    EXPECT_EQ(out.find("perlin"), std::string::npos) << out;
}

TEST(ShadersCli, UnknownNameIsExit2NamingWhatIsInstalled) {
    std::string out, err;
    EXPECT_EQ(run_pelage("shaders no_such_shader", &out, &err), 2);
    EXPECT_EQ(out, "");
    EXPECT_NE(err.find("no shader plugin \"no_such_shader\""), std::string::npos) << err;
    EXPECT_NE(err.find("worley"), std::string::npos) << err;
    EXPECT_EQ(run_pelage("shaders no_such_shader --json", &out, &err), 2);
    EXPECT_NE(err.find("no_such_shader"), std::string::npos) << err;
}

}  // namespace
}  // namespace pelage::test
