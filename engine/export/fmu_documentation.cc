#include "engine/export/fmu_documentation.h"

#include <cmath>
#include <cstdio>

#include "engine/report/report_tables.h"

namespace vesselid {
namespace {

std::string NumberCell(double value) {
  if (std::isnan(value)) return "";
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

// What installs a library on Debian and Ubuntu, for the libraries vesselid's runtime can need.
std::string Provider(const std::string& library) {
  if (library.rfind("libyaml-cpp.so.0.7", 0) == 0) return "package libyaml-cpp0.7";
  if (library.rfind("libstdc++.so", 0) == 0) return "the GNU C++ runtime, package libstdc++6";
  if (library.rfind("libgcc_s.so", 0) == 0) return "the GCC runtime, package libgcc-s1";
  if (library.rfind("libc.so", 0) == 0 || library.rfind("libm.so", 0) == 0 ||
      library.rfind("ld-linux", 0) == 0) {
    return "the C library (glibc), on every Linux system";
  }
  return "";
}

}  // namespace

std::string FmuDocumentationHtml(const IdentifiedModel& model, const std::vector<std::string>& needs) {
  std::string html = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" +
                     HtmlEscape(model.model) + "</title></head><body>\n<h1>" +
                     HtmlEscape(model.model) + "</h1>\n<p>Model family " +
                     HtmlEscape(model.family) + ", identified by vesselid from " +
                     HtmlEscape(model.results) +
                     ". Setting <code>ensemble_member</code> k flies the k-th of " +
                     std::to_string(model.ensemble.size()) + " parameter draws (" +
                     HtmlEscape(model.ensemble_source) +
                     "); a parameter the master sets to a value of its own keeps it.</p>\n";
  html += "<h2>Parameters</h2>\n<table>\n<tr><th>name</th><th>value</th><th>standard error</th>"
          "<th>unit</th></tr>\n";
  for (size_t i = 0; i < model.parameters.size(); ++i) {
    html += "<tr><td>" + HtmlEscape(model.parameters[i].name) + "</td><td>" +
            NumberCell(model.values[i]) + "</td><td>" +
            NumberCell(i < model.std_errors.size() ? model.std_errors[i] : NAN) + "</td><td>" +
            HtmlEscape(model.parameters[i].unit) + "</td></tr>\n";
  }
  html += "</table>\n<h2>Runtime dependencies</h2>\n<p>binaries/linux64 (x86-64) needs these "
          "shared libraries on the machine that loads it:</p>\n<ul>\n";
  for (const std::string& library : needs) {
    const std::string provider = Provider(library);
    html += "<li><code>" + HtmlEscape(library) + "</code>" +
            (provider.empty() ? "" : " (" + HtmlEscape(provider) + ")") + "</li>\n";
  }
  html += "</ul>\n</body></html>\n";
  return html;
}

}  // namespace vesselid
