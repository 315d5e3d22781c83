// `pelage bench <what>`: benchmarks of the hot paths, one JSON object on stdout each.
#include <iostream>
#include <vector>

#include "apps/bench/bench.h"

namespace pelage::renderer::cli {

void BenchOutput::add_to(CLI::App &benchmark) {
    stats_json.add_to(benchmark, "the benchmark's result (what stdout shows)");
    quiet.add_to(benchmark);
}

void BenchOutput::emit(const nlohmann::json &j) const {
    if (!quiet) std::cout << j.dump(2) << std::endl;
    stats_json.write(j);
}

Runner add_bench_command(CLI::App &app) {
    CLI::App *bench =
        app.add_subcommand("bench", "Benchmarks of the hot paths; each prints JSON");
    bench->require_subcommand(1);
    std::vector<std::pair<CLI::App *, Runner>> children;
    auto add = [&](Runner (*fn)(CLI::App &)) {
        const size_t before = bench->get_subcommands({}).size();
        Runner run = fn(*bench);
        children.emplace_back(bench->get_subcommands({})[before], std::move(run));
    };
    add(add_bench_crps);
    add(add_bench_lookup);
    add(add_bench_sim);
    add(add_bench_render);
    add(add_bench_hair);
    add(add_bench_fur);
    add(add_bench_fur_colour);
    add(add_bench_preset_colour);
    add(add_bench_fur_comb);
    add(add_bench_noise);
    add(add_bench_export);
    return [children] {
        for (const auto &[sub, run] : children)
            if (sub->parsed()) return run();
        return 2;
    };
}

}  // namespace pelage::renderer::cli
