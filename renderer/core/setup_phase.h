// Set-up steps that count nothing (loading meshes, building the BVH, growing fur,
// remeshing): while one lasts, the command's line on stderr names it with the seconds
// it has taken, "render: growing fur  3.4 s", so a long set-up is seen moving rather
// than a bar sitting at 0 %. Process-wide and silent until a command turns it on.
#pragma once

#include <functional>
#include <string>

namespace pelage::renderer {

class SetupPhase {
  public:
    // Phases nest (the innermost shows) and are opened and closed on one thread.
    explicit SetupPhase(std::string name);
    ~SetupPhase();
    SetupPhase(const SetupPhase &) = delete;
    SetupPhase &operator=(const SetupPhase &) = delete;

    // From now on, phases draw "label: name  seconds" on stderr when `enabled` (callers
    // pass !quiet && a TTY check); the line is cleared when the outermost phase ends.
    static void show(std::string label, bool enabled);

    // Called with each phase's name as it starts (tests; nullptr = none).
    static void observe(std::function<void(const std::string &)> observer);

    // The line drawn for `phase` after `seconds`.
    static std::string line(const std::string &label, const std::string &phase,
                            double seconds);
};

}  // namespace pelage::renderer
