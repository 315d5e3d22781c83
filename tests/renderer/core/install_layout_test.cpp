// Where an installation's parts are found: next to the running executable (this test
// binary in build/bin, whose build tree has an installation's layout), with
// $PELAGE_DATA_DIR searched first for each data file or folder.
#include "renderer/core/install_layout.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

// Sets $PELAGE_DATA_DIR for the scope of a test and restores it afterwards.
class DataDirVariable {
  public:
    explicit DataDirVariable(const std::string &value) {
        if (const char *old = std::getenv("PELAGE_DATA_DIR")) m_old = old, m_had = true;
        setenv("PELAGE_DATA_DIR", value.c_str(), 1);
    }
    ~DataDirVariable() {
        if (m_had)
            setenv("PELAGE_DATA_DIR", m_old.c_str(), 1);
        else
            unsetenv("PELAGE_DATA_DIR");
    }

  private:
    std::string m_old;
    bool m_had = false;
};

TEST(InstallLayout, FoldersAreNextToTheExecutablesBin) {
    char self[4096];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
    ASSERT_GT(n, 0);
    const fs::path exe(std::string(self, size_t(n)));
    EXPECT_EQ(renderer::executable_dir(), exe.parent_path().string());
    // In the build tree, as in an installation under its prefix.
    const std::string build = exe.parent_path().parent_path().string() + "/";
    const std::string lib = renderer::package_lib_dir(),
                      share = renderer::package_data_dir();
    EXPECT_EQ(lib.rfind(build, 0), 0u) << lib;
    EXPECT_EQ(share.rfind(build, 0), 0u) << share;
    EXPECT_TRUE(fs::exists(lib + "/libpelage_cli.so")) << lib;
    EXPECT_TRUE(fs::exists(lib + "/shaders/clonal_mosaic.so")) << lib;
    EXPECT_TRUE(fs::exists(share + "/ocio/config.ocio")) << share;
}

TEST(InstallLayout, CodeFileIsTheBinaryHoldingTheCode) {
    // Linked statically into this test; into lib/pelage/libpelage_cli.so in `pelage`.
    EXPECT_EQ(renderer::code_file(), fs::read_symlink("/proc/self/exe").string());
}

TEST(InstallLayout, DataDirIsSearchedFirstThenShare) {
    TempDir tmp;
    fs::create_directories(tmp.path() / "scenes" / "presets");
    const std::string share = renderer::package_data_dir();
    {
        DataDirVariable data_dir("");
        // Empty means unset: the build tree's share/pelage, which links the checkout's
        // scenes/.
        EXPECT_EQ(renderer::find_data("scenes/presets"), share + "/scenes/presets");
        EXPECT_TRUE(fs::exists(fs::path(share) / "scenes/presets/walter-cheetah.json"));
    }
    DataDirVariable data_dir(tmp.path().string());
    EXPECT_EQ(renderer::find_data("scenes/presets"), tmp.file("scenes/presets"));
    // Not in $PELAGE_DATA_DIR: the one next to the executable.
    EXPECT_EQ(renderer::find_data("ocio/config.ocio"), share + "/ocio/config.ocio");
    // Nowhere: where $PELAGE_DATA_DIR would have it, for the error message.
    EXPECT_EQ(renderer::find_data("ocio/missing.ocio"), tmp.file("ocio/missing.ocio"));
}

}  // namespace
}  // namespace pelage::test
