// The MClone case of `pelage bench sim`: Walter's cheetah-like run (thesis Fig. 3.10
// with Queiroz's w_d) on the cow, in both relaxation modes, in CPU seconds against the
// original author's program on the same configuration.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace pelage::renderer::cli {

struct McloneOptions {
    std::string mesh;  // the cow
    uint64_t seed = 1;
    int repeat = 3;  // the fastest counts
};

// {"mclone": {"mesh", "initial_cells", "mclone_cpu_seconds", "runs": [{relax,
// cpu_seconds, seconds, final_cells, cell_steps, ns_per_cell_step, speedup}]}}.
nlohmann::json mclone_runs(const McloneOptions &o);

}  // namespace pelage::renderer::cli
