// Synthetic test campaign of seed 002 on a 6-DOF vessel, every run simulated with the full
// (unrestricted) model:
//   thrust:  vessel restrained, commands swept, load-cell forces F_L, F_R recorded
//   decay:   released from an initial angle, displacement or rate, motors off
//   spiral:  mean command held, differential command stepped up and down
//   zigzag:  differential command switched when the heading passes +-heading
//   random:  both commands piecewise constant at random levels and durations
// Recorded at sample_time with Gaussian noise on positions, angles and forces.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "engine/model/model_handle.h"

namespace vesselid::erunsal6dof {

struct CampaignNoise {
  double position = 0.02;  // m
  double angle = 0.2 * M_PI / 180.0;  // rad
  double force = 0.05;  // N
};

struct CampaignRun {
  enum class Type { kThrust, kDecay, kSpiral, kZigzag, kRandom };
  Type type = Type::kDecay;
  std::string file;
  double duration = 20.0;
  std::vector<double> initial_state = std::vector<double>(12, 0.0);
  double mean_command = 0.6;       // spiral, zigzag
  double differential = 0.3;       // zigzag amplitude; spiral largest step
  double step_time = 10.0;         // spiral step length, thrust sweep step
  double zigzag_heading = 20.0 * M_PI / 180.0;
  unsigned seed = 1;
  // DOFs the run excites (seed 002 assumes e.g. that spiral tests leave heave, roll and pitch
  // at rest); all six by default. Thrust tests are always restrained (none).
  std::array<bool, 6> active = {true, true, true, true, true, true};
};

struct CampaignOptions {
  double sample_time = 0.02;
  int substeps = 2;
  CampaignNoise noise;
};

const char* CampaignTypeToString(CampaignRun::Type type);
bool StringToCampaignType(const std::string& text, CampaignRun::Type* type);

// Simulates one run of the campaign with `model` (all DOFs active) and the given parameters.
bool SimulateCampaignRun(const ModelHandle& model, const std::vector<double>& parameters,
                         const CampaignOptions& options, const CampaignRun& run,
                         Trajectory* trajectory, std::string* error);

}  // namespace vesselid::erunsal6dof
