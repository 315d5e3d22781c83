// Frame lists: every accepted form, and every refusal naming the offending item.
#include "renderer/job/frame_list.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sim/core/input_error.h"

namespace pelage::renderer {
namespace {

std::vector<int> frames(const std::string &spec, int step = 1) {
    return expand_frames(parse_frame_ranges(spec, step));
}

TEST(FrameList, AcceptsSinglesListsRangesAndSteps) {
    EXPECT_EQ(frames("7"), std::vector<int>({7}));
    EXPECT_EQ(frames("1,5,9"), std::vector<int>({1, 5, 9}));
    EXPECT_EQ(frames("3-6"), std::vector<int>({3, 4, 5, 6}));
    EXPECT_EQ(frames("1-20x5"), std::vector<int>({1, 6, 11, 16}));
    EXPECT_EQ(frames("0-20x5,33"), std::vector<int>({0, 5, 10, 15, 20, 33}));
    EXPECT_EQ(frames("4-4x3"), std::vector<int>({4}));
    const std::vector<int> vfx = frames("1001-1120");
    ASSERT_EQ(vfx.size(), 120u);
    EXPECT_EQ(vfx.front(), 1001);
    EXPECT_EQ(vfx.back(), 1120);
    // Sorted, each frame once, whatever order and overlap the items have.
    EXPECT_EQ(frames("9,1,5-6,5"), std::vector<int>({1, 5, 6, 9}));
}

TEST(FrameList, StepOptionAppliesToRangesWithoutTheirOwn) {
    EXPECT_EQ(frames("0-9", 3), std::vector<int>({0, 3, 6, 9}));
    EXPECT_EQ(frames("2,0-4", 2), std::vector<int>({0, 2, 4}));
    const auto r = parse_frame_ranges("10-20", 5);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].step, 5);
    EXPECT_EQ(r[0].text, "10-20");
}

// The refusal's message, "" when the spec is accepted.
std::string refusal(const std::string &spec, int step = 1) {
    try {
        parse_frame_ranges(spec, step);
    } catch (const InputError &e) {
        EXPECT_EQ(e.field(), "--frames");
        return e.what();
    }
    return "";
}

TEST(FrameList, RefusesMalformedItemsNamingThem) {
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"", "no frames"},
        {"5 9", "\"5 9\""},
        {" 5", "\" 5\""},
        {"5,", "an empty item"},
        {",5", "an empty item"},
        {"1,,2", "an empty item"},
        {"7abc", "unexpected \"abc\""},
        {"1-5,7abc", "\"7abc\""},
        {"9-3", "runs backwards"},
        {"0-119x0", "step must be"},
        {"0-119x-2", "step must be"},
        {"0-119x", "step must be"},
        {"5x2", "unexpected \"x2\""},
        {"-3", "not a frame number"},
        {"+3", "not a frame number"},
        {"3-", "a last frame"},
        {"1-2-3", "unexpected \"-3\""},
        {"1.5", "unexpected \".5\""},
        {"99999999999", "too large"},
        {"0-99999999999", "too large"},
        {"0-10x99999999999", "step must be"},
    };
    for (const auto &[spec, why] : bad) {
        const std::string msg = refusal(spec);
        EXPECT_NE(msg.find(why), std::string::npos) << spec << " -> " << msg;
    }
    EXPECT_NE(refusal("0-10x2", 3).find("both --step"), std::string::npos);
}

}  // namespace
}  // namespace pelage::renderer
