// A reference model for the final validation (`final_validation: {reference: <folder>}`): the
// identified model of another run, flown on the same held-out runs from their measured starts
// as the final values, so that a model identified from fewer or other runs is held against
// one the user already trusts. Read when the config is (ModelRegistry::ReferenceReader;
// export/reference_model.h reads a run's results.json).
#pragma once

#include <string>
#include <vector>

namespace vesselid {

struct ReferenceModel {
  std::string folder;          // the run's output folder, as resolved
  std::vector<double> values;  // in the run's model's parameter order
};

}  // namespace vesselid
