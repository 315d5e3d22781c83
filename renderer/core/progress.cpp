#include "renderer/core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>

namespace pelage::renderer {

namespace {
std::atomic<bool> g_interrupted{false};
void (*g_previous_handler)(int) = SIG_DFL;

extern "C" void on_sigint(int) {
    if (g_interrupted.load()) std::signal(SIGINT, SIG_DFL);
    g_interrupted.store(true);
}
}  // namespace

bool Progress::stderr_is_tty() { return isatty(STDERR_FILENO) == 1; }

Progress::Progress(std::string label, uint64_t total, bool enabled)
    : m_label(std::move(label)),
      m_total(total ? total : 1),
      m_enabled(enabled),
      m_start(std::chrono::steady_clock::now()) {
    if (!m_enabled) return;
    m_thread = std::thread([this] {
        while (!m_stop.load()) {
            draw(false);
            for (int i = 0; i < 5 && !m_stop.load(); ++i)
                std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
    });
}

Progress::~Progress() { finish(); }

void Progress::finish() {
    if (!m_enabled || m_stop.exchange(true)) return;
    if (m_thread.joinable()) m_thread.join();
    draw(true);
}

double Progress::fraction() const {
    return std::min(1.0, double(done()) / double(m_total));
}

std::string Progress::line(const std::string &label, double f, double seconds) {
    constexpr int width = 30;
    std::string bar(width, ' ');
    for (int i = 0; i < width && i < int(f * width); ++i) bar[size_t(i)] = '#';
    char tail[64];
    if (f > 0 && f < 1)
        std::snprintf(tail, sizeof tail, "%3d%%  ETA %.0f s   ", int(100 * f),
                      seconds * (1 - f) / f);
    else
        std::snprintf(tail, sizeof tail, "%3d%%  %.1f s        ", int(100 * f), seconds);
    return label + " [" + bar + "] " + tail;
}

void Progress::draw(bool final) {
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    std::fprintf(stderr, "\r%s%s", line(m_label, fraction(), t).c_str(),
                 final ? "\n" : "");
    std::fflush(stderr);
}

InterruptGuard::InterruptGuard() {
    g_interrupted.store(false);
    g_previous_handler = std::signal(SIGINT, on_sigint);
}

InterruptGuard::~InterruptGuard() { std::signal(SIGINT, g_previous_handler); }

const std::atomic<bool> &InterruptGuard::flag() { return g_interrupted; }

}  // namespace pelage::renderer
