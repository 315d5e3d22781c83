// The "did you mean" of a mistyped command: edit distances against values worked by
// hand, and which names are close enough to suggest.
#include "sim/core/spelling.h"

#include <gtest/gtest.h>

namespace pelage::sim {
namespace {

TEST(CommandSuggestion, EditDistanceOfKnownPairs) {
    EXPECT_EQ(edit_distance("", ""), 0u);
    EXPECT_EQ(edit_distance("", "sim"), 3u);
    EXPECT_EQ(edit_distance("render", "render"), 0u);
    EXPECT_EQ(edit_distance("rendr", "render"), 1u);    // deletion
    EXPECT_EQ(edit_distance("renderr", "render"), 1u);  // insertion
    EXPECT_EQ(edit_distance("rander", "render"), 1u);   // substitution
    EXPECT_EQ(edit_distance("redner", "render"), 1u);   // adjacent swap
    // Levenshtein's textbook example: k->s, e->i, +g.
    EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
    // Optimal string alignment edits a substring once: "ca" -> "ac" -> "abc" would be
    // 2, but the swapped pair cannot then be split, so it is 3 (Damerau-Levenshtein
    // proper gives 2).
    EXPECT_EQ(edit_distance("ca", "abc"), 3u);
    EXPECT_EQ(edit_distance("abc", "ca"), 3u);
}

TEST(CommandSuggestion, SuggestsOnlyCloseNames) {
    const std::vector<std::string> names = {"crps",   "sim",     "stats", "preview",
                                            "render", "shaders", "cells", "bench"};
    EXPECT_EQ(closest_name("rendr", names), "render");
    EXPECT_EQ(closest_name("shader", names), "shaders");
    EXPECT_EQ(closest_name("sm", names), "sim");
    EXPECT_EQ(closest_name("bnech", names), "bench");
    EXPECT_EQ(closest_name("frobnicate", names), "");
    // Two edits on a three-letter name are another word, not a typo.
    EXPECT_EQ(closest_name("sxy", names), "");
    // A tie goes to the first name listed.
    EXPECT_EQ(closest_name("ab", {"abc", "abd"}), "abc");
    EXPECT_EQ(closest_name("render", {}), "");
}

}  // namespace
}  // namespace pelage::sim
