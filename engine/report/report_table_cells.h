// Cells of the report's HTML tables: text cells are escaped, number cells right-aligned.
#pragma once

#include <cmath>
#include <string>

#include "engine/report/report_tables.h"

namespace vesselid {

inline std::string Th(const std::string& text) { return "<th>" + HtmlEscape(text) + "</th>"; }
inline std::string Td(const std::string& text) { return "<td>" + HtmlEscape(text) + "</td>"; }
// `text` is a formatted number (no markup).
inline std::string Num(const std::string& text) {
  return "<td class=\"num\">" + HtmlEscape(text) + "</td>";
}

// "[lower, upper]" with infinite ends as "−∞" and "∞".
inline std::string Bounds(double lower, double upper) {
  auto end = [](double v) {
    if (std::isinf(v)) return std::string(v < 0 ? "−∞" : "∞");
    return HtmlNumber(v, "%.6g");
  };
  return "[" + end(lower) + ", " + end(upper) + "]";
}

// The table folded under `summary` when it has more than `open_rows` rows.
inline std::string Fold(const std::string& table, size_t rows, const std::string& summary,
                        size_t open_rows) {
  if (rows <= open_rows) return table;
  return "<details><summary>" + HtmlEscape(summary) + "</summary>\n" + table + "</details>\n";
}

}  // namespace vesselid
