// Every key docs/config_reference.md documents has an effect, or is refused where it cannot have
// one: each case runs a small config with and without the key and requires the results to
// differ (estimates, fits, notes, validation, final values), or requires the reader to refuse
// it naming the key. Data: three closed-loop first-order Nomoto runs (T 2 s, K -0.17) with
// heading noise, one cut into segments by a column. (`wrap` has no effect on headings that
// never pass +-pi; angle_unwrap_test.cc covers it on a turning record.)
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <random>
#include <string>
#include <utility>

#include "engine/config/config.h"
#include "engine/diagnose/run_findings.h"
#include "engine/output/finding_report.h"
#include "engine/run/pipeline.h"
#include "engine/solve/global_start.h"
#include "gtest/gtest.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"
#include "problems/registry.h"

namespace vesselid {
namespace config_keys_test {

namespace fs = std::filesystem;

// One side of a case: what goes into the config template.
struct Variant {
  std::string a_keys;                  // added to experiment a
  std::string s_keys;                  // added to the segmented experiment s
  std::string experiments = "[a, b]";  // the stage's experiments
  std::string free = "[psi]";          // the stage's free initial states
  std::string stage;                   // stage keys
  std::string parameters;              // parameter lines (replacing a listed one by name)
  std::string top;                     // top-level keys
  std::string extra;                   // experiments added after s
  std::string model;                   // added to the model map

  Variant A(std::string v) const {
    Variant c = *this;
    c.a_keys = std::move(v);
    return c;
  }
  Variant S(std::string v) const {
    Variant c = *this;
    c.s_keys = std::move(v);
    return c;
  }
  Variant E(std::string v) const {
    Variant c = *this;
    c.experiments = std::move(v);
    return c;
  }
  Variant F(std::string v) const {
    Variant c = *this;
    c.free = std::move(v);
    return c;
  }
  Variant K(std::string v) const {
    Variant c = *this;
    c.stage = std::move(v);
    return c;
  }
  Variant P(std::string v) const {
    Variant c = *this;
    c.parameters = std::move(v);
    return c;
  }
  Variant T(std::string v) const {
    Variant c = *this;
    c.top = std::move(v);
    return c;
  }
  Variant X(std::string v) const {
    Variant c = *this;
    c.extra = std::move(v);
    return c;
  }
  Variant M(std::string v) const {
    Variant c = *this;
    c.model = std::move(v);
    return c;
  }
};

struct KeyCase {
  std::string name;
  Variant base, with;
  std::string refusal = {};  // non-empty: `with` must be refused (by the reader or before the first
                        // stage) with this in the message
  // Non-empty: the key changes what the run says (findings, notes), not its numbers; why.
  std::string words_only = {};
};

void PrintTo(const KeyCase& c, std::ostream* os) { *os << c.name; }

constexpr char kTemplate[] = R"(model: {family: nomoto, type: first_orderMODEL_KEYS}
experiments:
  - {name: a, file: run0.csv, inputs: {delta: delta}, outputs: {psi: psi, r: r}A_KEYS}
  - {name: b, file: run1.csv, inputs: {delta: delta}, outputs: {psi: psi, r: r}, window: [0, 60]}
  - {name: c, file: run2.csv, inputs: {delta: delta}, outputs: {psi: psi, r: r}}
  - {name: s, file: segmented.csv, inputs: {delta: delta}, outputs: {psi: psi, r: r},
     segments: {column: segment}S_KEYS}
MORE_ENTRIES
stages:
  - name: fit
    experiments: EXPERIMENTS
    free_initial_states: FREE
STAGE_KEYS
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 20}
      K: {start: -0.1, lower: -1, upper: -0.001}
      delta_0: {start: 0.0, role: fixed}
TOP_KEYS)";

const Variant V;
const Variant kNoisyRudder =
    V.X("  - {name: n, file: noisy.csv, inputs: {delta: delta}, outputs: {psi: psi, r: r}}")
        .E("[n, b]");
const Variant kLeastSquares = V.K("    type: least_squares\n    least_squares: {grid: psi}");
const Variant kPerRun =
    V.P("      delta_0: {start: 0.0, lower: -0.1, upper: 0.1, role: per_experiment}");

// A second segmented experiment whose `segments` map a case completes.
const std::string kS2 =
    "  - {name: s2, file: segmented.csv, inputs: {delta: delta}, outputs: {psi: psi, r: r},\n"
    "     segments: {column: segment";

const KeyCase kCases[] = {
    {"interpolation", V, V.A(", interpolation: {delta: zero_order_hold}")},
    // The experiments' output weights and length normalisation act under `weights: given`
    // (under the default noise weights of this two-output stage they serve the first solve).
    {"weights", V.K("    weights: given"), V.K("    weights: given").A(", weights: {psi: 3.0}")},
    {"stage_weights", V, V.K("    weights: given")},
    {"initial_state", V, V.A(", initial_state: {r: 0.05}")},
    {"window", V, V.A(", window: [10, 100]")},
    {"degrees", V, V.A(", degrees: [delta]")},
    {"segment_length", V, V.A(", segment_length: 30")},
    {"input_range", V, V.A(", input_range: {delta: [-0.3, 0.3]}")},
    {"input_noise", V, V.A(", input_noise: {delta: auto}")},
    {"input_noise_sigma_knots_correction", V.A(", input_noise: {delta: auto}"),
     V.A(", input_noise: {delta: {sigma: 0.01, knots: 0.5, correction: off}}")},
    {"segments", V, V.E("[a, s]")},
    {"stage_experiments", V, V.E("[a]")},
    {"outputs", V, V.K("    outputs: [psi]")},
    {"role_per_experiment", V, V.P("      delta_0: {start: 0.0, role: per_experiment}")},
    {"role_fixed", V, V.P("      K: {start: -0.15, role: fixed}")},
    {"free_initial_states", V, V.F("[psi, r]")},
    {"loss", V, V.K("    loss: {type: cauchy, scale: 0.001}")},
    {"integration", V, V.K("    integration: {max_step: 0.013}")},
    {"normalize_by_length", V.K("    weights: given"),
     V.K("    weights: given\n    normalize_by_length: false")},
    {"normalize_by_length_under_noise_weights", V, V.K("    normalize_by_length: true")},
    {"global", V, V.K("    global: {algorithm: GN_CRS2_LM, max_evaluations: 40, seed: 1}")},
    {"global_multistart", V, V.K("    global: {points: 8, short_iterations: 2}")},
    // (under `weights: given`: the noise-weight iterations re-solve without the global start)
    {"global_points", V.K("    weights: given\n    global: {points: 8, short_iterations: 2}"),
     V.K("    weights: given\n    global: {points: 16, short_iterations: 2}")},
    {"global_short_iterations",
     V.K("    weights: given\n    global: {points: 8, short_iterations: 2}"),
     V.K("    weights: given\n    global: {points: 8, short_iterations: 3}")},
    {"global_threads", V, V.K("    global: {points: 8, threads: -1}"), "threads must be >= 0"},
    {"global_nlopt_key_in_multistart", V, V.K("    global: {max_evaluations: 40}"),
     "max_evaluations applies to NLopt algorithms"},
    {"global_multistart_key_in_nlopt", V, V.K("    global: {algorithm: GN_CRS2_LM, points: 8}"),
     "points applies to the multistart"},
    {"local", V, V.K("    local: {max_iterations: 2}")},
    {"continuation", V, V.K("    continuation: [20]")},
    {"continuation_on_segments", V.E("[s]"), V.E("[s]").K("    continuation: [20]")},
    {"uncertainty", V, V.K("    uncertainty: false")},
    {"uncertainty_method", V, V.K("    uncertainty: {method: hessian}")},
    {"uncertainty_bandwidth", V.K("    uncertainty: {method: sandwich_hac}"),
     V.K("    uncertainty: {method: sandwich_hac, bandwidth: 3}")},
    {"uncertainty_aggregation", V.K("    uncertainty: {method: sandwich_hac}"),
     V.K("    uncertainty: {method: sandwich_hac, aggregation: 1}")},
    {"uncertainty_kernel", V.K("    uncertainty: {method: sandwich_hac}"),
     V.K("    uncertainty: {method: sandwich_hac, kernel: quadratic_spectral}")},
    {"uncertainty_prewhiten", V.K("    uncertainty: {method: sandwich_hac}"),
     V.K("    uncertainty: {method: sandwich_hac, prewhiten: true}")},
    {"uncertainty_block_bootstrap", V, V.K("    uncertainty: {method: block_bootstrap, runs: 10}")},
    {"uncertainty_runs", V.K("    uncertainty: {method: block_bootstrap, runs: 10}"),
     V.K("    uncertainty: {method: block_bootstrap, runs: 12}")},
    {"uncertainty_block_length", V.K("    uncertainty: {method: block_bootstrap, runs: 10}"),
     V.K("    uncertainty: {method: block_bootstrap, runs: 10, block_length: 2}")},
    {"uncertainty_seed", V.K("    uncertainty: {method: block_bootstrap, runs: 10}"),
     V.K("    uncertainty: {method: block_bootstrap, runs: 10, seed: 2}")},
    // Six experiments: a, b, c and the three segments of s.
    // run0 logged with 0.2 deg of white noise on its rudder: refits with it added again
    // widen the standard errors.
    {"uncertainty_input_noise", kNoisyRudder,
     kNoisyRudder.K("    uncertainty: {input_noise: off}")},
    {"uncertainty_input_noise_runs", kNoisyRudder,
     kNoisyRudder.K("    uncertainty: {input_noise_runs: 5}")},
    {"uncertainty_experiment_bootstrap", V.E("[a, b, c, s]"),
     V.E("[a, b, c, s]").K("    uncertainty: {method: experiment_bootstrap, runs: 10}")},
    // Six segments of 20 s cut from a's 120 s.
    {"uncertainty_experiment_bootstrap_segment_length", V.E("[a]").A(", segment_length: 20"),
     V.E("[a]")
         .A(", segment_length: 20")
         .K("    uncertainty: {method: experiment_bootstrap, runs: 10}")},
    // Three segments: known only from the data, a warning and auto's figures.
    {"uncertainty_experiment_bootstrap_three_segments", V.E("[s]"),
     V.E("[s]").K("    uncertainty: {method: experiment_bootstrap, runs: 10}"), "",
     "three segments are too few to resample: the stage keeps auto's standard errors and says "
     "why"},
    {"uncertainty_experiment_bootstrap_few", V,
     V.K("    uncertainty: {method: experiment_bootstrap}"),
     "config.yaml:12: stages[0].uncertainty.method: experiment_bootstrap in stage 'fit' needs at "
     "least 5 experiments or segments to resample, it has 2 (cut the records into segments with "
     "`segment_length`"},
    {"uncertainty_few_runs", V, V.K("    uncertainty: {method: block_bootstrap, runs: 5}"),
     "config.yaml:12: stages[0].uncertainty.runs: must be >= 10"},
    {"uncertainty_input_noise_bad", V, V.K("    uncertainty: {input_noise: maybe}"),
     "config.yaml:12: stages[0].uncertainty.input_noise: must be auto or off (true or false)"},
    {"uncertainty_input_noise_few_runs", V, V.K("    uncertainty: {input_noise_runs: 2}"),
     "config.yaml:12: stages[0].uncertainty.input_noise_runs: must be >= 5"},
    {"uncertainty_bad_block_length", V,
     V.K("    uncertainty: {method: block_bootstrap, block_length: 0}"),
     "config.yaml:12: stages[0].uncertainty.block_length: must be auto or > 0 (seconds)"},
    {"uncertainty_unknown_method", V, V.K("    uncertainty: {method: jackknife}"),
     "config.yaml:12: stages[0].uncertainty.method: unknown method 'jackknife' (auto, hessian, "
     "sandwich_hac, block_bootstrap, experiment_bootstrap)"},
    {"uncertainty_bad_bandwidth", V, V.K("    uncertainty: {bandwidth: 0.5}"),
     "config.yaml:12: stages[0].uncertainty.bandwidth: must be auto or >= 1 (blocks)"},
    {"validation", V, V.K("    validation: [c]")},
    {"initial_state_prior", V.E("[s]").K("    initial_state_prior: off"), V.E("[s]")},
    {"outliers", V.E("[a, b, c, s]"),
     V.E("[a, b, c, s]").K("    outliers: {action: drop, threshold: 0.01}")},
    {"type_least_squares", V, kLeastSquares},
    {"screen", V, V.A(", screen: {max_rate: {r: 0.001}}")},
    {"resample", V, V.A(", resample: {rate: 4, max_gap: 2}")},
    {"final_validation", V, V.T("final_validation: {experiments: [c]}")},
    {"validation_per_experiment", kPerRun.K("    validation: [c]"),
     kPerRun.K("    validation: [c]\n    validation_per_experiment: hold")},
    {"unit", V, V.A(", time: {unit: min}")},
    {"held_out", kPerRun.K("    validation: [c]"),
     kPerRun.K("    validation: [c]\n    held_out: {start: refitted}")},
    {"burn_in", kPerRun.K("    validation: [c]"),
     kPerRun.K("    validation: [c]\n    held_out: {burn_in: 3}")},
    {"implausible_sds", kPerRun.F("[psi, r]").K("    validation: [c]\n    held_out: {start: refitted}"),
     kPerRun.F("[psi, r]").K("    validation: [c]\n    held_out: {start: refitted, implausible_sds: 1.0e-6}"),
     "", "a refitted start beyond so few noise SDs is an implausible_start finding"},
    {"final_validation_per_experiment", kPerRun.T("final_validation: {experiments: [c]}"),
     kPerRun.T("final_validation: {experiments: [c], per_experiment: hold}")},
    {"velocity_validation_of_a_stage", V.K("    validation: [c]"),
     V.K("    validation: [c]\n    velocity_validation: false")},
    {"velocity_validation", V.T("final_validation: {experiments: [c]}\n"),
     V.T("final_validation: {experiments: [c]}\nvelocity_validation: false\n")},
    {"fusion",
     V.P("      T: {start: 3.0, lower: 0.1, upper: 20, role: shared}")
         .T("  - name: again\n    experiments: [c]\n    parameters:\n"
            "      T: {role: shared}\n"),
     V.P("      T: {start: 3.0, lower: 0.1, upper: 20, role: shared}")
         .T("  - name: again\n    experiments: [c]\n    parameters:\n"
            "      T: {role: shared}\nfusion: mean\n")},
    // Templates (docs/configs.md "Templates"): experiment_defaults, merge keys, files, sets.
    {"experiment_defaults", V, V.T("experiment_defaults: {weights: {psi: 3.0}}\n")},
    {"merge_key", V, V.K("    <<: {loss: {type: cauchy, scale: 0.001}}")},
    {"merge_key_own_key_wins", V.K("    uncertainty: false"),
     V.K("    <<: {uncertainty: false}\n    uncertainty: true")},
    {"files", V,
     V.X("  - {files: \"run[12].csv\", name: \"g{stem}\", inputs: {delta: delta},\n"
         "     outputs: {psi: psi, r: r}}")
         .E("[a, grun2]")},
    {"sets_as_validation", V, V.T("sets: {held_out: [c]}\n").K("    validation: held_out")},
    {"sets_in_a_list", V, V.T("sets: {pair: [a, b]}\n").E("[pair, c]")},
    // Refused templates, with the line.
    {"unknown_set", V, V.T("sets: {held_out: [c]}\n").K("    validation: [held_ot]"),
     "config.yaml:12: stages[0].validation[0]: no experiment or set named 'held_ot'"},
    {"set_without_sets", V, V.K("    validation: held_out"),
     "config.yaml:12: stages[0].validation: expected a list of experiment names"},
    {"experiment_listed_twice", V, V.T("sets: {pair: [a, b]}\n").E("[pair, a]"),
     "config.yaml:10: stages[0].experiments[1]: experiment 'a' is listed twice (in set 'pair' "
     "and by name)"},
    {"set_named_like_an_experiment", V, V.T("sets: {c: [a]}\n"),
     "sets.c: a set cannot have the name of an experiment"},
    {"files_without_match", V,
     V.X("  - {files: \"zz_*.csv\", inputs: {delta: delta}, outputs: {psi: psi}}"),
     "config.yaml:8: experiments[4].files: no file matches 'zz_*.csv' in "},
    {"files_beside_file", V,
     V.X("  - {files: \"run*.csv\", file: run0.csv, inputs: {delta: delta}, outputs: {psi: psi}}"),
     "experiments[4].files: file and files cannot be combined"},
    {"files_name_without_stem", V,
     V.X("  - {files: \"run*.csv\", name: run, inputs: {delta: delta}, outputs: {psi: psi}}"),
     "experiments[4].name: with files, the name holds {stem}"},
    {"defaults_with_a_name", V, V.T("experiment_defaults: {name: x}\n"),
     "experiment_defaults.name: every experiment gives its own"},
    {"merge_of_a_non_map", V, V.K("    <<: [5]"),
     "config.yaml:12: stages[0].<<[0]: a merge key's list holds maps"},
    {"merge_of_a_scalar", V, V.K("    <<: fast"),
     "config.yaml:12: stages[0].<<: a merge key takes a map or a list of maps"},
    {"duplicate_key_next_to_a_merge_key", V,
     V.K("    <<: {uncertainty: false}\n    loss: {type: cauchy}\n    loss: {type: huber}"),
     "config.yaml:14: stages[0].loss: given twice (lines 13 and 14)"},
    // Refused combinations.
    {"initial_state_with_segments", V, V.E("[a, s]").S(", initial_state: {r: 0}"),
     "initial_state: cannot be combined with 'segments'"},
    {"continuation_in_least_squares", V,
     kLeastSquares.K(kLeastSquares.stage + "\n    continuation: [20]"),
     "stages[0].continuation: not used by a least-squares stage"},
    {"outliers_in_least_squares", V,
     kLeastSquares.K(kLeastSquares.stage + "\n    outliers: {action: drop}"),
     "stages[0].outliers: not used by a least-squares stage"},
    {"wrap_of_a_rate", V, V.A(", wrap: [r]"), "output 'r' is not an angle"},
    {"unknown_stage_weights", V, V.K("    weights: heavy"),
     "config.yaml:12: stages[0].weights: unknown choice 'heavy' (noise, given)"},
    {"weights_in_least_squares", V, kLeastSquares.K(kLeastSquares.stage + "\n    weights: noise"),
     "stages[0].weights: not used by a least-squares stage"},
    {"input_noise_of_an_unknown_input", V, V.A(", input_noise: {rudder: auto}"),
     "config.yaml:3: experiments[0].input_noise.rudder: unknown key"},
    {"input_noise_sigma_not_positive", V, V.A(", input_noise: {delta: {sigma: 0}}"),
     "config.yaml:3: experiments[0].input_noise.delta.sigma: must be > 0 (or auto)"},
    {"input_noise_knots_too_short", V, V.A(", input_noise: {delta: {knots: 0.06}}"),
     "config.yaml:3: experiments[0].input_noise.delta: input noise: knots 0.06 s is shorter "
     "than two sample intervals (0.1 s)"},
    {"input_noise_correction_too_short", V, V.A(", input_noise: {delta: {correction: 0.2}}"),
     "config.yaml:3: experiments[0].input_noise.delta: correction spacing 0.2 s is shorter "
     "than 10 input samples"},
    {"velocity_validation_not_a_yes_or_no", V, V.K("    velocity_validation: sometimes"),
     "config.yaml:12: stages[0].velocity_validation: expected true or false"},
    {"model_length_without_n1_form", V, V.M(", length: 320"),
     "model.length: only the n1-form models (first_order_n1, norrbin_n1) take a ship length"},
    {"unknown_final_choice", V, V.T("final: newest\n"), "final: unknown choice 'newest'"},
    {"unknown_per_experiment_choice", V,
     V.T("final_validation: {experiments: [c], per_experiment: always}\n"),
     "final_validation.per_experiment: unknown choice 'always' (fit, hold)"},
    {"separator_the_file_does_not_use", V, V.A(", separator: \";\""),
     "the header is separated by ',', not ';'"},
    {"limits", V, V.T("limits: {integration_steps: 100}\n"), "(limits.integration_steps)"},
    // The data here have no mangled cell: log_as_logged_test.cc shows the key's effect.
    {"bad_cells", V, V.A(", bad_cells: 1.5"),
     "config.yaml:3: experiments[0].bad_cells: must be a share in [0, 1)"},
    // Keys for data this template does not have (epoch times, GNSS fixes, positions, row
    // jitter): real_log_test.cc and time_base_test.cc show their effect.
    {"time", V, V.A(", time: {column: r}"), "is not after the previous time"},
    {"position", V, V.A(", position: {lat: lat, lon: lon}"),
     "no column 'lat' (experiments[0].position.lat)"},
    {"screen_max_speed_without_positions", V, V.A(", screen: {max_speed: 5}"),
     "screen.max_speed needs positions"},
    {"screen_zero_fix_without_positions", V, V.A(", screen: {zero_fix: true}"),
     "screen.zero_fix needs positions"},
    // A stale sensor: experiment a's heading column holds no repeats, so a stale screen of
    // 2 samples has no run to remove but is read (an invalid count is refused).
    {"screen_stale", V, V.A(", screen: {stale: 1}"), "stale: must be >= 2"},
    // The local solver's settings.
    {"local_function_tolerance", V, V.K("    local: {function_tolerance: 0.5}")},
    {"local_gradient_tolerance", V, V.K("    local: {gradient_tolerance: 1e3}")},
    {"local_parameter_tolerance", V, V.K("    local: {parameter_tolerance: 1}")},
    {"local_trust_region", V, V.K("    local: {trust_region: dogleg}")},
    {"local_trust_region_reflective", V.K("    local: {trust_region: levenberg_marquardt}"),
     V.K("    local: {trust_region: reflective}")},
    // The initial radius of Ceres' trust regions (the reflective one starts from |x0|).
    {"local_initial_radius", V.K("    local: {trust_region: levenberg_marquardt, max_iterations: 5}"),
     V.K("    local: {trust_region: levenberg_marquardt, max_iterations: 5, initial_radius: 1e-6}")},
    {"local_initial_radius_refused", V, V.K("    local: {initial_radius: 0}"),
     "initial_radius must be a number > 0"},
    {"global_population", V.K("    global: {algorithm: GN_CRS2_LM, max_evaluations: 40, seed: 1}"),
     V.K("    global: {algorithm: GN_CRS2_LM, max_evaluations: 40, seed: 1, population: 50}")},
    {"limits_evaluations", V.K("    global: {algorithm: GN_CRS2_LM, max_evaluations: 40}"),
     V.K("    global: {algorithm: GN_CRS2_LM, max_evaluations: 40}")
         .T("limits: {evaluations: 10}\n"),
     "(limits.evaluations)"},
    {"limits_data_values", V, V.T("limits: {data_values: 100}\n"), "values"},
    // Experiment a's rudder leaves [-0.25, 0.25] rad now and then: stretches of 1 s or more.
    {"input_range_skip", V.A(", input_range: {delta: [-0.25, 0.25], min_duration: 1}"),
     V.A(", input_range: {delta: [-0.25, 0.25], min_duration: 1, skip: 0.5}")},
    {"input_range_min_duration", V.A(", input_range: {delta: [-0.25, 0.25]}"),
     V.A(", input_range: {delta: [-0.25, 0.25], min_duration: 30}")},
    // The linear solver changes the path, not the optimum (results equal to 12 digits with
    // cgnr): it is shown read by refusing an unknown one.
    {"local_linear_solver", V, V.K("    local: {linear_solver: cholmod}"),
     "unknown linear solver 'cholmod'"},
    // The multistart's settings (under `weights: given`, as global_points). min_separation 0
    // keeps every short solve's end point apart, where 0.05 joins them all to the optimum.
    {"global_candidates", V.K("    weights: given\n    global: {points: 8, short_iterations: 2}"),
     V.K("    weights: given\n    global: {points: 8, short_iterations: 2, candidates: "
         "1}")},
    {"global_min_separation",
     V.K("    weights: given\n    global: {points: 8, short_iterations: 2}"),
     V.K("    weights: given\n    global: {points: 8, short_iterations: 2, "
         "min_separation: 0}")},
    // The multistart searches on pieces of the records by default (search_horizons.h).
    {"global_horizons", V.K("    weights: given\n    global: {points: 8, short_iterations: 2}"),
     V.K("    weights: given\n    global: {points: 8, short_iterations: 2, horizons: "
         "none}")},
    {"global_horizons_given",
     V.K("    weights: given\n    global: {points: 8, short_iterations: 2}"),
     V.K("    weights: given\n    global: {points: 8, short_iterations: 2, horizons: "
         "[10]}")},
    {"global_horizons_with_continuation", V,
     V.K("    continuation: [20]\n    global: {horizons: [10]}"),
     "the stage's continuation sets the segments its global start searches on"},
    {"global_max_time", V.K("    weights: given\n    global: {points: 8, short_iterations: 2}"),
     V.K("    weights: given\n    global: {points: 8, short_iterations: 2, max_time: "
         "1e-9}")},
    // The least-squares stage's regression settings.
    {"least_squares_penalty", kLeastSquares,
     V.K("    type: least_squares\n    least_squares: {grid: psi, penalty: ridge, lambda: 0.5}")},
    {"least_squares_folds",
     V.K("    type: least_squares\n    least_squares: {grid: psi, penalty: ridge, lambda: -1}"),
     V.K("    type: least_squares\n    least_squares: {grid: psi, penalty: ridge, lambda: -1,\n"
         "                    folds: 2}")},
    {"least_squares_robust", kLeastSquares,
     V.K("    type: least_squares\n    least_squares: {grid: psi, robust: true}")},
    {"least_squares_smoothing", kLeastSquares,
     V.K("    type: least_squares\n    least_squares: {grid: psi, smoothing: {half_width: 3, "
         "order: 2}}")},
    // Segments of a record: the share and pick of validation segments.
    {"segments_take", V.E("[s2]").X(kS2 + "}}"),
     V.E("[s2]").X(kS2 + ", take: training, validation_share: 0.34, seed: 1}}")},
    {"initial_state_prior_bounds", V.E("[s]"),
     V.E("[s]").K("    initial_state_prior: {apply: segments, bounds: 0.05}")},
    {"step_regression_of_a_model_without_its_form", V,
     V.K("    type: step_regression\n    step_regression: {bootstrap: 0}"),
     "has no damping-inertia form for a step-regression stage"},
    {"bootstrap_runs", kLeastSquares,
     V.K("    type: least_squares\n    least_squares: {grid: psi, bootstrap: 20}")},
    {"bootstrap_blocks",
     V.K("    type: least_squares\n    least_squares: {grid: psi, bootstrap: 20}"),
     V.K("    type: least_squares\n    least_squares: {grid: psi, bootstrap: {runs: 20, blocks: "
         "8}}")},
    {"bootstrap_seed",
     V.K("    type: least_squares\n    least_squares: {grid: psi, bootstrap: 20}"),
     V.K("    type: least_squares\n    least_squares: {grid: psi, bootstrap: {runs: 20, seed: "
         "2}}")},
    {"bootstrap_lambda",
     V.K("    type: least_squares\n    least_squares: {grid: psi, penalty: lasso, bootstrap: 20}"),
     V.K("    type: least_squares\n    least_squares: {grid: psi, penalty: lasso,\n"
         "                    bootstrap: {runs: 20, lambda: selected}}")},
    {"bootstrap_one_run", V,
     V.K("    type: least_squares\n    least_squares: {grid: psi, bootstrap: 1}"),
     "stages[0].least_squares.bootstrap: bootstrap: runs must be 0 (none) or >= 2, not 1"},
    {"max_gap", V, V.K("    type: least_squares\n    least_squares: {grid: psi, max_gap: 0.5}"),
     "stages[0].least_squares.max_gap: must be >= 1"},
    {"limits_of_a_study", V,
     V.T("limits: {study_cases: 5}\nstudy: {monte_carlo: {runs: 6, noise: {psi: 0.01}}}\n"),
     "study.monte_carlo.runs: 6 is more than the limit of 5 (limits.study_cases)"},
};

// The config of a case's side: the template with the variant's keys put in.
std::string ConfigKeysText(const Variant& v) {
  std::string text = kTemplate;
  auto put = [&](const std::string& mark, const std::string& value) {
    text.replace(text.find(mark), mark.size(), value);
  };
  put("A_KEYS", v.a_keys);
  put("S_KEYS", v.s_keys);
  put("EXPERIMENTS", v.experiments);
  put("FREE", v.free);
  put("STAGE_KEYS\n", v.stage.empty() ? "" : v.stage + "\n");
  put("TOP_KEYS", v.top);
  put("MORE_ENTRIES\n", v.extra.empty() ? "" : v.extra + "\n");
  put("MODEL_KEYS", v.model);
  if (!v.parameters.empty()) {  // replaces the listed line of the same parameter
    const std::string head = v.parameters.substr(0, v.parameters.find(':') + 1);
    const size_t at = text.find(head);
    text.replace(at, text.find('\n', at) - at, v.parameters);
  }
  return text;
}

class ConfigKeys : public ::testing::TestWithParam<KeyCase> {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_config_keys_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    auto model = nomoto::MakeFirstOrderHandle();
    for (int i = 0; i < 4; ++i) {
      nomoto::ClosedLoopOptions loop;
      loop.duration = 120.0;
      loop.sample_time = 0.05;
      loop.controller_gain = 0.7;
      loop.excitation.amplitude = 0.3;
      loop.excitation.periods = {15.0 + 5 * i};
      loop.heading_noise = 0.003;
      loop.seed = 30 + i;
      Trajectory data;
      std::string error;
      ASSERT_TRUE(nomoto::SimulateClosedLoop(*model, {2.0, -0.17, 0.0}, loop, &data, &error));
      std::string name = "run" + std::to_string(i) + ".csv";
      if (i == 3) {  // three segments told apart by a column
        name = "segmented.csv";
        data.names.push_back("segment");
        data.columns.emplace_back();
        for (double t : data.t) data.columns.back().push_back(t < 40 ? 1 : t < 80 ? 2 : 3);
      }
      ASSERT_TRUE(WriteTrajectoryCsv((*dir_ / name).string(), data, &error));
      if (i == 0) {  // the same run, its rudder logged with white noise
        std::mt19937 rng(7);
        std::normal_distribution<double> noise(0.0, 0.2 * M_PI / 180.0);
        for (double& u : data.columns[data.Find("delta")]) u += noise(rng);
        ASSERT_TRUE(WriteTrajectoryCsv((*dir_ / "noisy.csv").string(), data, &error));
      }
    }
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }

  static std::string Text(const Variant& v) { return ConfigKeysText(v); }

  // Every number a key could change, and the counts of what was fitted and validated.
  // What a global start computed, without its wall time (which differs from run to run).
  static std::string GlobalSignature(const GlobalStartSummary& g) {
    std::string s = g.algorithm + " " + g.result + ": " + std::to_string(g.evaluations) +
                    " points, " + std::to_string(g.failed_evaluations) + " diverged, " +
                    std::to_string(g.abandoned) + " abandoned, " + std::to_string(g.short_solves) +
                    " short solves, " + std::to_string(g.clusters) + " clusters, " +
                    std::to_string(g.known_joined) + " known, " +
                    std::to_string(g.short_iterations_total) + " iterations; horizon " +
                    std::to_string(g.horizon_seconds) + ";";
    char line[64];
    for (size_t k = 0; k < g.candidates.size(); ++k) {
      std::snprintf(line, sizeof(line), "candidate %.9g:", g.candidate_costs[k]);
      s += line;
      for (double v : g.candidates[k]) {
        std::snprintf(line, sizeof(line), " %.9g", v);
        s += line;
      }
      s += ";";
    }
    return s;
  }

  static std::string Signature(const RunResult& r) {
    std::string s;
    char line[160];
    for (const StageResult& stage : r.stages) {
      for (const Estimate& e : stage.estimates) {
        std::snprintf(line, sizeof(line), "%s=%.12g/%.6g;", e.name.c_str(), e.value, e.std_error);
        s += line;
      }
      s += std::to_string(stage.summary.fits.size()) + " fits, " +
           std::to_string(stage.summary.refinements.size()) + " refinements, " +
           std::to_string(stage.validation.size()) + " validation, " +
           std::to_string(stage.velocity_validation.size()) + " velocity metrics;";
      if (stage.summary.global.run) s += GlobalSignature(stage.summary.global);
      for (size_t k = 0; k < stage.bootstrap.names.size(); ++k) {
        std::snprintf(line, sizeof(line), "%s SE %.6g;", stage.bootstrap.names[k].c_str(),
                      stage.bootstrap.std_error[k]);
        s += line;
      }
      for (const ExperimentFit& fit : stage.validation) {
        std::snprintf(line, sizeof(line), "%s:%.12g;", fit.experiment.c_str(), fit.rms_cost);
        s += line;
      }
    }
    for (const ExperimentFit& fit : r.final_validation) {
      std::snprintf(line, sizeof(line), "final %s:%.12g;", fit.experiment.c_str(), fit.rms_cost);
      s += line;
    }
    for (const FinalParameter& f : r.parameters) {
      std::snprintf(line, sizeof(line), "%s=%.12g;", f.name.c_str(), f.value);
      s += line;
    }
    return s + std::to_string(r.final_validation.size()) + " final validation, " +
           std::to_string(r.final_velocity_validation.size()) + " velocity metrics";
  }

  // What the run says of itself: its findings and the stages' notes.
  static std::string Words(const RunResult& r) {
    std::string s;
    for (const StageResult& stage : r.stages) {
      for (const std::string& note : stage.summary.notes) s += note + ";";
    }
    for (const Finding& f : AllFindings(r)) s += DescribeFinding(f) + ";";
    return s;
  }

  static bool Load(const std::string& text, RunConfig* config, std::string* error) {
    std::ofstream(*dir_ / "config.yaml") << text;
    static const ModelRegistry registry = DefaultRegistry();
    return LoadRunConfig((*dir_ / "config.yaml").string(), "", registry, config, error);
  }

  // The run's numbers (Signature) and its words (Words).
  static std::pair<std::string, std::string> Run(const std::string& text) {
    RunConfig config;
    RunResult result;
    std::string error;
    EXPECT_TRUE(Load(text, &config, &error)) << error << "\n" << text;
    EXPECT_TRUE(Identify(config, &result, &error)) << error << "\n" << text;
    return {Signature(result), Words(result)};
  }

  static fs::path* dir_;
};

fs::path* ConfigKeys::dir_ = nullptr;

TEST_P(ConfigKeys, HasAnEffectOrIsRefused) {
  const KeyCase& c = GetParam();
  if (!c.refusal.empty()) {
    // By the reader, or by the run before its first stage (what needs the data).
    RunConfig config;
    RunResult result;
    std::string error;
    EXPECT_FALSE(Load(Text(c.with), &config, &error) && Identify(config, &result, &error))
        << Text(c.with);
    EXPECT_TRUE(result.stages.empty());
    EXPECT_NE(error.find(c.refusal), std::string::npos) << error;
    return;
  }
  const auto base = Run(Text(c.base)), with = Run(Text(c.with));
  if (c.words_only.empty()) {
    // A key changes what the run computes, not only what it says.
    EXPECT_NE(base.first, with.first) << Text(c.with) << "\nwords:\n"
                                      << base.second << "\n" << with.second;
  } else {
    EXPECT_EQ(base.first, with.first) << c.words_only;
    EXPECT_NE(base.second, with.second) << c.words_only;
  }
}

std::string CaseName(const ::testing::TestParamInfo<KeyCase>& info) { return info.param.name; }

// The keys the first block of docs/config_reference.md (a staged run's) names: every `word:`
// in it, comments included ("min_separation: 0.05").
std::set<std::string> DocumentedKeys() {
  std::ifstream in(std::string(VESSELID_SOURCE_DIR) + "/docs/config_reference.md");
  std::string line;
  while (std::getline(in, line) && line != "## A staged run") {
  }
  std::getline(in, line);  // the blank line before the block
  std::set<std::string> keys;
  const std::regex key(R"((^|[^A-Za-z0-9_.-])([a-z_][a-z0-9_]*):)");
  while (std::getline(in, line) && line.rfind("    ", 0) == 0) {
    for (std::sregex_iterator it(line.begin(), line.end(), key), end; it != end; ++it) {
      keys.insert((*it)[2]);
    }
  }
  return keys;
}

// How many times `key:` occurs in `text`.
int Occurrences(const std::string& text, const std::string& key) {
  const std::regex pattern("(^|[^A-Za-z0-9_.-])" + key + ":");
  return static_cast<int>(std::distance(
      std::sregex_iterator(text.begin(), text.end(), pattern), std::sregex_iterator()));
}

// Words of the block followed by a colon that are not keys: the example's channel, parameter
// and set names, and prose in its comments ("default: all", "| hold: ...").
const std::set<std::string> kNotKeys = {
    // names
    "delta", "delta_0", "psi", "xi1", "u", "tau_m", "held_out", "training", "xi2",
    // prose
    "default", "false", "true", "given", "hold", "last", "selected"};

// Keys every case's config holds (the template's skeleton): each run exercises them.
const std::set<std::string> kSkeleton = {
    "model",  "family", "type",       "experiments", "name",  "file",
    "inputs", "outputs", "stages",    "parameters",  "start", "lower",
    "upper",  "role",    "free_initial_states", "column", "segments"};

// Keys whose effect needs data or a model this template does not have, and the test (or the
// shipped config a test runs) that shows it; the file must name the key.
const std::map<std::string, std::string> kShownElsewhere = {
    {"active_dofs", "tests/models/erunsal_identifiability_test.cc"},
    {"regions", "tests/system/thrust_law_fit_test.cc"},
    {"origin", "tests/system/real_log_test.cc"},
    // The shipped config EriksenConfig.RegressionThenRefinementImprovesTheValidationFit runs.
    {"step_regression", "configs/eriksen_2dof.yaml"},
    {"simulation", "tests/system/mismatch_campaign_test.cc"},
    {"file_mb", "tests/system/hostile_input_test.cc"},
    // Results are the same on any number of threads (by design): the test shows that.
    {"num_threads", "tests/system/thread_count_test.cc"},
    {"description", "tests/system/report_html_test.cc"},
    {"outside_data", "tests/system/hostile_input_test.cc"},
    {"memory_mb", "tests/system/hostile_input_test.cc"},
    {"max_profile_evaluations", "tests/system/thrust_law_fit_test.cc"},
    // Needs another run's output folder.
    {"reference", "tests/python/test_reference_model.py"},
    // The filter-error method's section (docs/models.md "Disturbance models").
    {"noise", "tests/system/filter_error_run_test.cc"},
    {"method", "tests/system/filter_error_run_test.cc"},
    {"angles", "tests/system/filter_error_run_test.cc"},
    {"measurement", "tests/system/filter_error_run_test.cc"},
    {"process", "tests/system/filter_error_run_test.cc"},
    {"wave", "tests/system/filter_error_run_test.cc"},
    {"bias", "tests/system/filter_error_run_test.cc"},
    {"prediction_steps", "tests/system/filter_error_run_test.cc"},
    {"tau", "tests/system/filter_error_run_test.cc"},
    {"white", "tests/system/filter_error_run_test.cc"},
    {"omega", "tests/system/filter_error_run_test.cc"},
    {"zeta", "tests/system/filter_error_run_test.cc"},
    {"q", "tests/system/filter_error_run_test.cc"},
    {"initial_sd", "tests/system/filter_error_run_test.cc"},
    {"gain", "tests/system/filter_error_run_test.cc"},
    {"sigma", "tests/system/filter_error_run_test.cc"},
};
// Every documented key has a case here that adds it (more occurrences in `with` than in
// `base`), is the template's skeleton, or is shown by a named test that names it.
TEST(ConfigKeysDocumented, EveryDocumentedKeyHasACase) {
  const std::set<std::string> documented = DocumentedKeys();
  ASSERT_GT(documented.size(), 80u) << "docs/config_reference.md's first block was not found";
  std::string missing;
  for (const std::string& key : documented) {
    if (kNotKeys.count(key) || kSkeleton.count(key)) continue;
    bool covered = false;
    for (const KeyCase& c : kCases) {
      covered |= Occurrences(ConfigKeysText(c.with), key) !=
                 Occurrences(ConfigKeysText(c.base), key);
    }
    if (covered) continue;
    const auto elsewhere = kShownElsewhere.find(key);
    if (elsewhere == kShownElsewhere.end()) {
      missing += " " + key;
      continue;
    }
    std::ifstream file(std::string(VESSELID_SOURCE_DIR) + "/" + elsewhere->second);
    std::stringstream text;
    text << file.rdbuf();
    EXPECT_TRUE(file.good() && Occurrences(text.str(), key) > 0)
        << key << ": " << elsewhere->second << " does not name it";
  }
  EXPECT_TRUE(missing.empty()) << "documented keys without a case:" << missing;
}

INSTANTIATE_TEST_SUITE_P(Reference, ConfigKeys, ::testing::ValuesIn(kCases), CaseName);

}  // namespace config_keys_test
}  // namespace vesselid
