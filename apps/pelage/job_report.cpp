#include "apps/pelage/job_report.h"

#include <fmt/format.h>

#include <cstdio>

namespace pelage::renderer::cli {

namespace {

class PrintedRun : public RenderObserver {
  public:
    explicit PrintedRun(const JobReporting &r) : m_r(r) {}
    void info(const std::string &line) override {
        if (!m_r.quiet) std::printf("%s\n", line.c_str());
    }
    void note(const std::string &line) override {
        if (!m_r.quiet) std::fprintf(stderr, "%s\n", line.c_str());
    }
    void warning(const std::string &line) override {
        std::fprintf(stderr, "%s: %s\n", m_r.command.c_str(), line.c_str());
    }
    void frame_written(const FrameReport &f) override {
        if (m_r.quiet) return;
        std::string line = fmt::format("{}: {}x{}", f.output, f.width, f.height);
        if (!f.tile.empty()) line += " tile " + f.tile;
        line += fmt::format(", {} spp", f.spp);
        if (f.adaptive) line += fmt::format(" (adaptive, mean {:.1f})", f.mean_spp);
        line += fmt::format(", {:.2f} s, {:.2f} Mrays/s", f.seconds,
                            f.rays_per_second * 1e-6);
        if (f.nonfinite_samples)
            line += fmt::format(", {} non-finite samples dropped", f.nonfinite_samples);
        std::printf("%s\n", line.c_str());
    }

  private:
    const JobReporting &m_r;
};

}  // namespace

int run_reported(RenderJob job, const JobReporting &reporting) {
    job.ctrl_c_stops = true;
    job.progress = reporting.quiet.progress();
    job.instrument = reporting.stats_json.wanted();  // plugin_seconds
    if (reporting.stats_json.wanted())
        job.other_outputs.emplace_back("--stats-json", reporting.stats_json.path);
    PrintedRun observer(reporting);
    const RenderTotals totals = run_render_job(job, observer);
    if (totals.aborted) return exit_interrupted;
    if (reporting.stats_json.wanted()) {
        nlohmann::json j = render_stats_json(job, totals);
        j["threads"] = reporting.threads;
        reporting.stats_json.write(j);
    }
    if (totals.animated && !reporting.quiet)
        std::printf("%d frame(s) rendered, %d skipped (complete), %.2f s\n",
                    totals.rendered, totals.skipped, totals.seconds);
    if (!reporting.quiet) {
        std::printf("wall %.2f s: set-up %.2f s, render %.2f s, ", totals.wall_seconds,
                    totals.setup_seconds, totals.seconds);
        if (totals.denoise_seconds > 0)  // its share, so the parts add up to the wall
            std::printf("denoise %.2f s, ", totals.denoise_seconds);
        std::printf("writing %.2f s\n", totals.write_seconds);
    }
    return totals.interrupted ? exit_interrupted : 0;
}

}  // namespace pelage::renderer::cli
