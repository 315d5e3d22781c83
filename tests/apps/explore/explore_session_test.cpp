// The explorer's model and server (apps/explore): its finished pattern is the one
// grow_cells gives for the same preset, seed and mesh (what `pelage sim` writes), a
// colour-only change relabels the cells exactly as growing them again would, a newer
// preset cancels the run in progress, and bad requests get the parser's messages as
// 4xx answers while the server keeps serving.
#include "apps/explore/explore_session.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "apps/explore/explore_server.h"
#include "sim/cells_io/cells_file.h"
#include "sim/core/input_error.h"
#include "sim/run/grow_cells.h"
#include "tests/test_paths.h"

namespace pelage::renderer::explore {
namespace {

const char *const sphere = "procedural:sphere:20x20";

ExploreOptions options(const test::TempDir &tmp) {
    ExploreOptions o;
    o.mesh = sphere;
    o.preset_dir = test::source_path("scenes/presets");
    o.work_dir = tmp.file("work");
    o.texture_size = 512;
    return o;
}

nlohmann::json leopard() {
    return nlohmann::json::parse(
        test::slurp(test::source_path("scenes/presets/teo-leopard.json")));
}

// Waits (at most a minute) until the session's full-scale result is ready and measured.
nlohmann::json wait_ready(const ExploreSession &s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    uint64_t version = 0;
    while (std::chrono::steady_clock::now() < end) {
        const nlohmann::json j = s.status(version, 1.0);
        version = j["version"];
        if (!j["error"].get<std::string>().empty()) ADD_FAILURE() << j["error"];
        if (j["result_ready"] && j["stats_stage"] == "full") return j;
    }
    ADD_FAILURE() << "no result within a minute";
    return {};
}

// What `pelage sim --mesh sphere --preset FILE --seed N -o` writes.
std::string grown_bytes(const test::TempDir &tmp, const nlohmann::json &preset,
                        uint64_t seed) {
    sim::GrowRequest r;
    r.mesh = sphere;
    r.preset = tmp.write("reference_preset.json", preset.dump(2));
    r.seed = seed;
    const std::vector<uint8_t> b = sim::serialize_cells(sim::grow_cells(r).data);
    return std::string(b.begin(), b.end());
}

TEST(ExploreSession, TheFinishedPatternIsWhatGrowCellsGives) {
    test::TempDir tmp;
    ExploreSession session(options(tmp));
    const nlohmann::json preset = leopard();
    ASSERT_GT(session.submit(preset.dump(), 3), 0u);
    const nlohmann::json status = wait_ready(session);
    EXPECT_EQ(status["stats_stage"], "full");
    EXPECT_GT(status["stats"]["spot_count"].get<int>(), 0);
    EXPECT_GT(status["texture_version"].get<int>(), 0);
    const ExploreResult r = session.result();
    ASSERT_TRUE(r.ready);
    EXPECT_EQ(test::slurp(r.cells_path), grown_bytes(tmp, preset, 3));
}

TEST(ExploreSession, AColourChangeRelabelsTheCellsAsGrowingThemAgainWould) {
    test::TempDir tmp;
    ExploreSession session(options(tmp));
    nlohmann::json preset = leopard();
    ASSERT_GT(session.submit(preset.dump(), 2), 0u);
    const nlohmann::json before = wait_ready(session);
    preset["types"][0]["colour"] = {1.0, 0.0, 0.0};
    preset["name"] = "red leopard";
    EXPECT_EQ(session.submit(preset.dump(), 2), 0u);  // no simulation
    const nlohmann::json after = session.status(0, 0);
    EXPECT_EQ(after["job"], before["job"]);
    EXPECT_EQ(after["types"][0]["colour"], nlohmann::json({1.0, 0.0, 0.0}));
    const ExploreResult r = session.result();
    ASSERT_TRUE(r.ready);
    EXPECT_EQ(test::slurp(r.cells_path), grown_bytes(tmp, preset, 2));
    // A change the simulation reads does simulate.
    preset["simulation"]["w_r"] = 1.5;
    EXPECT_GT(session.submit(preset.dump(), 2), 0u);
}

TEST(ExploreSession, ANewerPresetCancelsTheRunInProgress) {
    test::TempDir tmp;
    ExploreSession session(options(tmp));
    nlohmann::json preset = leopard();
    const uint64_t first = session.submit(preset.dump(), 1);
    preset["simulation"]["w_r"] = 2.0;
    const uint64_t second = session.submit(preset.dump(), 1);
    EXPECT_GT(second, first);
    const nlohmann::json status = wait_ready(session);
    EXPECT_EQ(status["job"], second);
    EXPECT_EQ(test::slurp(session.result().cells_path), grown_bytes(tmp, preset, 1));
}

TEST(ExploreSession, KeepsTheFilesOfTheLastTwoResultsOnly) {
    test::TempDir tmp;
    const ExploreOptions o = options(tmp);
    ExploreSession session(o);
    nlohmann::json preset = leopard();
    std::vector<uint64_t> jobs;
    for (double w_r : {2.0, 2.5, 3.0, 3.5}) {
        preset["simulation"]["w_r"] = w_r;
        jobs.push_back(session.submit(preset.dump(), 1));
        wait_ready(session);
    }
    // A render of the previous result may still be reading its files.
    std::set<std::string> held;
    for (const auto &e : std::filesystem::directory_iterator(o.work_dir)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("job", 0) == 0) held.insert(name.substr(0, name.find('_')));
    }
    EXPECT_EQ(held, (std::set<std::string>{"job" + std::to_string(jobs[2]),
                                           "job" + std::to_string(jobs[3])}));
    EXPECT_EQ(session.result().cells_path,
              o.work_dir + "/job" + std::to_string(jobs[3]) + "_full.cells");
}

TEST(ExploreSession, ABadPresetGetsTheParsersMessage) {
    test::TempDir tmp;
    ExploreSession session(options(tmp));
    nlohmann::json preset = leopard();
    preset["simulation"]["w_r"] = -1;
    try {
        session.submit(preset.dump(), 1);
        FAIL() << "accepted w_r -1";
    } catch (const InputError &e) {
        EXPECT_NE(std::string(e.what()).find("simulation.w_r"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("must be > 0"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(session.status(0, 0)["job"], 0);
}

TEST(ExploreServer, BadRequestsGetA4xxAndTheServerGoesOn) {
    test::TempDir tmp;
    ExploreSession session(options(tmp));
    ExploreHooks hooks;
    hooks.save = [](const ExploreResult &, const std::string &) {
        return std::vector<std::string>{};
    };
    hooks.render = [](const ExploreResult &, int, int, int, const std::string &) {};
    ExploreServer server(session, test::source_path("apps/explore/page"),
                         {{"teo-leopard", leopard().dump()}}, hooks);
    const int port = server.bind("127.0.0.1", 0);
    std::thread serving([&] { server.run(); });
    httplib::Client client("127.0.0.1", port);
    client.set_read_timeout(20, 0);
    auto error_of = [](const httplib::Result &r) {
        return nlohmann::json::parse(r->body).value("error", std::string());
    };

    httplib::Result r = client.Post("/api/preset", "not json", "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);
    EXPECT_NE(error_of(r).find("not a JSON object"), std::string::npos);

    nlohmann::json bad = leopard();
    bad["simulation"]["w_r"] = -1;
    r = client.Post("/api/preset", nlohmann::json{{"preset", bad}}.dump(),
                    "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);
    EXPECT_NE(error_of(r).find("simulation.w_r: -1: must be > 0"), std::string::npos)
        << error_of(r);

    r = client.Post("/api/preset",
                    nlohmann::json{{"preset", leopard()}, {"seed", -4}}.dump(),
                    "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);

    r = client.Get("/api/status?after=abc");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);

    r = client.Post("/api/save", R"({"name": "../outside"})", "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);
    r = client.Post("/api/save", R"({"name": "coat"})", "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 409);  // nothing grown yet
    r = client.Post("/api/render", R"({"width": 100000})", "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);
    r = client.Get("/api/texture");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 404);

    // Still serving: the page, the presets and the state.
    r = client.Get("/");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200);
    EXPECT_NE(r->body.find("pelage explore"), std::string::npos);
    r = client.Get("/api/presets");
    ASSERT_TRUE(r);
    EXPECT_EQ(nlohmann::json::parse(r->body)["names"][0], "teo-leopard");
    r = client.Get("/api/status");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200);
    r = client.Get("/api/mesh");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200);
    EXPECT_EQ(r->get_header_value("X-Pelage-Version"), "1");  // the page's cue to reload
    server.stop();
    serving.join();
}

}  // namespace
}  // namespace pelage::renderer::explore
