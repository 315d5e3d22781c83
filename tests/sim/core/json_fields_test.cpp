// sim/core/json_fields.h: each primitive's error names the file and the JSON path and
// says what was expected; the preset parsers' and the scene file's messages are these,
// word for word.
#include "sim/core/json_fields.h"

#include <gtest/gtest.h>

#include <limits>

namespace pelage::sim {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

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

// JsonObjectFields, as the scene file reads its objects: each message says what was
// found, keys are taken once and the rest are unknown, colour has two spellings.
TEST(JsonObjectFields, FieldsAreTypedRangedAndTheRestUnknown) {
    const ordered_json j = ordered_json::parse(
        R"({"n": 2, "i": "x", "b": 1, "v": [1, 2], "c": 0.5, "k": "z", "u": -3})");
    JsonObjectFields f(j, "film", "s.json");
    EXPECT_EQ(f.number("n", 0, 0, 10), 2);
    EXPECT_EQ(f.number("absent", 7, 0, 10), 7);
    EXPECT_EQ(error_of([&] { f.number("n", 0, 3, 10); }),
              "s.json: film.n: = 2: must be in [3, 10]");
    EXPECT_EQ(error_of([&] { f.number("n", 0, 2, 10, false, true); }),
              "s.json: film.n: = 2: must be in (2, 10]");
    EXPECT_EQ(error_of([&] { f.number("absent", 0, 0, 1, true); }),
              "s.json: film.absent: missing required field");
    EXPECT_EQ(error_of([&] { f.integer("i", 0, 0, 1); }),
              "s.json: film.i: expected an integer, got a string");
    EXPECT_EQ(error_of([&] { f.unsigned_integer("u", 0, 0, 9); }),
              "s.json: film.u: expected a non-negative integer, got a negative one");
    EXPECT_EQ(error_of([&] { f.boolean("b", false); }),
              "s.json: film.b: expected true or false, got an integer");
    EXPECT_EQ(error_of([&] { f.vec3("v", {}); }),
              "s.json: film.v: expected an array of 3 numbers, got an array of 2");
    const Rgb grey = f.color("c", {});
    EXPECT_EQ(grey.x, 0.5f);
    EXPECT_EQ(grey.z, 0.5f);
    EXPECT_EQ(error_of([&] {
                  f.choice<int>("k", 0, {{"a", 1}, {"b", 2}});
              }),
              "s.json: film.k: unknown value \"z\" (expected one of a, b)");
    EXPECT_EQ(error_of([&] { f.finish(); }), "");
    JsonObjectFields g(j, "", "s.json");
    g.take("n");
    // The first unknown key as the file lists it, with the closest key asked for.
    EXPECT_EQ(error_of([&] { g.finish(); }),
              "s.json: i: unknown field (did you mean \"n\"?)");
    JsonObjectFields far(j, "", "s.json");
    far.take("radius");  // nothing in the file is a misspelling of it
    EXPECT_EQ(error_of([&] { far.finish(); }).rfind("s.json: ", 0), 0u);
    EXPECT_EQ(error_of([&] { far.finish(); }).find("did you mean"), std::string::npos);
    const ordered_json three(3);
    EXPECT_EQ(error_of([&] { JsonObjectFields(three, "x", "s.json"); }),
              "s.json: x: expected an object, got an integer");
}

TEST(JsonObjectFields, ColourIsFoundInEitherSpellingAndNamedAsWritten) {
    const ordered_json j = ordered_json::parse(R"({"color": [1, 0, 0]})");
    JsonObjectFields f(j, "lights[0]", "s.json");
    EXPECT_TRUE(f.has("colour"));
    EXPECT_EQ(f.field("colour"), "lights[0].color");
    EXPECT_EQ(f.color("colour", {}).x, 1.0f);
    EXPECT_EQ(error_of([&] { f.finish(); }), "");
    const ordered_json both = ordered_json::parse(R"({"color": 1, "colour": 1})");
    EXPECT_NE(error_of([&] {
                  JsonObjectFields(both, "", "s.json").take("colour");
              }).find("given twice"),
              std::string::npos);
}

}  // namespace
}  // namespace pelage::sim
