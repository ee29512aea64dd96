// The disturbance model of the filter-error method (filter_error_cost.h): what the ship model
// does not explain, as random processes with identified parameters, instead of output error's
// white measurement noise alone. Each part is documented with its equation in docs/models.md
// ("Disturbance models"):
//
//   measured y_j(t_i) = g_j(x, u, p) + z_j(t_i) + v_i,       v_i ~ N(0, sigma_j^2)   (white)
//   model states       x' = f(x, u, p) + w_x,                 E[w_x w_x'] = diag(q) delta(t - t')
//
// with z_j a sum of linear disturbance states added to output j:
//   ar1:  z' = -z / tau + w,          stationary SD sigma (q = 2 sigma^2 / tau)
//   wave: z1' = z2, z2' = -omega^2 z1 - 2 zeta omega z2 + w, stationary SD of z1 sigma
//         (the linear wave-response model of autopilots' wave filters; q = 4 zeta omega^3 sigma^2)
//   bias: z' = w (random walk: current, wind, gyro drift), E[w^2] = q, z(t0) ~ N(0, sd0^2)
//
// The spec is what a config says (names, starts in the units of the output); the layout is the
// same resolved to indices for the cost function's hot path (no string lookup per step).
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/model/model.h"

namespace vesselid {

// Disturbance states a filter carries at most besides the model's (fixed-size arrays).
inline constexpr int kMaxDisturbanceStates = 8;

struct DisturbanceSpec {
  // output_error: no filter (today's white-noise output error); filter_error: the Kalman
  // filter's innovations likelihood with the parts below; auto: output error, then the
  // filter-error candidates in order of complexity, kept by BIC (disturbance_choice.h).
  enum class Method { kOutputError, kFilterError, kAuto };
  Method method = Method::kOutputError;

  // Measurement noise of one compared output: white (sigma), or first-order Gauss-Markov
  // (ar1: sigma, tau), with an optional white part beside it (white_sigma > 0 or NaN: start
  // from the data; 0: none).
  struct Measurement {
    std::string output;
    enum class Type { kWhite, kAr1 };
    Type type = Type::kWhite;
    double sigma = std::numeric_limits<double>::quiet_NaN();  // start; NaN: the data's level
    double tau = std::numeric_limits<double>::quiet_NaN();    // s; NaN: 1 s
    bool white_too = false;  // ar1 with a white part as well
  };
  // Process noise on one state's equation: spectral density q (state unit^2 / s); NaN: start
  // from the data.
  struct Process {
    std::string state;
    double q = std::numeric_limits<double>::quiet_NaN();
  };
  struct Wave {
    std::string output;
    double omega = 0.8;  // rad/s, peak frequency start
    double zeta = 0.1;   // damping ratio start
    double sigma = std::numeric_limits<double>::quiet_NaN();  // NaN: 3 x the data's level
  };
  struct Bias {
    std::string output;
    double q = std::numeric_limits<double>::quiet_NaN();  // unit^2/s; NaN: from the data
    double initial_sd = std::numeric_limits<double>::quiet_NaN();  // NaN: 10 x noise level
  };
  std::vector<Measurement> measurement;  // compared outputs not listed: white
  std::vector<Process> process;
  std::vector<Wave> wave;
  std::vector<Bias> bias;
  // Held-out k-step-ahead predictions through the filter (k nodes ahead).
  int prediction_steps = 10;
  // auto: the steady-state gain once the filter has converged on a stationary stretch
  // (kalman_filter.h); time_varying: the gain of every node computed.
  bool steady_gain = true;

  bool active() const { return method != Method::kOutputError; }
  bool empty() const { return measurement.empty() && process.empty() && wave.empty() && bias.empty(); }
};

const char* DisturbanceMethodToString(DisturbanceSpec::Method method);
bool StringToDisturbanceMethod(const std::string& text, DisturbanceSpec::Method* method);

// One identified quantity of the disturbance model.
struct NoiseParameter {
  enum class Kind { kWhiteSigma, kAr1Sigma, kAr1Tau, kWaveOmega, kWaveZeta, kWaveSigma, kBiasQ,
                    kProcessQ };
  Kind kind = Kind::kWhiteSigma;
  int target = 0;    // output (measurement, wave, bias) or state (process) index
  std::string name;  // "sigma.psi", "tau.psi", "q.eta2", "omega.wave.psi"
  std::string unit;  // "rad", "s", "rad/s", "", "rad^2/s"
  double start = 1.0, lower = 0.0, upper = std::numeric_limits<double>::infinity();
};

// The disturbance resolved for one model and its compared outputs. Indices are into
// `parameters` (-1: none).
struct DisturbanceLayout {
  std::vector<NoiseParameter> parameters;
  int num_states = 0;  // disturbance states (<= kMaxDisturbanceStates)
  struct OutputNoise {
    int white = -1;             // sigma of the white part
    int ar1_sigma = -1, ar1_tau = -1, ar1_state = -1;
    int wave_omega = -1, wave_zeta = -1, wave_sigma = -1, wave_state = -1;  // z1, z2 = state+1
    int bias_q = -1, bias_state = -1;
    double bias_initial_sd = 0.0;
    double floor = 0.0;  // variance always added (numerical floor), unit^2
  };
  std::vector<OutputNoise> outputs;  // per model output
  std::vector<int> process;          // per model state: q parameter index or -1
  // Freeze the gains once the filter is steady (kalman_filter.h); false: time-varying always.
  bool steady_gain = true;

  int size() const { return static_cast<int>(parameters.size()); }
  bool empty() const { return parameters.empty(); }
  // "sigma.psi, tau.psi, q.eta2"
  std::string Names() const;
  // "ar1(psi) + process(eta2)": the structure in words, for tables and the choice's report.
  std::string Describe() const;
};

// What the layout's starts and bounds are scaled by: the compared outputs (model indices), each
// output's noise level as the data show it (NaN: unknown), each state's largest |x| over the
// records at the start values (0: unknown), and the median sample interval, s.
struct DisturbanceScales {
  std::vector<int> compared;
  std::vector<double> noise_level;
  std::vector<double> state_magnitude;
  double sample_interval = 1.0;
};

// Resolves `spec` for `info`: every compared output gets a white part unless listed otherwise.
// Errors name the key and the unknown or uncompared output or state.
bool BuildDisturbanceLayout(const DisturbanceSpec& spec, const ModelInfo& info,
                            const DisturbanceScales& scales, DisturbanceLayout* layout,
                            std::string* error);

}  // namespace vesselid
