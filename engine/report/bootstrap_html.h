// A regression stage's bootstrap (output/bootstrap_report.h) as report.html shows it.
#pragma once

#include <string>

#include "engine/run/run_result.h"

namespace vesselid {

// report.html: a paragraph and two tables; empty without a bootstrap.
std::string BootstrapHtml(const StageResult& stage);

}  // namespace vesselid
