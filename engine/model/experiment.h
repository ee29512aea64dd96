// One recorded experiment prepared for output-error simulation.
//
// The integration grid has a node at the start time t0 and at every time where a selected
// output is sampled; between nodes k and k+1 it takes node_substeps[k] equal RK4 steps of
// length node_step[k] <= max_step. Inputs are interpolated once, at every step's start,
// midpoint and end, so the simulation loop only reads an array.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/data/interpolation.h"
#include "engine/data/segments.h"
#include "engine/data/trajectory.h"
#include "engine/model/experiment_data.h"
#include "engine/model/input_noise.h"
#include "engine/model/model.h"
#include "engine/model/record_channels.h"

namespace vesselid {

// What a config says about one experiment.
struct ExperimentSpec {
  std::string name;
  std::string file;                                    // CSV path as resolved by the config
  // The data folder `file` lies outside of (read under limits.outside_data), else empty.
  std::string outside_data_folder;
  // The record in memory (a program's arrays, a DataFrame from Python: trajectory_table.h);
  // when set it is used instead of `file`, which may then be empty.
  std::shared_ptr<const Trajectory> table;
  CsvReadOptions csv;                                  // separator and size limits
  std::map<std::string, std::string> inputs;           // model input -> column
  std::map<std::string, std::string> outputs;          // model output -> column
  std::map<std::string, Interpolation> interpolation;  // per model input (default below)
  Interpolation default_interpolation = Interpolation::kLinear;
  std::map<std::string, double> output_weights;  // per model output, default 1
  std::map<std::string, double> initial_state;   // per state; absent: see BuildExperiment
  std::vector<std::string> degree_columns;       // columns recorded in degrees
  bool IsDegreeColumn(const std::string& column) const {
    for (const std::string& c : degree_columns) {
      if (c == column) return true;
    }
    return false;
  }
  // Angle outputs compared modulo one turn (residual wrapped to (-pi, pi]) instead of
  // unwrapped: for a sensor whose jumps the sampling cannot resolve.
  std::vector<std::string> wrapped_outputs;
  double t_begin = -std::numeric_limits<double>::infinity();
  double t_end = std::numeric_limits<double>::infinity();
  // > 0: the record is identified as consecutive segments of this length, each simulated
  // from its own initial state ("<name>@<k>"), so that errors do not grow over a long or
  // unstable record (segmented output error).
  double segment_length = 0.0;
  // segments.column set: the record holds segments told apart by that column, each
  // identified as "<name>@<id>" from its own initial state (see segments.h).
  SegmentSelection segments;
  // Model input -> [lower, upper]: only the stretches where every listed input is inside are
  // identified, each from its own initial state ("<name>#<k>", input_range.h).
  std::map<std::string, std::pair<double, double>> input_range;
  double input_range_min_duration = 10.0;  // s, shorter stretches are dropped
  // s dropped at the start of a stretch that follows one outside the ranges: the state is
  // still leaving the region the model is not identified in.
  double input_range_skip = 0.0;
  // time, position, screen and resample keys: preparation of the raw columns.
  ExperimentDataSpec data;
  // Model input -> noise description: the input is simulated as a latent signal (input_noise.h).
  std::map<std::string, InputNoiseSpec> input_noise;
};

struct ExperimentSample {
  int output;     // model output index
  double value;   // measurement
  double weight;  // residual = weight * (simulated - value)
};

struct Experiment {
  std::string name;
  std::string record;  // the configured experiment it comes from (a segment's whole record)
  int num_inputs = 0;
  std::vector<double> node_time;
  std::vector<int> node_substeps;      // steps from node k to k+1 (size nodes - 1)
  std::vector<double> node_step;       // their length
  std::vector<int> node_first_sample;  // samples of node k: [first[k], first[k+1])
  std::vector<ExperimentSample> samples;
  // Inputs per RK4 step at its start, midpoint and end (the end as a left limit, so a
  // zero-order-hold switch at a sample time acts from the next step on), then one row at the
  // last node: (3 * steps + 1) x num_inputs.
  std::vector<double> input_cache;
  std::vector<double> initial_state;     // initial state where it is not estimated
  std::vector<double> initial_state_guess;  // start values where it is (model's guess)
  // Standard error of each guess, propagated from the start fits of the outputs it comes from
  // (record_start.h); NaN where the data say nothing of the state.
  std::vector<double> initial_state_sigma;
  // Residual weight that makes an initial-state prior count as one sample: the weighted noise
  // level of the experiment's outputs (ChannelMetrics::noise) over the length normalisation.
  double prior_weight = 0.0;
  bool segment = false;  // a piece of a longer record (segments, segment_length, input_range)
  std::vector<int> output_sample_count;  // per model output
  // Per model output: the factor its samples' weights carry for the channel (the configured
  // weight, or 1/sigma under noise weights, channel_weights.h), and count x noise level^2 of
  // its data (the prior weight's share; 0 where unknown).
  std::vector<double> channel_weight;
  std::vector<double> channel_noise_power;
  // Changes whenever sample weights change in place (SetChannelWeights), so that a cost
  // function's cached evaluations (evaluation_cache.h) of the old weights are not reused.
  long weights_revision = 0;
  std::vector<bool> wrapped_outputs;     // per model output: residual wrapped (empty: none)
  // Inputs simulated as latent signals (input_noise.h): the input cache holds their spline,
  // and the corrections (if any) are added per step by the cost function.
  std::vector<LatentInput> latent_inputs;
  std::vector<InputCorrectionGrid> input_corrections;

  int num_input_corrections() const {
    return input_corrections.empty()
               ? 0
               : input_corrections.back().offset + input_corrections.back().count;
  }

  // Noise SD of output `output`'s samples (channel_noise_power over its count); NaN when unknown.
  double NoiseLevel(int output) const {
    const int count = output_sample_count[output];
    const double power = channel_noise_power[output];
    return count > 0 && power > 0.0 ? std::sqrt(power / count)
                                    : std::numeric_limits<double>::quiet_NaN();
  }

  bool Wrapped(int output) const {
    return output < static_cast<int>(wrapped_outputs.size()) && wrapped_outputs[output];
  }

  int num_nodes() const { return static_cast<int>(node_time.size()); }
  int num_samples() const { return static_cast<int>(samples.size()); }
};

// Start values of a model's states from its outputs measured at t0 and their rates (NaN where
// not measured); x arrives holding the default start values (see BuildExperiment).
using StateGuess = std::function<void(const double* y, const double* ydot, double* x)>;

struct ExperimentOptions {
  std::vector<std::string> outputs;  // model outputs compared (empty: every mapped output)
  double max_step = 0.0;             // RK4 step bound; 0: median sample interval
  bool normalize_by_length = true;   // weights * 1/sqrt(samples): experiments weigh alike
  StateGuess state_guess;            // optional (ModelHandle::GuessState)
  double rate_window = 1.0;          // seconds of data behind each output rate at t0
  // Integration steps of the experiment's simulation past which it is refused.
  std::uint64_t max_steps = WorkLimits().integration_steps;
};

// Whether two option sets build the same simulations (a state guess is the model's: set in
// both or in neither counts as the same).
inline bool SameSimulation(const ExperimentOptions& x, const ExperimentOptions& y) {
  return x.outputs == y.outputs && x.max_step == y.max_step &&
         x.normalize_by_length == y.normalize_by_length &&
         static_cast<bool>(x.state_guess) == static_cast<bool>(y.state_guess) &&
         x.rate_window == y.rate_window && x.max_steps == y.max_steps;
}

// Largest change of an unwrapped angle output between two samples: beyond it the direction
// of the turn is ambiguous, and BuildExperiment refuses the record (or its `wrap` is needed).
inline constexpr double kMaxAngleStep = M_PI / 2;

// The bytes an experiment holds for `steps` integration steps of `inputs` model inputs, counted
// before BuildExperiment allocates them (and by the run's memory budget, work_size.h): the
// input cache and the steps' times, 3 rows per step (start, midpoint, end) and the last node.
inline double IntegrationStepBytes(double steps, double inputs) {
  return (3.0 * steps + 1.0) * (inputs + 1.0) * sizeof(double);
}

// Builds the simulation grid, input cache and samples. Initial-state values come from
// spec.initial_state, else from the output of the same name measured at t0, else 0; the start
// values of estimated initial states also take options.state_guess (the model's guess of,
// e.g., velocities from measured position rates) over the latter two.
// Errors name the experiment and the missing column or key.
bool BuildExperiment(const ExperimentSpec& spec, const Trajectory& trajectory,
                     const ModelInfo& info, const ExperimentOptions& options,
                     Experiment* experiment, std::string* error);
// The same, taking the record's channels from `channels` (shared by the experiments cut from
// one record; channels->trajectory() is the record).
bool BuildExperiment(const ExperimentSpec& spec, RecordChannels* channels,
                     const ModelInfo& info, const ExperimentOptions& options,
                     Experiment* experiment, std::string* error);

// Reads the CSV named by spec.file and prepares it as spec.data says (experiment_data.h;
// experiment_data.cc), converting degree columns to radians. Errors name the experiment, the
// file and line or the config key.
bool LoadExperimentData(const ExperimentSpec& spec, Trajectory* trajectory, std::string* error);

// What LoadExperimentData reads of `spec` but its name, as text: experiments with the same
// key (windows or segments of one log) read the same Trajectory (trajectory_cache.h).
std::string ReadKey(const ExperimentSpec& spec);

}  // namespace vesselid
