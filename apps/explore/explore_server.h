// `pelage explore`'s HTTP side (cpp-httplib, Debian's libcpp-httplib-dev: one header,
// threaded, no other dependency): the page and three.js as static files, and a small
// JSON API over an ExploreSession.
//
//   GET  /api/presets          the shipped presets, by name
//   GET  /api/status?after=V   the session's state once its version exceeds V (long poll)
//   GET  /api/mesh             the simulation surface (explore_session.h's layout)
//   GET  /api/texture          the latest type texture
//   POST /api/preset           {"preset": {...}, "seed": N}: simulate it (400: the
//                              preset parser's message)
//   POST /api/render           {"width", "height", "spp"}: a progressive path-traced
//                              preview of the finished look; GET /api/render/status and
//                              /api/render.png follow it
//   POST /api/save             {"name": STEM}: the preset, the cells and a scene that
//                              `pelage render` renders to the same look
//
// A bad request gets a 4xx and a JSON {"error": message}; no request stops the server.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "apps/explore/explore_session.h"

namespace httplib {
class Server;
}

namespace pelage::renderer::explore {

struct ExploreHooks {
    // Renders the finished look at width × height, spp samples per pixel, into a PNG.
    std::function<void(const ExploreResult &, int width, int height, int spp,
                       const std::string &png)>
        render;
    // Writes STEM.json (the scene), STEM_preset.json and STEM.cells; returns the paths.
    std::function<std::vector<std::string>(const ExploreResult &,
                                           const std::string &stem)>
        save;
};

class ExploreServer {
  public:
    // `presets`: (name, JSON text) of every preset offered as a starting point.
    ExploreServer(ExploreSession &session, std::string page_dir,
                  std::vector<std::pair<std::string, std::string>> presets,
                  ExploreHooks hooks);
    ~ExploreServer();

    // Binds to host:port (port 0: any free one) and returns the port; throws
    // std::runtime_error when it cannot.
    int bind(const std::string &host, int port);
    // Serves until stop() is called (from any thread).
    void run();
    void stop();

  private:
    void routes();
    void start_render(int width, int height, int spp);

    ExploreSession &m_session;
    std::string m_page_dir;
    std::vector<std::pair<std::string, std::string>> m_presets;
    ExploreHooks m_hooks;
    std::unique_ptr<httplib::Server> m_server;

    std::mutex m_render_mutex;
    uint64_t m_render_generation = 0;
    bool m_rendering = false;
    int m_render_spp = 0;  // of the latest finished pass
    uint64_t m_render_version = 0;
    std::string m_render_error;
    std::string m_render_png;  // bytes
    std::thread m_render_thread;
};

}  // namespace pelage::renderer::explore
