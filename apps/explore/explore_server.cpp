#include "apps/explore/explore_server.h"

#include <httplib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <stdexcept>

namespace pelage::renderer::explore {
namespace {

void reply_json(httplib::Response &res, const nlohmann::json &j, int status = 200) {
    res.status = status;
    res.set_header("Cache-Control", "no-store");
    res.set_content(j.dump(), "application/json");
}

void reply_error(httplib::Response &res, int status, const std::string &message) {
    reply_json(res, {{"error", message}}, status);
}

// Binary data with its version (X-Pelage-Version), or 404 with `missing` when empty.
void reply_bytes(httplib::Response &res, const std::vector<uint8_t> &bytes,
                 uint64_t version, const std::string &missing) {
    if (bytes.empty()) return reply_error(res, 404, missing);
    res.set_header("X-Pelage-Version", std::to_string(version));
    res.set_header("Cache-Control", "no-store");
    res.set_content(reinterpret_cast<const char *>(bytes.data()), bytes.size(),
                    "application/octet-stream");
}

// The request's body as a JSON object; throws std::invalid_argument naming what is wrong.
nlohmann::json body_object(const httplib::Request &req) {
    const nlohmann::json j = nlohmann::json::parse(req.body, nullptr, false);
    if (j.is_discarded() || !j.is_object())
        throw std::invalid_argument("the request's body is not a JSON object");
    return j;
}

int int_field(const nlohmann::json &j, const char *key, int fallback, int lo, int hi) {
    if (!j.contains(key)) return fallback;
    if (!j[key].is_number_integer() || j[key].get<long long>() < lo ||
        j[key].get<long long>() > hi)
        throw std::invalid_argument(std::string(key) + ": expected an integer in [" +
                                    std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return j[key].get<int>();
}

std::string read_file(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

ExploreServer::ExploreServer(ExploreSession &session, std::string page_dir,
                             std::vector<std::pair<std::string, std::string>> presets,
                             ExploreHooks hooks)
    : m_session(session),
      m_page_dir(std::move(page_dir)),
      m_presets(std::move(presets)),
      m_hooks(std::move(hooks)),
      m_server(std::make_unique<httplib::Server>()) {
    routes();
}

ExploreServer::~ExploreServer() {
    stop();
    {
        std::lock_guard lock(m_render_mutex);
        ++m_render_generation;
    }
    if (m_render_thread.joinable()) m_render_thread.join();
}

int ExploreServer::bind(const std::string &host, int port) {
    const int bound = port == 0 ? m_server->bind_to_any_port(host)
                                : (m_server->bind_to_port(host, port) ? port : -1);
    if (bound <= 0)
        throw std::runtime_error("cannot listen on " + host + ":" + std::to_string(port) +
                                 " (in use? choose another with --port)");
    return bound;
}

void ExploreServer::run() { m_server->listen_after_bind(); }

void ExploreServer::stop() { m_server->stop(); }

void ExploreServer::routes() {
    httplib::Server &s = *m_server;
    if (!s.set_mount_point("/", m_page_dir))
        throw std::runtime_error("the explorer's page is missing: no folder " +
                                 m_page_dir);
    // Every handler's exception is the client's error, reported, never the server's end.
    s.set_exception_handler(
        [](const httplib::Request &, httplib::Response &res, std::exception_ptr ep) {
            try {
                std::rethrow_exception(ep);
            } catch (const std::exception &e) {
                reply_error(res, 400, e.what());
            } catch (...) {
                reply_error(res, 500, "unknown error");
            }
        });

    s.Get("/api/presets", [this](const httplib::Request &, httplib::Response &res) {
        nlohmann::json names = nlohmann::json::array(), all = nlohmann::json::object();
        for (const auto &[name, text] : m_presets) {
            names.push_back(name);
            all[name] = nlohmann::json::parse(text);
        }
        reply_json(res, {{"names", names}, {"presets", all}});
    });
    s.Get("/api/status", [this](const httplib::Request &req, httplib::Response &res) {
        uint64_t after = 0;
        if (req.has_param("after")) {
            const std::string v = req.get_param_value("after");
            if (v.empty() || v.find_first_not_of("0123456789") != std::string::npos ||
                v.size() > 18)
                throw std::invalid_argument("after: expected a version number");
            after = std::stoull(v);
        }
        reply_json(res, m_session.status(after, 10.0));
    });
    s.Get("/api/mesh", [this](const httplib::Request &, httplib::Response &res) {
        uint64_t version = 0;
        const std::vector<uint8_t> bytes = m_session.mesh_bytes(&version);
        reply_bytes(res, bytes, version, "no surface yet");
    });
    s.Get("/api/texture", [this](const httplib::Request &, httplib::Response &res) {
        uint64_t version = 0;
        const std::vector<uint8_t> bytes = m_session.texture_bytes(&version);
        reply_bytes(res, bytes, version, "no pattern yet");
    });
    s.Post("/api/preset", [this](const httplib::Request &req, httplib::Response &res) {
        const nlohmann::json j = body_object(req);
        if (!j.contains("preset") || !j["preset"].is_object())
            return reply_error(res, 400, "preset: expected the preset as a JSON object");
        uint64_t seed = 1;
        if (j.contains("seed")) {
            if (!j["seed"].is_number_unsigned())
                return reply_error(res, 400, "seed: expected an integer >= 0");
            seed = j["seed"].get<uint64_t>();
        }
        const uint64_t job = m_session.submit(j["preset"].dump(), seed);
        reply_json(res, {{"simulating", job != 0}, {"job", job}});
    });
    s.Post("/api/render", [this](const httplib::Request &req, httplib::Response &res) {
        const nlohmann::json j = body_object(req);
        const int width = int_field(j, "width", 480, 16, 1920);
        const int height = int_field(j, "height", 270, 16, 1080);
        const int spp = int_field(j, "spp", 64, 1, 4096);
        if (!m_session.result().ready)
            return reply_error(res, 409, "the full-scale pattern is not grown yet");
        start_render(width, height, spp);
        reply_json(res, {{"rendering", true}});
    });
    s.Get("/api/render/status", [this](const httplib::Request &, httplib::Response &res) {
        std::lock_guard lock(m_render_mutex);
        reply_json(res, {{"rendering", m_rendering},
                         {"spp", m_render_spp},
                         {"version", m_render_version},
                         {"error", m_render_error}});
    });
    s.Get("/api/render.png", [this](const httplib::Request &, httplib::Response &res) {
        std::lock_guard lock(m_render_mutex);
        if (m_render_png.empty()) return reply_error(res, 404, "nothing rendered yet");
        res.set_header("Cache-Control", "no-store");
        res.set_content(m_render_png, "image/png");
    });
    s.Post("/api/save", [this](const httplib::Request &req, httplib::Response &res) {
        const nlohmann::json j = body_object(req);
        const std::string name = j.value("name", std::string("explore"));
        static const std::regex stem("[A-Za-z0-9_-][A-Za-z0-9._-]{0,63}");
        if (!std::regex_match(name, stem))
            return reply_error(res, 400,
                               "name: expected 1 to 64 letters, digits, '.', '_' or '-', "
                               "not starting with '.'");
        const ExploreResult result = m_session.result();
        if (!result.ready)
            return reply_error(res, 409, "the full-scale pattern is not grown yet");
        reply_json(res, {{"files", m_hooks.save(result, name)}});
    });
}

void ExploreServer::start_render(int width, int height, int spp) {
    uint64_t generation = 0;
    {
        std::lock_guard lock(m_render_mutex);
        generation = ++m_render_generation;
    }
    // The previous render stops after its current pass.
    if (m_render_thread.joinable()) m_render_thread.join();
    {
        std::lock_guard lock(m_render_mutex);
        m_rendering = true;
        m_render_error.clear();
    }
    const ExploreResult result = m_session.result();
    m_render_thread = std::thread([this, generation, result, width, height, spp] {
        // Progressive: each pass four times the samples of the last, up to spp.
        for (int n = 1;; n = std::min(spp, 4 * n)) {
            {
                std::lock_guard lock(m_render_mutex);
                if (m_render_generation != generation) break;
            }
            const std::string png = m_session.work_dir() + "/render.png";
            try {
                m_hooks.render(result, width, height, n, png);
            } catch (const std::exception &e) {
                std::lock_guard lock(m_render_mutex);
                m_render_error = e.what();
                break;
            }
            std::string bytes = read_file(png);
            std::filesystem::remove(png);
            std::lock_guard lock(m_render_mutex);
            if (m_render_generation != generation) break;
            m_render_png = std::move(bytes);
            m_render_spp = n;
            ++m_render_version;
            if (n >= spp) break;
        }
        std::lock_guard lock(m_render_mutex);
        if (m_render_generation == generation) m_rendering = false;
    });
}

}  // namespace pelage::renderer::explore
