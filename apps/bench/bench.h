// The children of `pelage bench`, one file each.
#pragma once

#include "apps/common/common.h"

namespace pelage::renderer::cli {

// What every benchmark shares: its result, one JSON object, printed on stdout (unless
// -q) and written to --stats-json.
struct BenchOutput {
    QuietOption quiet;
    StatsJsonOption stats_json;
    void add_to(CLI::App &benchmark);
    void emit(const nlohmann::json &j) const;
};

Runner add_bench_crps(CLI::App &bench);
Runner add_bench_lookup(CLI::App &bench);
Runner add_bench_sim(CLI::App &bench);
Runner add_bench_render(CLI::App &bench);
Runner add_bench_hair(CLI::App &bench);
Runner add_bench_fur(CLI::App &bench);
Runner add_bench_fur_colour(CLI::App &bench);
Runner add_bench_preset_colour(CLI::App &bench);
Runner add_bench_fur_comb(CLI::App &bench);
Runner add_bench_noise(CLI::App &bench);
Runner add_bench_export(CLI::App &bench);

}  // namespace pelage::renderer::cli
