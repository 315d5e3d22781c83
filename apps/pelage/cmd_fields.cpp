// `pelage fields [TABLE]`: the scene file's reference tables, printed from the table the
// parser reads by (renderer/scene_file/scene_fields.h), as Markdown: the same text as
// docs/guide/scene-format.md and fur.md, which a test keeps equal to it.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "apps/common/common.h"
#include "renderer/scene_file/scene_fields.h"
#include "sim/core/input_error.h"
#include "sim/core/spelling.h"

namespace pelage::renderer::cli {
namespace {

struct FieldsOptions {
    std::string table;
};

int run(const FieldsOptions &o) {
    const std::vector<std::string> tables = scene_field_tables();
    if (!o.table.empty()) {
        bool known = false;
        for (const std::string &t : tables) known = known || t == o.table;
        if (!known) {
            std::string all;
            for (const std::string &t : tables) all += (all.empty() ? "" : ", ") + t;
            const std::string guess = sim::closest_name(o.table, tables);
            throw InputError(
                "", 0, "TABLE",
                "no table \"" + o.table + "\"" +
                    (guess.empty() ? "" : " (did you mean \"" + guess + "\"?)") +
                    "; the tables are " + all);
        }
        std::fputs(scene_fields_markdown(o.table).c_str(), stdout);
        return 0;
    }
    for (size_t i = 0; i < tables.size(); ++i)
        std::printf("%s## %s\n\n%s", i ? "\n" : "", tables[i].c_str(),
                    scene_fields_markdown(tables[i]).c_str());
    return 0;
}

}  // namespace

Runner add_fields_command(CLI::App &app) {
    auto o = std::make_shared<FieldsOptions>();
    CLI::App *sub = app.add_subcommand("fields",
                                       "Print the scene file's fields (the tables of "
                                       "docs/guide/scene-format.md, fur.md)");
    sub->add_option("table", o->table,
                    "Only this table: camera, film, lights, objects, transform, "
                    "material, integrator, animation or fur");
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
