// The body of the `pelage` command, lib/pelage/libpelage_cli.so: bin/pelage
// (launcher.cpp) loads it and calls pelage_cli_main. One command, subcommands composed
// through files and JSON (docs/design.md).
// Exit codes: 0 success, 1 runtime failure, 2 bad usage or bad input.
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "apps/common/common.h"
#include "apps/pelage/version.h"
#include "sim/core/input_error.h"
#include "sim/core/spelling.h"

namespace {

// Where the command line names a command (`pelage COMMAND`, `pelage bench COMMAND`),
// the word must be one; CLI11 itself would say only that a subcommand is required, or
// that the word was not expected. No word there prints that level's usage, which lists
// its commands. Returns the exit code when the command line stops here, -1 to go on.
int check_command_words(CLI::App &app, int argc, char **argv) {
    CLI::App *level = &app;
    std::string path = "pelage";
    for (int i = 1; level->get_require_subcommand_min() > 0; ++i) {
        if (i == argc) {
            std::fputs(level->help().c_str(), stderr);
            return 2;
        }
        const std::string word = argv[i];
        if (word.empty() || word[0] == '-') return -1;  // --help, --version: CLI11's
        std::vector<std::string> names;
        CLI::App *next = nullptr;
        for (CLI::App *sub : level->get_subcommands({})) {
            names.push_back(sub->get_name());
            if (sub->check_name(word)) next = sub;
        }
        if (!next) {
            const std::string guess = pelage::sim::closest_name(word, names);
            if (!guess.empty()) {
                std::fprintf(stderr, "%s: unknown command \"%s\"; did you mean \"%s\"?\n",
                             path.c_str(), word.c_str(), guess.c_str());
            } else {
                std::string list;
                for (const std::string &n : names) list += (list.empty() ? "" : ", ") + n;
                std::fprintf(stderr, "%s: unknown command \"%s\" (commands: %s)\n",
                             path.c_str(), word.c_str(), list.c_str());
            }
            return 2;
        }
        level = next;
        path += " " + word;
    }
    return -1;
}

// A default the option itself refuses (--spp 0 where --spp takes 1 and up, --crf -1
// where it takes 0 to 51) or an empty list stands for "not given": the scene's, the
// preset's or the program's own choice, which the option's description names. --help
// shows no default for it rather than a value that is never used.
void hide_unused_defaults(CLI::App &app) {
    for (CLI::Option *opt : app.get_options()) {
        const std::string value = opt->get_default_str();
        if (value.empty()) continue;
        bool unused = value == "[]";
        for (int i = 0; !unused && value.front() != '['; ++i) {
            CLI::Validator *check = nullptr;
            try {
                check = opt->get_validator(i);
            } catch (const CLI::OptionNotFound &) {
                break;
            }
            std::string copy = value;
            unused = !(*check)(copy).empty();
        }
        if (unused) opt->default_str("");
    }
    for (CLI::App *sub : app.get_subcommands({})) hide_unused_defaults(*sub);
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int pelage_cli_main(int argc,
                                                                      char **argv) {
    using namespace pelage;
    CLI::App app{
        "pelage " PELAGE_VERSION
        " - a physically based renderer for animal coats (Clonal Mosaic patterns)",
        "pelage"};
    app.require_subcommand(1);
    app.set_version_flag("--version", PELAGE_VERSION_LINE);
    // Every option's default in its --help line; subcommands inherit this when created.
    app.option_defaults()->always_capture_default();

    std::vector<std::pair<CLI::App *, renderer::cli::Runner>> commands;
    auto add = [&](renderer::cli::Runner (*fn)(CLI::App &)) {
        const size_t before = app.get_subcommands({}).size();
        renderer::cli::Runner run = fn(app);
        commands.emplace_back(app.get_subcommands({})[before], std::move(run));
    };
    add(renderer::cli::add_look_command);
    add(renderer::cli::add_explore_command);
    add(renderer::cli::add_crps_command);
    add(renderer::cli::add_sim_command);
    add(renderer::cli::add_stats_command);
    add(renderer::cli::add_preview_command);
    add(renderer::cli::add_render_command);
    add(renderer::cli::add_shaders_command);
    add(renderer::cli::add_fields_command);
    add(renderer::cli::add_presets_command);
    add(renderer::cli::add_info_command);
    add(renderer::cli::add_compare_command);
    add(renderer::cli::add_cells_command);
    add(renderer::cli::add_lookup_command);
    add(renderer::cli::add_bake_command);
    add(renderer::cli::add_export_command);
    add(renderer::cli::add_movie_command);
    add(renderer::cli::add_matte_command);
    add(renderer::cli::add_merge_command);
    add(renderer::cli::add_bench_command);

    hide_unused_defaults(app);

    if (const int rc = check_command_words(app, argc, argv); rc >= 0) return rc;
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
