// The shared core of sim/core: the integer mixer, the vector types and the invariant
// checks every layer builds on.
#include <gtest/gtest.h>

#include "sim/core/hash.h"

namespace pelage {
namespace {

// SplitMix64 seeded with 0 (Steele et al. 2014): its first outputs, as the reference
// implementation prints them. A change to the mixer changes every random stream.
TEST(CoreHash, SplitMix64MatchesReferenceSequence) {
    EXPECT_EQ(splitmix64(0), 0xe220a8397b1dcdafull);
    EXPECT_EQ(splitmix64(golden_gamma), 0x6e789e6aa1b965f4ull);
    EXPECT_EQ(splitmix64(2 * golden_gamma), 0x06c45d188009454full);
    EXPECT_EQ(mix64(golden_gamma), splitmix64(0));
    static_assert(mix64(0) == 0);
}

}  // namespace
}  // namespace pelage
