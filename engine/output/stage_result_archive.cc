#include "engine/output/stage_result_archive.h"

#include <cstdint>
#include <cstring>
#include <memory>

namespace nlohmann {

// Eigen matrices and vectors as {rows, cols, column-major data}.
template <>
struct adl_serializer<Eigen::MatrixXd> {
  static void to_json(json& j, const Eigen::MatrixXd& m) {
    j = {{"rows", m.rows()},
         {"cols", m.cols()},
         {"data", std::vector<double>(m.data(), m.data() + m.size())}};
  }
  static void from_json(const json& j, Eigen::MatrixXd& m) {
    const auto data = j.at("data").get<std::vector<double>>();
    m.resize(j.at("rows").get<Eigen::Index>(), j.at("cols").get<Eigen::Index>());
    if (static_cast<size_t>(m.size()) != data.size()) throw json::other_error::create(
        501, "matrix data does not match its size", &j);
    std::copy(data.begin(), data.end(), m.data());
  }
};

template <>
struct adl_serializer<Eigen::VectorXd> {
  static void to_json(json& j, const Eigen::VectorXd& v) {
    j = std::vector<double>(v.data(), v.data() + v.size());
  }
  static void from_json(const json& j, Eigen::VectorXd& v) {
    const auto data = j.get<std::vector<double>>();
    v = Eigen::Map<const Eigen::VectorXd>(data.data(), static_cast<Eigen::Index>(data.size()));
  }
};

}  // namespace nlohmann

namespace vesselid {

// Every member of each type, so that a restored stage is the stage. A member missing here
// is lost on resume; the resume test compares every output of a resumed run with an
// uninterrupted one.
namespace {

// A column of samples as a CBOR byte string of its doubles (the machine's byte order: a
// checkpoint resumes on the machine that wrote it): a fit's trace is hundreds of thousands of
// samples, which as JSON numbers cost a node each to write and to read.
nlohmann::json SamplesToBinary(const std::vector<double>& values) {
  std::vector<std::uint8_t> bytes(values.size() * sizeof(double));
  if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  return nlohmann::json::binary(std::move(bytes));
}

std::vector<double> SamplesFromBinary(const nlohmann::json& j) {
  const nlohmann::json::binary_t& bytes = j.get_binary();
  if (bytes.size() % sizeof(double) != 0) {
    throw nlohmann::json::other_error::create(501, "samples are not a whole number of doubles",
                                              &j);
  }
  std::vector<double> values(bytes.size() / sizeof(double));
  if (!values.empty()) std::memcpy(values.data(), bytes.data(), bytes.size());  // not null
  return values;
}

}  // namespace

void to_json(nlohmann::json& j, const Trajectory& trajectory) {
  nlohmann::json columns = nlohmann::json::array();
  for (const std::vector<double>& column : trajectory.columns)
    columns.push_back(SamplesToBinary(column));
  j = {{"source", trajectory.source},
       {"names", trajectory.names},
       {"t", SamplesToBinary(trajectory.t)},
       {"columns", std::move(columns)}};
}

void from_json(const nlohmann::json& j, Trajectory& trajectory) {
  j.at("source").get_to(trajectory.source);
  j.at("names").get_to(trajectory.names);
  trajectory.t = SamplesFromBinary(j.at("t"));
  trajectory.columns.clear();
  for (const nlohmann::json& column : j.at("columns"))
    trajectory.columns.push_back(SamplesFromBinary(column));
  if (trajectory.columns.size() != trajectory.names.size()) {
    throw nlohmann::json::other_error::create(501, "trace columns do not match their names", &j);
  }
  for (const std::vector<double>& column : trajectory.columns) {
    if (column.size() != trajectory.t.size()) {
      throw nlohmann::json::other_error::create(501, "trace column length differs from t", &j);
    }
  }
}

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ChannelMetrics, experiment, output, samples, rmse, mae, r2,
                                   fit_percent, hold_mae, noise)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(StartOffset, state, measured, refitted, noise, sds)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(HeldOutStartReport, mode, burn_in, requested_burn_in,
                                   estimated, weighed, refitted, measured_start,
                                   measured_start_diverged, offsets, implausible_sds)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ExperimentFit, experiment, diverged, message, rms_cost, channels,
                                   trace, start)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(HeldOutCheck, done, outputs, start_mae, stage_mae,
                                   start_diverged, stage_diverged, start_far_worse, worse,
                                   baseline)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(GlobalStartSummary, run, variables, around_start, algorithm,
                                   horizon_seconds, evaluations, failed_evaluations, abandoned,
                                   short_solves, known_joined, clusters, short_iterations_total,
                                   best_cost, time_seconds, result, message, candidates,
                                   candidate_costs, best_cost_history)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(LocalSolveSummary, run, usable, initial_cost, final_cost,
                                   iterations, successful_steps, unsuccessful_steps, time_seconds,
                                   termination, message, cost_history, residual_seconds,
                                   jacobian_seconds, linear_solver_seconds, residual_evaluations,
                                   jacobian_evaluations)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Uncertainty, available, message, variables, covariance,
                                   correlation, std_errors, residual_variance, undetermined,
                                   undetermined_variables, method, hessian_std_errors,
                                   method_reason, hac_bandwidth, bootstrap_runs, bootstrap_failed,
                                   block_length, replicates, replicate_names, input_noise_runs,
                                   input_noise_failed, input_noise_inputs, input_noise_std_errors,
                                   input_noise_share)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(WeakDirection, combination, coefficients, eigenvalue_ratio,
                                   std_dev, std_dev_normalised, status)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(LocalAnalysis, available, message, parameters, names,
                                   profiled, num_residuals, num_free, residual_variance,
                                   information, eigenvalues, condition_number, directions,
                                   std_errors, channels, sensitivity, noise_sensitivity,
                                   time_seconds)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ResidualCrossCorrelation, input, values, band_99, correlated)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ResidualAnalysis, experiment, output, samples, lags,
                                   autocorrelation, band_99, band_95, ljung_box_q, ljung_box_p,
                                   lag1, white, cross_correlation, input_correlated,
                                   interval_spread, noise_free, input_noise_share)
// Kind and severity as the words results.json uses; an unknown word fails the archive.
void to_json(nlohmann::json& j, FindingKind kind) { j = FindingKindToString(kind); }
void from_json(const nlohmann::json& j, FindingKind& kind) {
  if (!StringToFindingKind(j.get<std::string>(), &kind)) {
    throw nlohmann::json::other_error::create(501, "unknown finding kind " + j.dump(), &j);
  }
}
void to_json(nlohmann::json& j, FindingSeverity severity) { j = FindingSeverityToString(severity); }
void from_json(const nlohmann::json& j, FindingSeverity& severity) {
  if (!StringToFindingSeverity(j.get<std::string>(), &severity)) {
    throw nlohmann::json::other_error::create(501, "unknown finding severity " + j.dump(), &j);
  }
}
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Finding, kind, severity, stage, experiment, segment, parameter,
                                   output, value, threshold, count, message)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(StageSummary, name, usable, message, global, refinements,
                                   chosen, uncertainty, analysis, fits, notes, findings,
                                   time_seconds)
// Kind and role as the words results.json uses; an unknown word fails the archive.
void to_json(nlohmann::json& j, EstimateKind kind) { j = EstimateKindToString(kind); }
void from_json(const nlohmann::json& j, EstimateKind& kind) {
  if (!StringToEstimateKind(j.get<std::string>(), &kind)) {
    throw nlohmann::json::other_error::create(501, "unknown estimate kind " + j.dump(), &j);
  }
}
void to_json(nlohmann::json& j, ParameterRole role) { j = ParameterRoleToString(role); }
void from_json(const nlohmann::json& j, ParameterRole& role) {
  if (!StringToParameterRole(j.get<std::string>(), &role)) {
    throw nlohmann::json::other_error::create(501, "unknown parameter role " + j.dump(), &j);
  }
}
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(NoiseModel, method, iterations, converged, outputs, sigma,
                                   samples)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Estimate, name, kind, role, experiment, value, start,
                                   std_error, lower, upper, undetermined)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(HeldOutParameters, fitted, parameters, estimates, without)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(DampingSample, record, t, duration, x, sigma, turns, weight,
                                   group, mirrored)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(InertiaSample, record, term, t, x, inertia, gain,
                                   time_constant, rms, weight, group, mirrored)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(StepSamples, damping, inertia, intervals, steady, steps, notes,
                                   window_seconds, fit_seconds)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(LassoPath, lambda, beta, nonzero, cv_error, cv_standard_error,
                                   best, one_standard_error, groups, sweeps)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TermRegression::AsymptoteCv, a, b, cv_error, lambda)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TermRegression, name, samples, groups, mean_x, sd_x, mean_y,
                                   sd_y, path, lambda, normalised, a, b, asymptote_grid,
                                   coefficients, r2, rms, seconds)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(StepRegressionReport, samples, terms, normalisation_seconds,
                                   regression_seconds)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(BootstrapSummary, runs, failed, groups, resampled, lambda_held,
                                   names, std_error, lower, upper, coefficient_names, zero_share,
                                   message, time_seconds)

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(DisturbanceCandidateScore, name, solved, why,
                                   negative_log_likelihood, unknowns, bic, chosen)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FilterPrediction, experiment, output, steps, seconds_ahead,
                                   k_step_fit_percent, one_step_fit_percent, free_run_fit_percent)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(DisturbanceReport, method, model, filter_error,
                                   negative_log_likelihood, candidates, predictions)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FreeRunDrift, experiment, output, samples, observed_sse,
                                   expected_sse)

namespace {
// 3: Uncertainty method, hessian_std_errors, method_reason, hac_bandwidth; 4: bootstrap runs,
// failed, block length; 6: traces' samples as byte strings; 7: typed solver findings,
// comparable cost, state limits; 9: bootstrap replicates; 10: input noise refits, the held-out
// check's baseline; 11: the disturbance model's report and the free run's drift (a resumed
// stage lost them: its verdict then read output error's residuals)
constexpr int kArchiveVersion = 11;
}  // namespace

nlohmann::json StageResultToArchive(const StageResult& stage) {
  nlohmann::json j = {{"archive_version", kArchiveVersion},
                      {"name", stage.name},
                      {"model", stage.model},
                      {"summary", stage.summary},
                      {"estimates", stage.estimates},
                      {"correlation_names", stage.correlation_names},
                      {"correlation", stage.correlation},
                      {"admissibility", stage.admissibility},
                      {"validation", stage.validation},
                      {"held_out", stage.held_out},
                      {"held_out_parameters", stage.held_out_parameters},
                      {"rejected", stage.rejected},
                      {"integration_step", stage.integration_step},
                      {"comparable_cost", stage.comparable_cost},
                      {"state_limits", stage.state_limits},
                      {"structure_doubts", stage.structure_doubts},
                      {"noise_model", stage.noise_model},
                      {"velocity_validation", stage.velocity_validation},
                      {"residuals", stage.residuals},
                      {"validation_residuals", stage.validation_residuals},
                      {"disturbance", stage.disturbance},
                      {"free_run_drift", stage.free_run_drift}};
  if (stage.step_regression) j["step_regression"] = *stage.step_regression;
  if (stage.bootstrap.done() || !stage.bootstrap.message.empty()) j["bootstrap"] = stage.bootstrap;
  return j;
}

bool StageResultFromArchive(const nlohmann::json& j, StageResult* stage, std::string* error) {
  try {
    if (j.at("archive_version").get<int>() != kArchiveVersion) {
      *error = "stage archive version " + j.at("archive_version").dump() + ", expected " +
               std::to_string(kArchiveVersion);
      return false;
    }
    StageResult s;
    j.at("name").get_to(s.name);
    j.at("model").get_to(s.model);
    j.at("summary").get_to(s.summary);
    j.at("estimates").get_to(s.estimates);
    j.at("correlation_names").get_to(s.correlation_names);
    j.at("correlation").get_to(s.correlation);
    j.at("admissibility").get_to(s.admissibility);
    j.at("validation").get_to(s.validation);
    j.at("held_out").get_to(s.held_out);
    // Absent from archives written before held-out runs had per-experiment parameters.
    if (j.contains("held_out_parameters"))
      j.at("held_out_parameters").get_to(s.held_out_parameters);
    j.at("rejected").get_to(s.rejected);
    j.at("integration_step").get_to(s.integration_step);
    j.at("comparable_cost").get_to(s.comparable_cost);
    j.at("state_limits").get_to(s.state_limits);
    j.at("structure_doubts").get_to(s.structure_doubts);
    // Absent from archives written before stages had a noise model (configured weights).
    if (j.contains("noise_model")) j.at("noise_model").get_to(s.noise_model);
    j.at("velocity_validation").get_to(s.velocity_validation);
    // Absent from archives written before stages analysed their residuals.
    if (j.contains("residuals")) j.at("residuals").get_to(s.residuals);
    if (j.contains("validation_residuals"))
      j.at("validation_residuals").get_to(s.validation_residuals);
    if (j.contains("step_regression")) {
      s.step_regression =
          std::make_shared<const StepRegressionReport>(j.at("step_regression").get<StepRegressionReport>());
    }
    if (j.contains("bootstrap")) j.at("bootstrap").get_to(s.bootstrap);
    j.at("disturbance").get_to(s.disturbance);
    j.at("free_run_drift").get_to(s.free_run_drift);
    *stage = std::move(s);
    return true;
  } catch (const nlohmann::json::exception& e) {
    *error = std::string("stage archive: ") + e.what();
    return false;
  }
}

}  // namespace vesselid
