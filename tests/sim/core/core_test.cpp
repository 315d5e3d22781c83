// The shared core in sim/core: the integer mixer, the vector types and the invariant
// checks every layer builds on.
#include <gtest/gtest.h>

#include "sim/core/check.h"
#include "sim/core/hash.h"
#include "sim/core/vec.h"

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

// operator/ multiplies by one rounded reciprocal; divide_exactly() divides each
// component. Code that needs one cannot use the other without moving results by an ulp.
TEST(CoreVec3f, DivisionsRoundAsDocumented) {
    const Vec3f v{1, 2, 10};
    const float s = 3;
    const float inv = 1.0f / s;
    EXPECT_EQ(v / s, (Vec3f{1 * inv, 2 * inv, 10 * inv}));
    EXPECT_EQ(divide_exactly(v, s), (Vec3f{1 / s, 2 / s, 10 / s}));
    EXPECT_EQ(normalize(Vec3f{0, 3, 4}), (Vec3f{0, 0.6f, 0.8f}));
}

TEST(CoreCheck, PassingChecksDoNothing) {
    PELAGE_CHECK(1 + 1 == 2);
    PELAGE_DCHECK(1 + 1 == 2);
}

TEST(CoreCheckDeathTest, CheckPrintsFileLineAndConditionAndAborts) {
    EXPECT_DEATH(PELAGE_CHECK(1 + 1 == 3),
                 "core_test.cpp:[0-9]+: check failed: 1 \\+ 1 == 3");
}

TEST(CoreCheckDeathTest, DcheckIsCompiledOutWithNdebug) {
#ifdef NDEBUG
    int evaluated = 0;
    PELAGE_DCHECK(++evaluated == 5);
    EXPECT_EQ(evaluated, 0);  // the condition is never evaluated
#else
    EXPECT_DEATH(PELAGE_DCHECK(2 < 1), "check failed: 2 < 1");
#endif
}

}  // namespace
}  // namespace pelage
