// The plugin SDK on its own: parameters read by name against a table, and a create()
// whose exceptions become the ABI's refusal.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "shader/sdk/create_guard.h"
#include "shader/sdk/params.h"

namespace pelage::test {
namespace {

using namespace pelage::shader::sdk;

const PelageParamSpec table[] = {
    {"size", PELAGE_PARAM_FLOAT, {2, 0, 0}, nullptr, 0, 10, "a float"},
    {"count", PELAGE_PARAM_INT, {3, 0, 0}, nullptr, 0, 10, "an int"},
    {"tint", PELAGE_PARAM_RGB, {0.1f, 0.2f, 0.3f}, nullptr, 0, 1, "a colour"},
    {"label", PELAGE_PARAM_STRING, {0, 0, 0}, "x", 0, 0, "a string"},
    {nullptr, PelageParamType(0), {0, 0, 0}, nullptr, 0, 0, nullptr},
};

std::vector<PelageParamValue> table_order() {
    return {{"size", PELAGE_PARAM_FLOAT, {2.5f, 0, 0}, 0, nullptr},
            {"count", PELAGE_PARAM_INT, {0, 0, 0}, 7, nullptr},
            {"tint", PELAGE_PARAM_RGB, {0.4f, 0.5f, 0.6f}, 0, nullptr},
            {"label", PELAGE_PARAM_STRING, {0, 0, 0}, 0, "spots"}};
}

PelageParamSet set_of(const std::vector<PelageParamValue> &v) {
    PelageParamSet ps{};
    ps.count = uint32_t(v.size());
    ps.values = v.data();
    return ps;
}

// The message of the ParamError that `read` throws ("" when it throws none).
template <typename F>
std::string param_error(F read) {
    try {
        read();
    } catch (const ParamError &e) {
        return e.what();
    }
    return "";
}

TEST(ShaderSdk, ReadsEveryTypeByName) {
    const auto v = table_order();
    const PelageParamSet ps = set_of(v);
    const Params p(table, ps);
    EXPECT_EQ(p.get_float("size"), 2.5f);
    EXPECT_EQ(p.get_int("count"), 7);
    EXPECT_TRUE(p.get_bool("count"));
    EXPECT_EQ(p.get_rgb("tint"), (std::array<float, 3>{0.4f, 0.5f, 0.6f}));
    EXPECT_EQ(p.get_string("label"), "spots");
}

TEST(ShaderSdk, FindsValuesOutOfTableOrder) {
    auto v = table_order();
    std::swap(v[0], v[3]);
    std::swap(v[1], v[2]);
    const PelageParamSet ps = set_of(v);
    const Params p(table, ps);
    EXPECT_EQ(p.get_float("size"), 2.5f);
    EXPECT_EQ(p.get_int("count"), 7);
    EXPECT_EQ(p.get_rgb("tint")[2], 0.6f);
    EXPECT_EQ(p.get_string("label"), "spots");
}

TEST(ShaderSdk, NullStringReadsEmpty) {
    auto v = table_order();
    v[3].s = nullptr;
    const PelageParamSet ps = set_of(v);
    EXPECT_EQ(Params(table, ps).get_string("label"), "");
}

TEST(ShaderSdk, NameNotInTableIsAnError) {
    const auto v = table_order();
    const PelageParamSet ps = set_of(v);
    const Params p(table, ps);
    EXPECT_EQ(param_error([&] { p.get_float("sise"); }),
              "parameter \"sise\" is not in the plugin's table");
}

TEST(ShaderSdk, WrongGetterIsAnError) {
    const auto v = table_order();
    const PelageParamSet ps = set_of(v);
    const Params p(table, ps);
    EXPECT_EQ(param_error([&] { p.get_int("size"); }),
              "parameter \"size\" is float in the plugin's table, read as int");
    EXPECT_NE(param_error([&] { p.get_float("tint"); }), "");
    EXPECT_NE(param_error([&] { p.get_string("count"); }), "");
    EXPECT_NE(param_error([&] { p.get_bool("label"); }), "");
}

TEST(ShaderSdk, ValueOfAnotherTypeInTheSetIsAnError) {
    auto v = table_order();
    v[1].type = PELAGE_PARAM_FLOAT;
    const PelageParamSet ps = set_of(v);
    EXPECT_EQ(param_error([&] { Params(table, ps).get_int("count"); }),
              "parameter \"count\" is int in the plugin's table, float in the parameter "
              "set");
}

TEST(ShaderSdk, MissingValueIsAnError) {
    auto v = table_order();
    v.pop_back();
    const PelageParamSet ps = set_of(v);
    EXPECT_EQ(param_error([&] { Params(table, ps).get_string("label"); }),
              "parameter \"label\" has no value in the parameter set");
}

struct Instance {
    float size;
};

std::unique_ptr<Instance> make_reading(const PelageParamSet &ps) {
    const Params p(table, ps);
    return std::make_unique<Instance>(Instance{p.get_float("size")});
}
std::unique_ptr<Instance> make_misreading(const PelageParamSet &ps) {
    const Params p(table, ps);
    return std::make_unique<Instance>(Instance{float(p.get_int("size"))});
}
std::unique_ptr<Instance> make_throwing_int(const PelageParamSet &) { throw 42; }
std::unique_ptr<Instance> make_long_message(const PelageParamSet &) {
    throw std::runtime_error(std::string(1000, 'x'));
}
std::unique_ptr<Instance> make_nothing(const PelageParamSet &) { return nullptr; }

TEST(ShaderSdk, GuardedCreateMakesTheInstance) {
    const auto v = table_order();
    const PelageParamSet ps = set_of(v);
    PelageError err{};
    void *self = guarded_create<make_reading>(&ps, &err);
    ASSERT_NE(self, nullptr);
    EXPECT_EQ(static_cast<Instance *>(self)->size, 2.5f);
    EXPECT_STREQ(err.message, "");
    destroy_instance<Instance>(self);
}

TEST(ShaderSdk, GuardedCreateTurnsAMisreadIntoTheError) {
    const auto v = table_order();
    const PelageParamSet ps = set_of(v);
    PelageError err{};
    EXPECT_EQ(guarded_create<make_misreading>(&ps, &err), nullptr);
    EXPECT_STREQ(err.message,
                 "parameter \"size\" is float in the plugin's table, read as int");
}

TEST(ShaderSdk, GuardedCreateCatchesEverything) {
    const auto v = table_order();
    const PelageParamSet ps = set_of(v);
    PelageError err{};
    EXPECT_EQ(guarded_create<make_throwing_int>(&ps, &err), nullptr);
    EXPECT_STREQ(err.message,
                 "create() failed with an exception that is not a std::exception");
    PelageError long_err{};
    EXPECT_EQ(guarded_create<make_long_message>(&ps, &long_err), nullptr);
    EXPECT_EQ(std::string(long_err.message), std::string(255, 'x'));
    PelageError none{};
    EXPECT_EQ(guarded_create<make_nothing>(&ps, &none), nullptr);
    EXPECT_STREQ(none.message, "create() made no instance");
    // No parameter set, no error struct: still a refusal, not a crash.
    EXPECT_EQ(guarded_create<make_reading>(nullptr, nullptr), nullptr);
}

}  // namespace
}  // namespace pelage::test
