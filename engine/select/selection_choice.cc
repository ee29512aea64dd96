#include "engine/select/selection_choice.h"

#include <cmath>
#include <cstdio>

namespace vesselid {

void ChooseByOneStandardError(SelectionResult* result) {
  std::vector<SelectionCandidate>& c = result->candidates;
  result->best = result->chosen = -1;
  for (int i = 0; i < static_cast<int>(c.size()); ++i) {
    c[i].within_one_se = false;
    if (c[i].usable && std::isfinite(c[i].score) &&
        (result->best < 0 || c[i].score > c[result->best].score)) {
      result->best = i;
    }
  }
  if (result->best < 0) {
    result->reason = "no candidate could be scored";
    return;
  }
  const SelectionCandidate& best = c[result->best];
  const double se = std::isfinite(best.score_se) ? best.score_se : 0.0;
  const double threshold = best.score - se;
  for (int i = 0; i < static_cast<int>(c.size()); ++i) {
    if (!c[i].usable || !(c[i].score >= threshold)) continue;
    c[i].within_one_se = true;
    const int j = result->chosen;
    if (j < 0 || c[i].complexity < c[j].complexity ||
        (c[i].complexity == c[j].complexity && c[i].score > c[j].score)) {
      result->chosen = i;
    }
  }
  const SelectionCandidate& chosen = c[result->chosen];
  char text[512];
  if (result->chosen == result->best) {
    std::snprintf(text, sizeof(text),
                  "'%s': the best cross-validated score (%.2f %% +- %.2f), and no simpler "
                  "candidate within one standard error of it (>= %.2f %%)",
                  chosen.name.c_str(), best.score, se, threshold);
  } else {
    std::snprintf(text, sizeof(text),
                  "'%s' (%d shared parameters, %.2f %%): the simplest candidate within one "
                  "standard error of the best, '%s' (%d shared parameters, %.2f %% +- %.2f; "
                  "threshold %.2f %%)",
                  chosen.name.c_str(), chosen.complexity, chosen.score, best.name.c_str(),
                  best.complexity, best.score, se, threshold);
  }
  result->reason = text;
}

}  // namespace vesselid
