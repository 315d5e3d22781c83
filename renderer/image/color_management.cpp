#include "renderer/image/color_management.h"

#include <cstdlib>
#include <stdexcept>

#include "renderer/core/install_layout.h"
#include "sim/core/input_error.h"

namespace OCIO = OCIO_NAMESPACE;

namespace pelage::renderer {

std::string DisplayTransform::config_location() {
    if (const char *env = std::getenv("OCIO"); env && *env) return env;
    return find_data("ocio/config.ocio");
}

DisplayTransform::DisplayTransform(const std::string &view, const std::string &display) {
    m_config_path = config_location();
    OCIO::ConstConfigRcPtr config;
    try {
        config = OCIO::Config::CreateFromFile(m_config_path.c_str());
        m_display = display.empty() ? config->getDefaultDisplay() : display;
        m_view = view.empty() ? config->getDefaultView(m_display.c_str()) : view;
    } catch (const OCIO::Exception &e) {
        throw std::runtime_error(m_config_path +
                                 ": cannot read OpenColorIO config: " + e.what());
    }
    bool found = false;
    std::string views;
    for (int i = 0; i < config->getNumViews(m_display.c_str()); ++i) {
        const std::string v = config->getView(m_display.c_str(), i);
        found |= v == m_view;
        views += (views.empty() ? "" : ", ") + v;
    }
    if (!found)
        throw InputError(m_config_path, 0, "film.view",
                         "unknown view \"" + m_view + "\" for display \"" + m_display +
                             "\" (views: " + views + ")");
    try {
        auto t = OCIO::DisplayViewTransform::Create();
        t->setSrc(OCIO::ROLE_SCENE_LINEAR);
        t->setDisplay(m_display.c_str());
        t->setView(m_view.c_str());
        m_cpu = config->getProcessor(t)->getDefaultCPUProcessor();
    } catch (const OCIO::Exception &e) {
        throw std::runtime_error(m_config_path + ": OpenColorIO: " + e.what());
    }
}

void DisplayTransform::apply_rgb(float *rgb, size_t pixels) const {
    OCIO::PackedImageDesc img(rgb, long(pixels), 1, 3);
    m_cpu->apply(img);
}

}  // namespace pelage::renderer
