// The hair colour inversion against the forward model (issue: "a dense slab of fibres
// of the requested colour in a white furnace reflects that colour within 5 % per
// channel"): `pelage bench fur-colour` renders the slab with the renderer, so what is
// checked is the converged path-traced slab, not the formula. The colours lie between
// the table's entries (renderer/bsdf/hair_colour_table.h), at another sample count.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

TEST(FurColourCli, AThickSlabReflectsTheRequestedColour) {
    std::string out, err;
    ASSERT_EQ(run_pelage("bench fur-colour --presets '' --slab-spp 48 --threads 2 "
                         "--slab-colours 0.62,0.33,0.11 --slab-colours 0.18,0.09,0.045",
                         &out, &err),
              0)
        << err;
    const auto j = nlohmann::json::parse(out);
    ASSERT_EQ(j["slab"].size(), 2u);
    for (const auto &run : j["slab"])
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(run["relative_error"][k].get<double>(), 0, 0.05) << run.dump();
    EXPECT_TRUE(j["presets"].empty());
}

}  // namespace
}  // namespace pelage::test
