#include "renderer/core/setup_phase.h"

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace pelage::renderer {

namespace {

using Clock = std::chrono::steady_clock;

struct PhaseLine {
    std::mutex mutex;
    std::condition_variable wake;
    bool shown = false;
    std::string label;
    std::vector<std::pair<std::string, Clock::time_point>> open;  // innermost last
    std::function<void(const std::string &)> observer;
    std::thread ticker;
    size_t drawn = 0;  // characters of the last line drawn, to blank it
};

PhaseLine &phase_line() {
    static PhaseLine l;
    return l;
}

// Redraws the innermost phase about 4 times a second until none is open, then blanks
// the line for whatever is printed next.
void tick(PhaseLine &l) {
    std::unique_lock<std::mutex> lock(l.mutex);
    while (!l.open.empty()) {
        const auto &[name, start] = l.open.back();
        const double t = std::chrono::duration<double>(Clock::now() - start).count();
        std::string text = SetupPhase::line(l.label, name, t);
        const size_t n = text.size();
        if (n < l.drawn) text.append(l.drawn - n, ' ');
        l.drawn = n;
        std::fprintf(stderr, "\r%s", text.c_str());
        std::fflush(stderr);
        l.wake.wait_for(lock, std::chrono::milliseconds(250));
    }
    std::fprintf(stderr, "\r%s\r", std::string(l.drawn, ' ').c_str());
    std::fflush(stderr);
    l.drawn = 0;
}

}  // namespace

SetupPhase::SetupPhase(std::string name) {
    PhaseLine &l = phase_line();
    std::lock_guard<std::mutex> lock(l.mutex);
    if (l.observer) l.observer(name);
    l.open.emplace_back(std::move(name), Clock::now());
    if (l.shown && !l.ticker.joinable()) l.ticker = std::thread(tick, std::ref(l));
    l.wake.notify_all();  // show the new name now
}

SetupPhase::~SetupPhase() {
    PhaseLine &l = phase_line();
    std::thread done;
    {
        std::lock_guard<std::mutex> lock(l.mutex);
        l.open.pop_back();
        if (l.open.empty()) done = std::move(l.ticker);
        l.wake.notify_all();
    }
    if (done.joinable()) done.join();
}

void SetupPhase::show(std::string label, bool enabled) {
    PhaseLine &l = phase_line();
    std::lock_guard<std::mutex> lock(l.mutex);
    l.label = std::move(label);
    l.shown = enabled;
}

void SetupPhase::observe(std::function<void(const std::string &)> observer) {
    PhaseLine &l = phase_line();
    std::lock_guard<std::mutex> lock(l.mutex);
    l.observer = std::move(observer);
}

std::string SetupPhase::line(const std::string &label, const std::string &phase,
                             double seconds) {
    char t[32];
    std::snprintf(t, sizeof t, "  %.1f s", seconds);
    return label + ": " + phase + " ..." + t;
}

}  // namespace pelage::renderer
