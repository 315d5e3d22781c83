// sim/core/json_fields.h: each primitive's error names the file and the JSON path and
// says what was expected; the preset parsers' messages are these, word for word.
#include "sim/core/json_fields.h"

#include <gtest/gtest.h>

#include <limits>

namespace pelage::sim {
namespace {

using nlohmann::json;

// The parser rejects numbers beyond a double; a caller that builds JSON in code can still
// hand over an infinity.
const double inf = std::numeric_limits<double>::infinity();

// The message `read` throws as an InputError, "" when it throws nothing.
template <class Read>
std::string error_of(Read read) {
    try {
        read();
    } catch (const InputError &e) {
        return e.what();
    }
    return "";
}

TEST(JsonFieldsPreset, KeysAreCheckedAgainstTheAllowedSet) {
    const JsonFields f("p.json");
    const json j = json::parse(R"({"a": 1, "b": 2})");
    EXPECT_EQ(error_of([&] { f.check_keys(j, "", {"a", "b"}); }), "");
    EXPECT_EQ(error_of([&] { f.check_keys(j, "", {"a"}); }), "p.json: b: unknown key");
    EXPECT_EQ(error_of([&] { f.check_keys(j, "x.y", {"a"}); }),
              "p.json: x.y.b: unknown key");
    EXPECT_EQ(error_of([&] { f.check_keys(json(3), "", {"a"}); }),
              "p.json: (top level): expected an object");
    EXPECT_EQ(error_of([&] { f.check_keys(json(3), "x", {"a"}); }),
              "p.json: x: expected an object");
}

TEST(JsonFieldsPreset, NumbersAreFiniteAndFallBackWhenAbsent) {
    const JsonFields f("p.json");
    const nlohmann::ordered_json j = {{"n", 2.5}, {"s", "x"}, {"big", inf}};
    EXPECT_EQ(f.number(j, "o", "n", 0), 2.5);
    EXPECT_EQ(f.number(j, "o", "absent", 7), 7);
    EXPECT_EQ(error_of([&] { f.number(j, "o", "absent", 7, true); }),
              "p.json: o.absent: missing");
    EXPECT_EQ(error_of([&] { f.number(j, "o", "s", 0); }),
              "p.json: o.s: expected a number");
    EXPECT_EQ(error_of([&] { f.number(j, "o", "big", 0); }),
              "p.json: o.big: expected a finite number");
    EXPECT_EQ(JsonFields::format(0.5), "0.5");
    EXPECT_EQ(JsonFields::format(1e6), "1e+06");
}

TEST(JsonFieldsPreset, ThreeNumbersAndTheirErrors) {
    const JsonFields f("p.json");
    const Vec3d v = f.vec3(json::parse("[1, -2, 3.5]"), "at");
    EXPECT_EQ(v.x, 1);
    EXPECT_EQ(v.y, -2);
    EXPECT_EQ(v.z, 3.5);
    EXPECT_EQ(error_of([&] { f.vec3(json::parse("[1, 2]"), "at"); }),
              "p.json: at: expected 3 numbers");
    EXPECT_EQ(error_of([&] { f.vec3(json::parse(R"([1, "2", 3])"), "at"); }),
              "p.json: at: expected 3 numbers");
    EXPECT_EQ(error_of([&] {
                  f.vec3(json::array({1, inf, 3}), "at");
              }),
              "p.json: at[1]: not finite");
    EXPECT_EQ(error_of([&] {
                  f.numbers(json::array({1, inf, 3}), "at", 3, "bad");
              }),
              "p.json: at: bad");
}

TEST(JsonFieldsPreset, Strings) {
    const JsonFields f("p.json");
    const json j = json::parse(R"({"s": "x", "e": "", "n": 1})");
    EXPECT_EQ(f.string(j, "", "s", "d"), "x");
    EXPECT_EQ(f.string(j, "", "absent", "d"), "d");
    EXPECT_EQ(error_of([&] { f.string(j, "", "n", "d"); }),
              "p.json: n: expected a string");
    EXPECT_EQ(error_of([&] { f.string(j, "", "absent", "d", true); }),
              "p.json: absent: missing");
    EXPECT_EQ(error_of([&] { f.non_empty_string(j["e"], "o.e"); }),
              "p.json: o.e: expected a non-empty string");
}

}  // namespace
}  // namespace pelage::sim
