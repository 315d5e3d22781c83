#include "apps/pelage/export_report.h"

#include <fmt/core.h>

#include <cstdio>

namespace pelage::renderer::cli {

ExportReport run_export_reported(const ExportJob &job, const std::string &command,
                                 const QuietOption &quiet) {
    const ExportReport r = run_export(job, [&](const std::string &note) {
        if (!quiet) std::fprintf(stderr, "%s: %s\n", command.c_str(), note.c_str());
    });
    if (!quiet) {
        fmt::print("{}: wrote {} ({} skin{}, {} triangles", command, r.files[0], r.skins,
                   r.skins == 1 ? "" : "s", r.triangles);
        if (r.strands) fmt::print(", {} strands of fur", r.strands);
        if (r.frames.size() > 1) fmt::print(", {} frames", r.frames.size());
        fmt::print("; {:.1f} MB", double(r.bytes) / 1e6);
        for (size_t k = 1; k < r.files.size(); ++k)
            fmt::print("{}{}", k == 1 ? "; texture " : ", ", r.files[k]);
        fmt::print("): set-up {:.2f} s, ", r.setup_seconds);
        if (r.files.size() > 1) fmt::print("textures {:.2f} s, ", r.texture_seconds);
        fmt::print("export {:.2f} s\n", r.write_seconds);
    }
    return r;
}

nlohmann::json export_report_json(const ExportReport &r) {
    return {{"files", r.files},
            {"frames", r.frames},
            {"skins", r.skins},
            {"triangles", r.triangles},
            {"strands", r.strands},
            {"points", r.points},
            {"bytes", r.bytes},
            {"setup_seconds", r.setup_seconds},
            {"texture_seconds", r.texture_seconds},
            {"export_seconds", r.write_seconds}};
}

}  // namespace pelage::renderer::cli
