// A run's model as self-contained C99 (`vesselid export --format c`): <name>.h and <name>.c
// with the right-hand side and output map written from the model's own templated equations
// (recorded on expressions, traced_function.h), an RK4 step as the engine takes it, a record
// simulation with the run's step rule and input interpolation, the parameter values, their
// standard errors and covariance and the ensemble members; and <name>_example.c, a short
// program that simulates the model from rest for the estimate and every member. The code
// needs only <math.h> (and <stdlib.h> for the median step) and compiles with
// `cc -std=c99 -Wall -Werror`.
#pragma once

#include <string>
#include <vector>

#include "engine/export/model_json.h"
#include "engine/model/model_handle.h"

namespace vesselid {

struct CModelFile {
  std::string name, text;
};

// The header, source and example of `model` (whose equations `handle` holds). False with a
// message when the model's decisions take too many paths to write out.
bool MakeCModel(const IdentifiedModel& model, const ModelHandle& handle,
                std::vector<CModelFile>* files, std::string* error);

// The C identifier the files and functions are named by (the model's name, e.g.
// "nomoto_norrbin_n1_speed").
std::string CIdentifier(const std::string& name);

}  // namespace vesselid
