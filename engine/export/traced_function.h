// A model function (the right-hand side, the output map) recorded on expressions
// (model/expression.h) along every path its decisions allow, and written as the body of a C
// function: the paths form a decision tree, each decision an `if`, each leaf either the
// results (`out[i] = ...; return 1;`) or a refusal (`return 0;`, the model rejecting a state or
// parameter, as the engine's `return false`). Temporaries needed on both sides of a decision
// are computed before it, so code shared by the branches appears once.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/model/expression.h"

namespace vesselid {

struct TracedPath {
  std::vector<symbolic::ExpressionDecision> decisions;
  bool ok = true;            // false: the function refused on this path
  std::vector<int> results;  // result nodes (when ok)
};

struct TracedFunction {
  std::vector<TracedPath> paths;
};

// Runs `trace` (records on `tape`, the current tape; fills the result nodes; returns false
// where the function refuses) once per outcome sequence of its decisions, depth first.
// False with a message when it takes more than `max_paths` paths.
bool TraceFunction(symbolic::ExpressionTape* tape,
                   const std::function<bool(std::vector<int>* results)>& trace, int max_paths,
                   TracedFunction* function, std::string* error);

// The statements of the C function (indented by two spaces per level from `indent`): results
// are stored in `out[i]`; with `status`, a leaf returns 1 and a refusal 0 (a function without
// status must have no refusal).
std::string TracedFunctionToC(const symbolic::ExpressionTape& tape, const TracedFunction& function,
                              const std::string& out, bool status, int indent);

// A double as a C99 literal that reads back to the same value (NAN, INFINITY where needed).
std::string CDoubleLiteral(double value);

}  // namespace vesselid
