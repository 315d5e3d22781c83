// Frame placeholders (####, %04d, $F4) format and match file names as written, and a
// sequence on disk is found with its step, its holes named.
#include "renderer/image/frame_pattern.h"

#include <gtest/gtest.h>

#include <fstream>

#include "renderer/image/frame_sequence.h"
#include "sim/core/input_error.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using namespace pelage::renderer;

TEST(FramePattern, EveryPlaceholderSpellingFormatsLikePrintf) {
    struct Case {
        const char *pattern;
        int frame;
        const char *expected;
    };
    const Case cases[] = {
        {"cow.####.exr", 7, "cow.0007.exr"},      {"cow.#.exr", 7, "cow.7.exr"},
        {"cow.##.exr", 123, "cow.123.exr"},       {"cow.%04d.exr", 7, "cow.0007.exr"},
        {"cow.%d.exr", 42, "cow.42.exr"},         {"cow.%06d.exr", 0, "cow.000000.exr"},
        {"cow.$F4.exr", 7, "cow.0007.exr"},       {"cow.$F.exr", 7, "cow.7.exr"},
        {"a#b.####.exr", 12345, "a#b.12345.exr"}, {"$F2_%03d", 5, "$F2_005"},
    };
    for (const Case &c : cases) {
        const auto p = parse_frame_pattern(c.pattern);
        ASSERT_TRUE(p) << c.pattern;
        char printf_ref[64];  // the independent reference for the padded number
        std::snprintf(printf_ref, sizeof printf_ref, "%0*d", p->width, c.frame);
        EXPECT_EQ(format_frame(*p, c.frame), c.expected) << c.pattern;
        EXPECT_NE(std::string(c.expected).find(printf_ref), std::string::npos)
            << c.pattern;
        EXPECT_EQ(match_frame(*p, c.expected), c.frame) << c.pattern;
    }
    const auto hashes = parse_frame_pattern("dir/cow.####.exr");
    ASSERT_TRUE(hashes);
    EXPECT_EQ(hashes->head, "dir/cow.");
    EXPECT_EQ(hashes->tail, ".exr");
    EXPECT_EQ(hashes->token, "####");
    EXPECT_EQ(parse_frame_pattern("cow.%04d.exr")->token, "%04d");
    EXPECT_EQ(parse_frame_pattern("cow.$F4.exr")->width, 4);
}

TEST(FramePattern, NoPlaceholderOrAnUnusableOneIsNone) {
    for (const char *s : {"cow.exr", "cow.%4d.exr", "cow.%0d.exr", "cow.%0xd.exr",
                          "cow.$G4.exr", "cow.###########.exr", "100%.exr"})
        EXPECT_FALSE(parse_frame_pattern(s)) << s;
}

TEST(FramePattern, MatchesOnlyWhatFormatWouldWrite) {
    const FramePattern p = *parse_frame_pattern("cow.####.exr");
    EXPECT_EQ(match_frame(p, "cow.0000.exr"), 0);
    EXPECT_EQ(match_frame(p, "cow.12345.exr"), 12345);
    for (const char *s : {"cow.007.exr", "cow.00007.exr", "cow.00a7.exr", "cow..exr",
                          "cow.0007.exr.tmp", "dog.0007.exr", "cow.99999999999.exr"})
        EXPECT_FALSE(match_frame(p, s)) << s;
    const FramePattern unpadded = *parse_frame_pattern("cow.%d.exr");
    EXPECT_EQ(match_frame(unpadded, "cow.0.exr"), 0);
    EXPECT_FALSE(match_frame(unpadded, "cow.07.exr"));
}

// What `pelage render` writes (substitute_frame) is what `pelage movie` reads back.
TEST(FramePattern, TokensOfEveryFormArePadded) {
    EXPECT_EQ(substitute_frame("out.####.exr", 7), "out.0007.exr");
    EXPECT_EQ(substitute_frame("out.#.exr", 7), "out.7.exr");
    EXPECT_EQ(substitute_frame("out.##.exr", 1001), "out.1001.exr");
    EXPECT_EQ(substitute_frame("out.%04d.exr", 7), "out.0007.exr");
    EXPECT_EQ(substitute_frame("out.%d.exr", 42), "out.42.exr");
    EXPECT_EQ(substitute_frame("out.$F4.exr", 7), "out.0007.exr");
    EXPECT_EQ(substitute_frame("out.$F.exr", 7), "out.7.exr");
    EXPECT_EQ(substitute_frame("out_$F6", 1001), "out_001001");
    // The last token is the frame; earlier ones stay as written.
    EXPECT_EQ(substitute_frame("take#2/out.###.exr", 5), "take#2/out.005.exr");
    EXPECT_EQ(substitute_frame("a%04d.$F2.exr", 5), "a%04d.05.exr");
    // Not tokens: a lone %, %s, %4d (space padding), $G, and no token at all.
    for (const std::string name :
         {"out.exr", "100%.exr", "out.%s.exr", "out.%4d.exr", "out.$G4.exr"}) {
        EXPECT_FALSE(has_frame_token(name)) << name;
        EXPECT_EQ(substitute_frame(name, 3), name);
    }
    for (const std::string name : {"a.#.exr", "a.%d.exr", "a.%03d.exr", "a.$F.exr"})
        EXPECT_TRUE(has_frame_token(name)) << name;
}

// The rules on which render's and movie's parsers once disagreed. A width is read whole
// and must be 1 to 10 digits (an int's); a name whose last token is outside that has no
// token, and is neither written frame by frame nor read as a sequence.
TEST(FramePattern, WidthsAreReadWholeAndBoundedForRenderAndMovieAlike) {
    // $F followed by a zero: the zero is part of the width ($F04 is four digits), so
    // $F0 is a width of 0, which no frame has.
    EXPECT_EQ(substitute_frame("out.$F04.exr", 7), "out.0007.exr");
    EXPECT_EQ(parse_frame_pattern("out.$F04.exr")->token, "$F04");
    // Widths of more than two ($F) or three (%0Nd) digits are read to their end.
    EXPECT_EQ(substitute_frame("out.%00004d.exr", 7), "out.0007.exr");
    EXPECT_EQ(parse_frame_pattern("out.%00004d.exr")->token, "%00004d");
    EXPECT_EQ(substitute_frame("out.$F010.exr", 7), "out.0000000007.exr");
    // Widths of 0 or above 10, however written, are refused.
    for (const char *s :
         {"out.%00d.exr", "out.$F0.exr", "out.%011d.exr", "out.$F11.exr", "out.$F100.exr",
          "out.%01234d.exr", "out.###########.exr", "out.$F99999999999.exr"}) {
        EXPECT_FALSE(parse_frame_pattern(s)) << s;
        EXPECT_FALSE(has_frame_token(s)) << s;
        EXPECT_EQ(substitute_frame(s, 7), s);
    }
    // An unusable last token is not passed over for an earlier one.
    EXPECT_FALSE(has_frame_token("take_####/out.%00d.exr"));
    EXPECT_TRUE(has_frame_token("take_%00d/out.####.exr"));
    // Ten digits, the widest, round-trips.
    const FramePattern ten = *parse_frame_pattern("out.##########.exr");
    EXPECT_EQ(format_frame(ten, 2147483647), "out.2147483647.exr");
    EXPECT_EQ(match_frame(ten, "out.0000000007.exr"), 7);
}

void touch(const TempDir &tmp, const std::string &name) {
    std::ofstream(tmp.file(name)) << "x";
}

std::string sequence_error(const std::string &pattern) {
    try {
        find_frame_sequence(pattern, "frames");
    } catch (const InputError &e) {
        EXPECT_EQ(e.field(), "frames");
        return e.what();
    }
    return "";
}

TEST(FrameSequence, FindsTheStepAndNamesTheHoles) {
    TempDir tmp;
    for (int f = 0; f <= 110; f += 10)
        touch(tmp, "cow." + std::to_string(10000 + f).substr(1) + ".exr");
    touch(tmp, "cow.0010.exr.tmp123");  // a temporary, not a frame
    touch(tmp, "dog.0005.exr");
    const FrameSequence seq = find_frame_sequence(tmp.file("cow.####.exr"), "frames");
    ASSERT_EQ(seq.frames.size(), 12u);
    EXPECT_EQ(seq.step, 10);
    EXPECT_EQ(seq.frames.front().frame, 0);
    EXPECT_EQ(seq.frames.back().frame, 110);
    EXPECT_EQ(seq.frames[3].path, tmp.file("cow.0030.exr"));
    // The same files through the other spellings.
    EXPECT_EQ(find_frame_sequence(tmp.file("cow.%04d.exr"), "frames").frames.size(), 12u);
    EXPECT_EQ(find_frame_sequence(tmp.file("cow.$F4.exr"), "frames").frames.size(), 12u);

    std::filesystem::remove(tmp.file("cow.0030.exr"));
    std::string e = sequence_error(tmp.file("cow.####.exr"));
    EXPECT_NE(e.find("frame 30 missing from the sequence 0-110, step 10"),
              std::string::npos)
        << e;
    std::filesystem::remove(tmp.file("cow.0040.exr"));
    std::filesystem::remove(tmp.file("cow.0080.exr"));
    e = sequence_error(tmp.file("cow.####.exr"));
    EXPECT_NE(e.find("frames 30-40 (step 10) missing (3 in all)"), std::string::npos)
        << e;
    touch(tmp, "cow.0030.exr");
    touch(tmp, "cow.0040.exr");
    touch(tmp, "cow.0080.exr");
    touch(tmp, "cow.0025.exr");  // from another render, on another step
    e = sequence_error(tmp.file("cow.####.exr"));
    EXPECT_NE(e.find("cow.0025.exr (frame 25) is off the sequence's step of 10"),
              std::string::npos)
        << e;
    std::filesystem::remove(tmp.file("cow.0025.exr"));
    touch(tmp, "cow.0005.exr");  // a stray first frame is the one named
    e = sequence_error(tmp.file("cow.####.exr"));
    EXPECT_NE(e.find("(frame 5) is off"), std::string::npos) << e;
}

TEST(FrameSequence, ConsecutiveFramesAndPlainErrors) {
    TempDir tmp;
    for (int f : {3, 4, 5, 7}) touch(tmp, "f." + std::to_string(f) + ".exr");
    std::string e = sequence_error(tmp.file("f.%d.exr"));
    EXPECT_NE(e.find("frame 6 missing from the sequence 3-7;"), std::string::npos) << e;
    touch(tmp, "f.6.exr");
    const FrameSequence seq = find_frame_sequence(tmp.file("f.%d.exr"), "frames");
    EXPECT_EQ(seq.frames.size(), 5u);
    EXPECT_EQ(seq.step, 1);
    e = sequence_error(tmp.file("g.####.exr"));
    EXPECT_NE(e.find("no frames found"), std::string::npos) << e;
    e = sequence_error(tmp.file("f.exr"));
    EXPECT_NE(e.find("expected a frame pattern"), std::string::npos) << e;
    touch(tmp, "one.0042.exr");
    // Gaps of 2 and 4: the step is the smaller, and the hole is named.
    for (int f : {20, 22, 26}) touch(tmp, "h." + std::to_string(f) + ".exr");
    e = sequence_error(tmp.file("h.#.exr"));
    EXPECT_NE(e.find("frame 24 missing from the sequence 20-26, step 2"),
              std::string::npos)
        << e;
    const FrameSequence single = find_frame_sequence(tmp.file("one.####.exr"), "frames");
    EXPECT_EQ(single.frames.size(), 1u);
    EXPECT_EQ(single.step, 1);
}

}  // namespace
}  // namespace pelage::test
