#include "engine/output/shown_parameters.h"

#include <initializer_list>

namespace vesselid {
namespace {

// Scaling by a positive factor keeps the order of bounds and interval ends.
void Scale(double scale, std::initializer_list<double*> values) {
  for (double* v : values) *v *= scale;
}

}  // namespace

Estimate Shown(const Estimate& estimate, const DisplayUnit& unit) {
  Estimate e = estimate;
  Scale(unit.scale, {&e.value, &e.start, &e.std_error, &e.lower, &e.upper});
  return e;
}

FinalParameter Shown(const FinalParameter& parameter, const DisplayUnit& unit) {
  FinalParameter f = parameter;
  Scale(unit.scale, {&f.value, &f.std_error, &f.runs_min, &f.runs_max});
  return f;
}

ParameterReport Shown(const ParameterReport& report, const DisplayUnit& unit) {
  ParameterReport r = report;
  Scale(unit.scale, {&r.lower, &r.upper, &r.interval_low, &r.interval_high});
  return r;
}

}  // namespace vesselid
