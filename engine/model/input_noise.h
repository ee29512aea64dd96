// Errors in a measured input (config `input_noise`): the simulation uses a latent input,
//   u(t) = s(t) + c_j(t),
// s a smoothing spline of the measured samples (data/latent_input.h) and c_j piecewise-constant
// low-frequency corrections on a coarse grid of spacing D, estimated with the parameters and
// tied to the measurement by a prior residual c_j / (sigma sqrt(dt / D)): the SD of the mean of
// white input noise over one interval (dt the sample interval). The spline removes the noise
// the outputs cannot see; the corrections remove what they can, the noise's low-frequency part
// that psi' = r integrates into a random walk.
#pragma once

#include <string>
#include <vector>

namespace vesselid {

// What a config says about one noisy input.
struct InputNoiseSpec {
  double sigma = 0.0;       // noise SD in the column's unit; 0: estimated from the spline fit
  double knots = 0.0;       // spline knot spacing in s; 0: chosen from the data (GCV / C_p)
  double correction = 0.0;  // spacing D of the corrections in s; 0: auto; < 0: none
  std::string key;          // "file:line: key" of the config entry, for messages
};

// Corrections per experiment at most, and their shortest spacing in input samples.
inline constexpr int kMaxInputCorrections = 32;
inline constexpr double kMinCorrectionSamples = 10.0;

// The latent input of one experiment as fitted.
struct LatentInput {
  int input = 0;             // model input index
  std::string column;
  bool degrees = false;      // the column is recorded in degrees (values below in radians)
  double sigma = 0.0;        // noise SD used (rad for a degree column)
  bool sigma_estimated = false;
  double noise_level = 0.0;  // second-difference estimate of the samples (noise_level.h)
  double knot_spacing = 0.0;
  double sample_interval = 0.0;  // median
  int samples = 0;
};

// Piecewise-constant corrections of one input: value j acts on the steps starting in
// [t0 + j D, t0 + (j + 1) D).
struct InputCorrectionGrid {
  int input = 0;
  double spacing = 0.0;          // D, s
  int count = 0;
  int offset = 0;                // first index among the experiment's correction values
  double sigma = 0.0;            // prior SD of each value: sigma sqrt(dt / D)
  std::vector<int> step_interval;  // per RK4 step: its value's index in [0, count)
};

}  // namespace vesselid
