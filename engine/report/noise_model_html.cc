#include "engine/report/noise_model_html.h"

#include <sstream>

#include "engine/output/noise_model_report.h"
#include "engine/report/report_tables.h"

namespace vesselid {

std::string NoiseModelHtml(const RunConfig& config, const StageResult& stage) {
  const NoiseModel& noise = stage.noise_model;
  if (!noise.active()) return "";
  std::ostringstream html;
  html << "<h3>Noise model (weights 1/&sigma; per channel)</h3>\n<p>Maximum likelihood for "
          "Gaussian noise of unknown variance per output channel: "
       << HtmlEscape(NoiseSettling(noise))
       << ". The standard errors use these weights.</p>\n<table>\n<tr><th>output</th>"
          "<th>&sigma;</th><th>unit</th><th>samples</th></tr>\n";
  for (size_t k = 0; k < noise.outputs.size(); ++k) {
    const DisplayUnit unit = NoiseUnitOf(config, stage, noise.outputs[k]);
    html << "<tr><td>" << HtmlEscape(noise.outputs[k]) << "</td><td class=\"num\">"
         << HtmlNumber(noise.sigma[k] * unit.scale, "%.4g") << "</td><td>"
         << HtmlEscape(unit.unit) << "</td><td class=\"num\">" << noise.samples[k]
         << "</td></tr>\n";
  }
  html << "</table>\n";
  return html.str();
}

}  // namespace vesselid
