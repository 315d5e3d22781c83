// Scene-linear to display through OpenColorIO. The config is $OCIO when set, else
// pelage's own (renderer/image/ocio/config.ocio: sRGB display; Standard, Filmic and Raw
// views), share/pelage/ocio next to the executable (renderer/core/install_layout.h).
#pragma once

#include <OpenColorIO/OpenColorIO.h>

#include <string>
#include <vector>

namespace pelage::renderer {

class DisplayTransform {
  public:
    // display "" = the config's default display; view "" = that display's default view.
    // Throws std::runtime_error for a config that cannot be read, pelage::InputError
    // (field "film.view") for an unknown view.
    DisplayTransform(const std::string &view, const std::string &display = "");

    // In place, `pixels` interleaved RGB triples.
    void apply_rgb(float *rgb, size_t pixels) const;

    const std::string &config_path() const { return m_config_path; }
    const std::string &display() const { return m_display; }
    const std::string &view() const { return m_view; }

    // $OCIO, else ocio/config.ocio in $PELAGE_DATA_DIR or share/pelage.
    static std::string config_location();

  private:
    std::string m_config_path, m_display, m_view;
    OCIO_NAMESPACE::ConstCPUProcessorRcPtr m_cpu;
};

}  // namespace pelage::renderer
