// Readers of config sections shared by the files that parse a config (config.cc,
// study_config.cc, step_regression_config.cc). Each fails through YamlReader with the file,
// line and key.
#pragma once

#include <string>
#include <vector>

#include "engine/config/experiment_sets.h"
#include "engine/config/yaml_reader.h"
#include "engine/run/run_config.h"
#include "engine/study/study_options.h"

namespace vesselid {

// `global: {algorithm, points, short_iterations, threads, max_evaluations, max_time, seed,
// population, candidates, min_separation, horizons}` over the values already in `global`.
// `horizons` (auto | none | [lengths]) only where `horizons` is given (a stage's global start).
void ReadGlobal(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                GlobalStartOptions* global, SearchHorizons* horizons = nullptr);

// Segment lengths in s, > 0 and increasing (a stage's `continuation`, `global.horizons`).
std::vector<double> ReadSegmentLengths(const YamlReader& reader, const YAML::Node& node,
                                       const std::string& key);

// A stage's `uncertainty`: true | false, or {method, bandwidth, kernel, prewhiten}
// (uncertainty_config.cc) over the values already in `options`.
void ReadUncertainty(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                     StageOptions* options);
// experiment_bootstrap refused (file:line) when the stage's experiments are known to be fewer
// than kMinBootstrapExperiments (none cut into segments or ranges).
void CheckBootstrapExperiments(const YamlReader& reader, const YAML::Node& node,
                               const std::string& path, const RunConfig& config,
                               const StageConfig& stage);

// Fails unless every name is in `known` (a model's `kind` names, e.g. outputs).
void CheckNames(const YamlReader& reader, const YAML::Node& node, const std::string& key,
                const std::vector<std::string>& names, const std::vector<std::string>& known,
                const std::string& kind, const ModelInfo& info);

// `grid` and `smoothing` keys of a regression stage's map (regression_data.h).
void ReadRegressionData(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                        const ModelInfo& info, RegressionDataOptions* data);

// The `bootstrap` key of a regression stage, a run count or a map (bootstrap_config.cc);
// `blocks` is allowed for least-squares stages.
void ReadBootstrap(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                   bool blocks, GroupBootstrapOptions* bootstrap);

// The `step_regression` map of a step-regression stage (step_regression_config.cc).
void ReadStepRegression(const YamlReader& reader, const YAML::Node& node,
                        const std::string& path, const ModelHandle& model, StageConfig* stage);

// `surfaces: {<state>: [lower, upper, points], ...}` for both regressed states of the model's
// damping-inertia form.
SurfaceGrid ReadSurfaces(const YamlReader& reader, const YAML::Node& node, const ModelHandle& model);

// The `study` section (study_options.h); a Monte Carlo part without its own `truth` takes the
// `simulation` map's.
StudyConfig ReadStudy(const YamlReader& reader, const YAML::Node& node, const RunConfig& config,
                      const YAML::Node& simulation);

}  // namespace vesselid
