// The hair colour inversion against the forward model (issue: "a dense slab of fibres of
// the requested colour in a white furnace reflects that colour within 5 % per
// channel"): `pelage bench fur-colour` renders slabs of `pelage look`'s coat in the
// requested colour, on a skin of that colour, in a white furnace, and measures the
// fraction of light they reflect (three views, Gauss–Legendre), so what is checked is
// the converged path-traced coat, not the formula. The colours lie between the table's
// entries (renderer/bsdf/hair_coat_table.h), at another sample count, and so are the
// depths.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

void expect_slabs_within(const std::string &args, size_t slabs, double tolerance) {
    std::string out, err;
    ASSERT_EQ(
        run_pelage("bench fur-colour --presets '' --slab-spp 48 --threads 2 " + args,
                   &out, &err),
        0)
        << err;
    const auto j = nlohmann::json::parse(out);
    ASSERT_EQ(j["slab"].size(), slabs);
    for (const auto &run : j["slab"])
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(run["relative_error"][k].get<double>(), 0, tolerance)
                << run.dump();
    EXPECT_TRUE(j["presets"].empty());
}

// Coats about as deep as `pelage look`'s (two fibre cross-sections): the skin shows
// through, and the colour must still be the coat's.
TEST(FurColourCli, AThinCoatReflectsTheRequestedColour) {
    expect_slabs_within(
        "--slab-depths 2.8 --slab-colours 0.62,0.33,0.11 --slab-colours 0.18,0.09,0.045",
        2, 0.05);
}

// A coat deep enough to hide the skin (few paths reach it through ten cross-sections
// of these fibres), between two of the table's depths.
TEST(FurColourCli, ADeepCoatReflectsTheRequestedColour) {
    expect_slabs_within("--slab-depths 10 --slab-colours 0.18,0.09,0.045", 1, 0.05);
}

}  // namespace
}  // namespace pelage::test
