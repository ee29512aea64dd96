#include "problems/erunsal6dof/campaign.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/model/open_loop_simulation.h"

namespace vesselid::erunsal6dof {
namespace {

const char* const kTypeNames[] = {"thrust", "decay", "spiral", "zigzag", "random"};

// Commands held between samples, as a flight controller would send them.
Trajectory Commands(const std::vector<double>& t, const std::vector<double>& left,
                    const std::vector<double>& right) {
  Trajectory c;
  c.t = t;
  c.names = {"c_L", "c_R"};
  c.columns = {left, right};
  return c;
}

std::vector<double> Times(double duration, double dt) {
  std::vector<double> t;
  const long n = static_cast<long>(std::floor(duration / dt + 1e-9));
  for (long k = 0; k <= n; ++k) t.push_back(k * dt);
  return t;
}

// Zigzag by differential command: switched when psi passes +-heading. Simulated piecewise,
// one sample at a time, so the switching sees the heading as the controller would.
bool SimulateZigzag(const ModelHandle& model, const std::vector<double>& p,
                    const CampaignOptions& options, const CampaignRun& run, Trajectory* out,
                    std::string* error) {
  const std::vector<double> t = Times(run.duration, options.sample_time);
  std::vector<double> left, right, x = run.initial_state;
  double sign = 1.0;
  Trajectory result;
  OpenLoopOptions open;
  open.substeps = options.substeps;
  const int psi = model.info().OutputIndex("psi");
  for (size_t k = 0; k + 1 < t.size(); ++k) {
    Trajectory piece = Commands({t[k], t[k + 1]}, {run.mean_command + sign * run.differential},
                                {run.mean_command - sign * run.differential});
    piece.columns[0].push_back(piece.columns[0][0]);
    piece.columns[1].push_back(piece.columns[1][0]);
    Trajectory step;
    if (!SimulateOpenLoop(model, p, x, piece, open, &step, error)) return false;
    const size_t first = piece.names.size();
    if (k == 0) {
      result.names = step.names;
      result.columns.assign(step.columns.size(), {});
    }
    for (size_t c = 0; c < step.columns.size(); ++c) result.columns[c].push_back(step.columns[c][0]);
    result.t.push_back(t[k]);
    for (int i = 0; i < 12; ++i) x[i] = step.columns[first + i][1];
    const double heading = x[psi];
    // Left thrust above right turns to starboard (r > 0): switch at +heading, then -heading.
    if (sign > 0 && heading >= run.zigzag_heading) sign = -1.0;
    else if (sign < 0 && heading <= -run.zigzag_heading) sign = 1.0;
    if (k + 2 == t.size()) {
      for (size_t c = 0; c < step.columns.size(); ++c) result.columns[c].push_back(step.columns[c][1]);
      result.t.push_back(t[k + 1]);
    }
  }
  *out = std::move(result);
  return true;
}

}  // namespace

const char* CampaignTypeToString(CampaignRun::Type type) {
  return kTypeNames[static_cast<int>(type)];
}

bool StringToCampaignType(const std::string& text, CampaignRun::Type* type) {
  for (int i = 0; i < 5; ++i) {
    if (text == kTypeNames[i]) {
      *type = static_cast<CampaignRun::Type>(i);
      return true;
    }
  }
  return false;
}

bool SimulateCampaignRun(const ModelHandle& model, const std::vector<double>& parameters,
                         const CampaignOptions& options, const CampaignRun& run,
                         Trajectory* trajectory, std::string* error) {
  const std::vector<double> t = Times(run.duration, options.sample_time);
  std::mt19937_64 random(run.seed);
  std::vector<double> left(t.size()), right(t.size());
  Trajectory simulated;
  OpenLoopOptions open;
  open.substeps = options.substeps;
  switch (run.type) {
    case CampaignRun::Type::kThrust: {
      // Commands stepped from -1 to 1 and back, each held step_time.
      const int levels = 9;
      for (size_t k = 0; k < t.size(); ++k) {
        const int step = static_cast<int>(t[k] / run.step_time) % (2 * levels - 2);
        const int level = step < levels ? step : 2 * levels - 2 - step;
        left[k] = -1.0 + 2.0 * level / (levels - 1);
        right[k] = 1.0 - 2.0 * level / (levels - 1);
      }
      if (!SimulateOpenLoop(model, parameters, run.initial_state, Commands(t, left, right), open,
                            &simulated, error)) {
        return false;
      }
      break;
    }
    case CampaignRun::Type::kDecay: {
      Trajectory silent;
      silent.t = t;
      if (!SimulateOpenLoop(model, parameters, run.initial_state, silent, open, &simulated,
                            error)) {
        return false;
      }
      break;
    }
    case CampaignRun::Type::kSpiral: {
      // Differential command 0, d/3, 2d/3, d, 2d/3, d/3, 0, -d/3, ... every step_time.
      const double pattern[] = {0, 1, 2, 3, 2, 1, 0, -1, -2, -3, -2, -1};
      for (size_t k = 0; k < t.size(); ++k) {
        const int step = static_cast<int>(t[k] / run.step_time) % 12;
        const double d = run.differential * pattern[step] / 3.0;
        left[k] = run.mean_command + d;
        right[k] = run.mean_command - d;
      }
      if (!SimulateOpenLoop(model, parameters, run.initial_state, Commands(t, left, right), open,
                            &simulated, error)) {
        return false;
      }
      break;
    }
    case CampaignRun::Type::kZigzag:
      if (!SimulateZigzag(model, parameters, options, run, &simulated, error)) return false;
      break;
    case CampaignRun::Type::kRandom: {
      std::uniform_real_distribution<double> level(0.1, 1.0), hold(1.0, 6.0);
      double next = 0.0, l = 0.0, r = 0.0;
      for (size_t k = 0; k < t.size(); ++k) {
        if (t[k] >= next) {
          l = level(random);
          r = level(random);
          next = t[k] + hold(random);
        }
        left[k] = l;
        right[k] = r;
      }
      if (!SimulateOpenLoop(model, parameters, run.initial_state, Commands(t, left, right), open,
                            &simulated, error)) {
        return false;
      }
      break;
    }
  }

  // Measurement noise.
  std::normal_distribution<double> unit(0.0, 1.0);
  auto add_noise = [&](const char* name, double sigma) {
    const int c = simulated.Find(name);
    if (c < 0 || sigma <= 0) return;
    for (double& v : simulated.columns[c]) v += sigma * unit(random);
  };
  for (const char* name : {"x", "y", "z"}) add_noise(name, options.noise.position);
  for (const char* name : {"phi", "theta", "psi"}) add_noise(name, options.noise.angle);
  if (run.type == CampaignRun::Type::kThrust) {
    for (const char* name : {"F_L", "F_R"}) add_noise(name, options.noise.force);
  } else {
    // A free-running vessel has no load cell: drop the force columns.
    for (const char* name : {"F_L", "F_R"}) {
      const int c = simulated.Find(name);
      if (c < 0) continue;
      simulated.names.erase(simulated.names.begin() + c);
      simulated.columns.erase(simulated.columns.begin() + c);
    }
  }
  *trajectory = std::move(simulated);
  return true;
}

}  // namespace vesselid::erunsal6dof
