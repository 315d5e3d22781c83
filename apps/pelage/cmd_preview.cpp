// `pelage preview FILE.cells -o out.png`: a quick orthographic, flat-shaded view of the
// mesh stored in a .cells file with its cells as coloured dots (a debugging view, not
// the renderer; sim/cells_report/cells_preview.h).
#include <cmath>

#include "apps/common/common.h"
#include "renderer/image/image_output.h"
#include "sim/cells_io/cells_file.h"
#include "sim/cells_report/cells_preview.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

struct PreviewCliOptions {
    std::string file, output, res;
    sim::PreviewOptions view;
    std::vector<double> direction;
};

int run_preview(PreviewCliOptions o) {
    if (o.direction.size() == 3) {
        const double len2 = o.direction[0] * o.direction[0] +
                            o.direction[1] * o.direction[1] +
                            o.direction[2] * o.direction[2];
        if (!(len2 > 0) || !std::isfinite(len2))
            throw InputError("", 0, "--direction", "must be a non-zero direction");
        o.view.view = {o.direction[0], o.direction[1], o.direction[2]};
    }
    if (!o.res.empty()) {
        const Resolution r =
            parse_resolution(o.res, 8192, ResolutionForm::or_longer_side, "--res", 16);
        if (r.longer_side_only) {
            o.view.size = r.width;
        } else {
            o.view.width = r.width;
            o.view.height = r.height;
        }
    }
    const sim::CellsData data = sim::read_cells_file(o.file);
    const sim::PreviewImage img = sim::render_cells_preview(data, o.view);
    renderer::write_rgb8(o.output, img.width, img.height, img.rgb);
    return 0;
}

}  // namespace

Runner add_preview_command(CLI::App &app) {
    auto o = std::make_shared<PreviewCliOptions>();
    CLI::App *sub =
        app.add_subcommand("preview", "Debugging picture of a .cells file (PNG)");
    sub->add_option("file", o->file, ".cells file")->required();
    sub->add_option("-o,--output", o->output, "PNG to write")->required();
    sub->add_option("--res", o->res,
                    "WIDTHxHEIGHT (the mesh fit inside), or the longer side N, the other "
                    "following the mesh (default 800)");
    sub->add_option("--direction", o->direction,
                    "Viewing direction X Y Z (default 0 0 -1)")
        ->expected(3);
    sub->add_option("--dot", o->view.dot_radius, "Dot radius in pixels")
        ->check(CLI::Range(0, 16));
    return [o] { return run_preview(*o); };
}

}  // namespace pelage::renderer::cli
