// An export (renderer/export/export_job.h) as the commands show it: the patterns' notes
// on stderr, one line on stdout of what was written, and its JSON for --stats-json.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "apps/common/common.h"
#include "renderer/export/export_job.h"

namespace pelage::renderer::cli {

ExportReport run_export_reported(const ExportJob &job, const std::string &command,
                                 const QuietOption &quiet);
nlohmann::json export_report_json(const ExportReport &report);

}  // namespace pelage::renderer::cli
