// A render job (renderer/job/render_job.h) run as the commands show it: each frame's
// line and the summary on stdout, warnings on stderr under the command's name, the
// totals to --stats-json, and the exit code (130 when Ctrl-C stopped it).
#pragma once

#include <string>

#include "apps/common/common.h"
#include "renderer/job/render_job.h"

namespace pelage::renderer::cli {

// Stopped by Ctrl-C: the shell convention 128 + SIGINT, so scripts can tell an
// interrupted render (whose EXR is whole but marked pelage:interrupted) from a failure.
constexpr int exit_interrupted = 128 + 2;

struct JobReporting {
    std::string command = "pelage render";  // names the warnings
    QuietOption quiet;
    StatsJsonOption stats_json;
    int threads = 0;  // as --threads gave it, for the statistics
};

// Runs `job` with Ctrl-C stopping it at the next tile; returns the exit code.
int run_reported(RenderJob job, const JobReporting &reporting);

}  // namespace pelage::renderer::cli
