// The MMG variant (KVLCC2 model, problems/mmg) on its own free-running campaign: zigzags and
// a turning circle at the 7 m model's propeller rate, positions, heading and speed logged.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "problems/mmg/campaign.h"
#include "problems/mmg/handles.h"
#include "tests/models/model_factory.h"

namespace vesselid::testing {
namespace {

constexpr double kDegree = M_PI / 180.0;

mmg::CampaignRun Run(mmg::CampaignRun::Type type, double rudder_deg, double heading_deg,
                     double first, double duration, double sample_time) {
  mmg::CampaignRun run;
  run.type = type;
  run.rudder = rudder_deg * kDegree;
  run.heading = heading_deg * kDegree;
  run.first = first;
  run.duration = duration;
  run.sample_time = sample_time;
  return run;
}

Trajectory Simulate(const ModelHandle& model, const std::vector<double>& truth,
                    const mmg::CampaignRun& run) {
  Trajectory data;
  std::string error;
  if (!mmg::SimulateRun(model, truth, run, &data, &error)) throw std::runtime_error(error);
  return data;
}

ExperimentSpec Spec(const std::vector<std::string>& outputs) {
  ExperimentSpec spec;
  spec.name = "run";
  spec.inputs = {{"delta", "delta"}, {"n", "n"}};
  const std::map<std::string, std::string> columns = {{"x", "x"}, {"y", "y"},      {"psi", "psi"},
                                                      {"U", "U"}, {"r", "r_true"}, {"v", "v_true"}};
  for (const std::string& o : outputs) spec.outputs[o] = columns.at(o);
  return spec;
}

// 40 s of a 20/20 zigzag, every output that the parameters reach; every parameter 5 % off
// (the rudder bias 0.003 rad), the initial state off the data's.
JacobianCase Jacobian(const ModelHandle& model, const std::vector<double>& truth) {
  const Trajectory data =
      Simulate(model, truth, Run(mmg::CampaignRun::Type::kZigzag, 20, 10, 1.0, 40, 0.2));
  JacobianCase c;
  c.experiment = Build(Spec({"x", "y", "psi", "U", "r", "v"}), data, model.info());
  c.scales.assign(truth.size(), 1.0);
  c.scales[model.info().ParameterIndex("Y_v")] = 0.3;
  c.theta = JacobianPoint(truth, c.scales, 1.05, 0.003, {0.1, -0.1, 0.02, 1.0, 0.02, 0.01});
  c.tolerance = 1e-5;
  c.min_columns = static_cast<int>(c.theta.size());
  return c;
}

// 40 s of a 35 deg turn sampled every 0.5 s, the inputs held between samples.
Rk4Case Rk4(const ModelHandle& model) {
  const ModelInfo& info = model.info();
  const Trajectory data = Simulate(model, info.parameter_defaults,
                                   Run(mmg::CampaignRun::Type::kTurning, 35, 0, 1.0, 40, 0.5));
  ExperimentSpec spec = Spec({"x", "y", "psi", "U"});
  spec.default_interpolation = Interpolation::kZeroOrderHold;
  spec.initial_state = {{"x", 0.0}, {"y", 0.0}, {"psi", 0.0}, {"u", 1.0}, {"v", 0.0}, {"r", 0.0}};
  return MakeRk4Case(info, spec, data, 0.5 / 256, {0.25, 0.125, 0.0625}, 0.4);
}

// Four 60 s zigzags (10/10, 20/20 both sides, 35/35) with 0.02 m, 0.1 deg and 5 mm/s noise,
// residuals weighted to metres; the hull's 12 lateral derivatives from +-20 %, the first
// positions, heading and surge speed estimated.
RecoveryCase Recovery(const ModelHandle& model, const std::vector<double>& truth) {
  RecoveryCase c;
  const double position = 0.02, heading = 0.1 * kDegree, speed = 0.005;
  const struct {
    double rudder, heading, first;
  } zigzags[] = {{10, 10, 1.0}, {20, 20, -1.0}, {20, 20, 1.0}, {35, 35, -1.0}};
  unsigned seed = 1;
  for (const auto& z : zigzags) {
    mmg::CampaignRun run =
        Run(mmg::CampaignRun::Type::kZigzag, z.rudder, z.heading, z.first, 60, 0.2);
    run.position_noise = position;
    run.heading_noise = heading;
    run.speed_noise = speed;
    run.seed = seed++;
    ExperimentSpec spec = Spec({"x", "y", "psi", "U"});
    spec.output_weights = {{"psi", position / heading}, {"U", position / speed}};
    spec.initial_state = {{"u", 1.0}, {"v", 0.0}, {"r", 0.0}};
    c.experiments.push_back(Build(spec, Simulate(model, truth, run), model.info()));
  }
  c.options.free_initial_states = {"x", "y", "psi", "u"};
  const ModelInfo& info = model.info();
  const std::vector<std::string> free = {"Y_v", "Y_r", "Y_vvv", "Y_vvr", "Y_vrr", "Y_rrr",
                                         "N_v", "N_r", "N_vvv", "N_vvr", "N_vrr", "N_rrr"};
  for (size_t i = 0; i < truth.size(); ++i) {
    ParameterSpec s;
    s.name = info.parameters[i];
    s.start = truth[i];
    s.role = ParameterRole::kFixed;
    if (std::find(free.begin(), free.end(), s.name) != free.end()) {
      s = PerturbedSpec(s.name, truth[i], c.free_parameters, 0.2);
      ++c.free_parameters;
    }
    c.specs.push_back(s);
  }
  c.sigmas = 3.0;
  c.residual_sd = position;
  c.residual_weight = 1.0 / c.experiments.front().num_samples();
  c.residual_tolerance = 0.05;
  return c;
}

}  // namespace

void AddMmgVariants(std::vector<ModelVariant>* variants) {
  const mmg::Ship ship;
  variants->push_back({"MmgKvlcc2", [ship] { return mmg::MakeMmgHandle(ship); },
                       mmg::MakeMmgHandle(ship)->info().parameter_defaults, Jacobian, Rk4,
                       Recovery});
}

}  // namespace vesselid::testing
