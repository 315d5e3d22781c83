// Progress with ETA on a terminal, silence otherwise; and Ctrl-C as a request to stop.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>

#include "renderer/core/setup_phase.h"  // the steps before a Progress has work to count

namespace pelage::renderer {

// Draws "label [#####     ] 47%  ETA 12 s" on stderr about 4 times a second when
// `enabled` (callers pass a TTY check). The fraction is work done over `total` in units
// of equal cost (the renderer counts pixel-samples), so the ETA, elapsed × (1 − f) / f,
// holds as long as the units do. advance() is thread-safe and cheap (one atomic add).
class Progress {
  public:
    Progress(std::string label, uint64_t total, bool enabled);
    ~Progress();
    Progress(const Progress &) = delete;
    Progress &operator=(const Progress &) = delete;

    void advance(uint64_t n = 1) { m_done.fetch_add(n, std::memory_order_relaxed); }
    void finish();
    uint64_t done() const { return m_done.load(std::memory_order_relaxed); }
    uint64_t total() const { return m_total; }
    double fraction() const;
    static bool stderr_is_tty();

    // The line drawn for `fraction` of the work done after `seconds`.
    static std::string line(const std::string &label, double fraction, double seconds);

  private:
    void draw(bool final);
    std::string m_label;
    uint64_t m_total;
    bool m_enabled;
    std::atomic<uint64_t> m_done{0};
    std::atomic<bool> m_stop{false};
    std::chrono::steady_clock::time_point m_start;
    std::thread m_thread;
};

// While alive, SIGINT (Ctrl-C) sets a flag instead of killing the process, so the
// renderer can stop at the next tile and write what is done. A second Ctrl-C restores the
// default action and kills the process.
class InterruptGuard {
  public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard &) = delete;
    InterruptGuard &operator=(const InterruptGuard &) = delete;
    static const std::atomic<bool> &flag();
};

}  // namespace pelage::renderer
