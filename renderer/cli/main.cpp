// pelage: one binary, subcommands composed through files and JSON (docs/design.md).
// Exit codes: 0 success, 1 runtime failure, 2 bad usage or bad input.
#include <cstdio>
#include <exception>
#include <new>
#include <vector>

#include "renderer/cli/common.h"
#include "sim/core/input_error.h"

int main(int argc, char **argv) {
    using namespace pelage;
    CLI::App app{
        "pelage " PELAGE_VERSION
        " - a physically based renderer for animal coats (Clonal Mosaic patterns)",
        "pelage"};
    app.require_subcommand(1);
    app.set_version_flag("--version", PELAGE_VERSION);

    std::vector<std::pair<CLI::App *, renderer::cli::Runner>> commands;
    auto add = [&](renderer::cli::Runner (*fn)(CLI::App &)) {
        const size_t before = app.get_subcommands({}).size();
        renderer::cli::Runner run = fn(app);
        commands.emplace_back(app.get_subcommands({})[before], std::move(run));
    };
    add(renderer::cli::add_look_command);
    add(renderer::cli::add_crps_command);
    add(renderer::cli::add_sim_command);
    add(renderer::cli::add_stats_command);
    add(renderer::cli::add_preview_command);
    add(renderer::cli::add_render_command);
    add(renderer::cli::add_shaders_command);
    add(renderer::cli::add_compare_command);
    add(renderer::cli::add_cells_command);
    add(renderer::cli::add_lookup_command);
    add(renderer::cli::add_bake_command);
    add(renderer::cli::add_movie_command);
    add(renderer::cli::add_matte_command);
    add(renderer::cli::add_merge_command);
    add(renderer::cli::add_bench_command);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        const int rc = app.exit(e);  // prints help or the error
        return rc == 0 ? 0 : 2;
    }

    for (auto &[sub, run] : commands) {
        if (!sub->parsed()) continue;
        const std::string name = "pelage " + sub->get_name();
        try {
            return run();
        } catch (const InputError &e) {
            std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
            return 2;
        } catch (const std::bad_alloc &) {
            std::fprintf(stderr, "%s: out of memory\n", name.c_str());
            return 1;
        } catch (const std::exception &e) {
            std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
            return 1;
        }
    }
    return 2;
}
