// One set-up step of a run, told to the caller's `phase` callback (GrowRequest::phase):
// its name when it starts, "" when it ends. The command line shows it as a line that
// counts the seconds (renderer/core/setup_phase.h).
#pragma once

#include <functional>
#include <string>

namespace pelage::sim {

class SetupStep {
  public:
    SetupStep(const std::function<void(const std::string &)> &phase,
              const std::string &name)
        : m_phase(phase) {
        if (m_phase) m_phase(name);
    }
    ~SetupStep() {
        if (m_phase) m_phase("");
    }
    SetupStep(const SetupStep &) = delete;
    SetupStep &operator=(const SetupStep &) = delete;

  private:
    const std::function<void(const std::string &)> &m_phase;
};

}  // namespace pelage::sim
