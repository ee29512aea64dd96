// Recorded experiments of a run made ready for a stage: each configured record read once
// (TrajectoryCache), cut into the experiments it is identified as (its `segment` column, a
// length, input ranges), and built for a model (output error) or as regression records
// (equation error).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "engine/model/experiment.h"
#include "engine/model/model_handle.h"
#include "engine/regression/regression_data.h"
#include "engine/run/run_config.h"
#include "engine/run/trajectory_cache.h"

namespace vesselid {

// The configured record an experiment comes from: a segment "<record>@<id>" or a piece
// "<record>#<k>" of it, or the record itself.
inline std::string RecordName(const std::string& experiment) {
  return experiment.substr(0, experiment.find_first_of("@#"));
}

// The data of `spec` from the cache, read (LoadExperimentData) on first use; null on error.
inline const Trajectory* LoadCachedTrajectory(const ExperimentSpec& spec, TrajectoryCache* cache,
                                              std::string* error) {
  return cache->Load(spec, error);
}

// The finite samples of `column` within the experiment's time window [t_begin, t_end], read
// through the cache; false when the data cannot be read or have no such column (checks that
// look at one column pass over it then).
bool WindowSamples(const ExperimentSpec& spec, const std::string& column, TrajectoryCache* cache,
                   std::vector<double>* values);

// Reads and prepares experiments for a model (used by RunIdentification and by tools); the
// model guesses initial states from the data (ModelHandle::GuessState). segment_length > 0
// cuts every record into segments no longer than that (continuation phases); 0 keeps each
// experiment's own segmentation.
bool PrepareExperiments(const RunConfig& config, const std::vector<std::string>& names,
                        const ModelHandle& model, const ExperimentOptions& options,
                        TrajectoryCache* cache, std::vector<Experiment>* experiments,
                        std::string* error, double segment_length = 0.0);

// The experiments a configured record is identified as: itself, its segments (segments
// column) or consecutive pieces no longer than segment_length (its own or the given one).
bool RecordSpecs(const ExperimentSpec& spec, const Trajectory& data, double segment_length,
                 std::vector<ExperimentSpec>* specs, std::string* error);

// Equation-error records of `names` (each segment its own record).
bool PrepareRegressionRecords(const RunConfig& config, const std::vector<std::string>& names,
                              const ModelHandle& model, const RegressionDataOptions& options,
                              TrajectoryCache* cache, std::vector<RegressionRecord>* records,
                              std::string* error);

}  // namespace vesselid
