#include "problems/eriksen2dof/campaign.h"

#include <algorithm>
#include <array>
#include <random>

#include "engine/model/rk4.h"

namespace vesselid::eriksen2dof {
namespace {

using Random = std::mt19937;
using Command = std::array<double, 2>;  // tau_m, tau_delta

// Output columns after t.
enum Column {
  kRun,
  kNorth,
  kEast,
  kCourse,
  kSog,
  kRot,
  kThrottle,
  kRudder,
  kSogTrue,
  kRotTrue,
  kColumns
};
const char* const kColumnNames[] = {"run", "n",        "e",      "course",   "sog",
                                    "rot", "throttle", "rudder", "sog_true", "rot_true"};

// Random streams: step campaign and validation runs draw from disjoint seed sequences.
enum Stream { kPlanStream, kGustStream, kNoiseStream, kStreams };

double Uniform(Random& random, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(random);
}

// Wraps an angle to (-pi, pi].
double WrapAngle(double angle) {
  const double wrapped = std::remainder(angle, 2.0 * M_PI);
  return wrapped <= -M_PI ? wrapped + 2.0 * M_PI : wrapped;
}

// True when value = count x unit for an integer count >= 1 (within rounding).
bool IntegerMultiple(double value, double unit, long* count) {
  *count = std::lround(value / unit);
  return *count >= 1 && std::abs(*count * unit - value) <= 1e-9 * std::max(1.0, value);
}

// 0, 1/n, ..., 1, (n-1)/n, ..., 0 for step = 1/n.
std::vector<double> UpAndDown(double step) {
  long n = 0;
  IntegerMultiple(1.0, step, &n);
  std::vector<double> levels;
  for (long k = 0; k <= n; ++k) levels.push_back(double(k) / double(n));
  for (long k = n - 1; k >= 0; --k) levels.push_back(double(k) / double(n));
  return levels;
}

// The craft in its environment, a still-water shadow driven by the same commands (to judge
// settling), and the log being written.
class Voyage {
 public:
  Voyage(const CraftParameters& parameters, const CampaignOptions& options, unsigned stream_base)
      : parameters_(parameters), options_(options) {
    std::seed_seq gust_seed{options.seed, stream_base + kGustStream};
    gust_random_.seed(gust_seed);
    std::seed_seq noise_seed{options.seed, stream_base + kNoiseStream};
    noise_random_.seed(noise_seed);
    IntegerMultiple(options.sample_period, options.step, &steps_per_sample_);
    environment_.current_n = options.current_speed * std::cos(options.current_direction);
    environment_.current_e = options.current_speed * std::sin(options.current_direction);
    SetWind();
    out_.names.assign(kColumnNames, kColumnNames + kColumns);
    out_.columns.assign(kColumns, {});
  }

  // Puts the craft (and the shadow) in the still-water steady state of `command` at the
  // origin, then runs it unlogged for warm_up s in the real environment.
  bool StartRun(const Command& command, std::string* error) {
    CraftSteadyState steady;
    if (!SteadyState(parameters_, command[0], command[1], &steady)) {
      *error = "campaign: no steady state for tau_m = " + std::to_string(command[0]) +
               ", tau_delta = " + std::to_string(command[1]);
      return false;
    }
    const double heading = x_[kCraftPsi];
    std::fill(x_, x_ + kCraftStates, 0.0);
    x_[kCraftPsi] = heading;
    x_[kCraftU] = steady.u;
    x_[kCraftV] = steady.v;
    x_[kCraftR] = steady.r;
    x_[kCraftThrust] = steady.thrust;
    x_[kCraftAngle] = steady.angle;
    std::copy(x_, x_ + kCraftStates, shadow_);
    command_ = command;
    const long warm_up = std::lround(options_.warm_up / options_.step);
    for (long k = 0; k < warm_up; ++k) {
      if (!Step(false, error)) return false;
    }
    x_[kCraftN] = 0.0;
    x_[kCraftE] = 0.0;
    quiet_ = 0.0;
    return true;
  }

  // Logs the sample at the current time with `command`, then holds the command for one
  // sample period.
  bool Sample(const Command& command, std::string* error) {
    command_ = command;
    Log();
    for (long k = 0; k < steps_per_sample_; ++k) {
      if (!Step(true, error)) return false;
    }
    return true;
  }

  // Step campaign level: settle, then hold for one full turn of the shadow.
  bool Level(const Command& command, std::string* error) {
    quiet_ = 0.0;
    double elapsed = 0.0;
    const double dt = options_.sample_period;
    while (elapsed < options_.max_settle - 1e-9 &&
           !(elapsed >= options_.min_settle - 1e-9 && quiet_ >= options_.settle_window - 1e-9)) {
      if (!Sample(command, error)) return false;
      elapsed += dt;
    }
    const double r = std::abs(shadow_[kCraftR]);
    const double turn = r > 0.0 ? 2.0 * M_PI / r : options_.max_steady;
    const double hold = std::clamp(turn, options_.min_steady, options_.max_steady);
    const long samples = std::lround(std::ceil(hold / dt - 1e-9));
    for (long k = 0; k < samples; ++k) {
      if (!Sample(command, error)) return false;
    }
    return true;
  }

  // Closes the run: the next one starts run_gap s after this run's last sample.
  void EndRun() {
    ++run_;
    step_count_ += std::lround(options_.run_gap / options_.step) - steps_per_sample_;
  }

  Trajectory Release() { return std::move(out_); }

 private:
  void SetWind() {
    const double speed = std::max(0.0, options_.wind_speed + gust_);
    environment_.wind_n = -speed * std::cos(options_.wind_direction);  // blows from direction
    environment_.wind_e = -speed * std::sin(options_.wind_direction);
  }

  // One RK4 step of the craft (environment held over the step) and, when `shadow`, of the
  // still-water shadow with its quiet-time bookkeeping; then the gust moves on.
  bool Step(bool shadow, std::string* error) {
    const CraftRhs rhs{&parameters_, &environment_};
    const double* tau = command_.data();
    bool ok = Rk4Step<CraftRhs, double>(rhs, tau, tau, tau, nullptr, options_.step, x_);
    if (ok && shadow) {
      const CraftRhs still{&parameters_, &calm_};
      double xdot[kCraftStates];
      ok = Rk4Step<CraftRhs, double>(still, tau, tau, tau, nullptr, options_.step, shadow_) &&
           CraftDerivative(parameters_, shadow_, tau, calm_, xdot);
      const bool quiet = ok && std::abs(xdot[kCraftU]) < options_.settle_acceleration &&
                         std::abs(xdot[kCraftR]) < options_.settle_yaw_acceleration;
      quiet_ = quiet ? quiet_ + options_.step : 0.0;
    }
    if (!ok) {
      *error = "campaign: simulation failed at t = " + std::to_string(Time()) + " s";
      return false;
    }
    if (shadow) ++step_count_;
    const double a = std::exp(-options_.step / options_.gust_time_constant);
    gust_ = a * gust_ + options_.gust_sd * std::sqrt(1.0 - a * a) * gust_unit_(gust_random_);
    SetWind();
    return true;
  }

  double Time() const { return std::round(step_count_ * options_.step * 1e6) / 1e6; }

  // One row at the current time; noise drawn in a fixed order.
  void Log() {
    double sog = 0.0, course = 0.0;
    GroundTrack(x_, environment_, &sog, &course);
    double row[kColumns];
    row[kRun] = run_;
    row[kNorth] = x_[kCraftN] + options_.position_noise * noise_unit_(noise_random_);
    row[kEast] = x_[kCraftE] + options_.position_noise * noise_unit_(noise_random_);
    row[kCourse] = WrapAngle(course + options_.course_noise * noise_unit_(noise_random_));
    row[kSog] = sog + options_.sog_noise * noise_unit_(noise_random_);
    row[kRot] = x_[kCraftR] + options_.rot_noise * noise_unit_(noise_random_);
    row[kThrottle] = command_[0];
    row[kRudder] = command_[1];
    row[kSogTrue] = sog;
    row[kRotTrue] = x_[kCraftR];
    out_.t.push_back(Time());
    for (int c = 0; c < kColumns; ++c) out_.columns[c].push_back(row[c]);
  }

  const CraftParameters& parameters_;
  const CampaignOptions& options_;
  Random gust_random_, noise_random_;
  std::normal_distribution<double> gust_unit_{0.0, 1.0}, noise_unit_{0.0, 1.0};
  CraftEnvironment environment_, calm_;
  double gust_ = 0.0;
  double x_[kCraftStates] = {};
  double shadow_[kCraftStates] = {};
  Command command_ = {0.0, 0.0};
  double quiet_ = 0.0;  // s the shadow has been quiet
  long steps_per_sample_ = 1;
  long step_count_ = 0;  // RK4 steps of logged time (and gaps) so far
  int run_ = 0;
  Trajectory out_;
};

// Commands of one validation run, one per sample.
class ValidationPlan {
 public:
  ValidationPlan(const CampaignOptions& options, Random* random)
      : o_(options),
        random_(*random),
        samples_(
            std::lround(std::ceil(options.validation_duration / options.sample_period - 1e-9))) {}

  std::vector<Command> Make(int kind) {
    switch (kind % 4) {
      case 0:
        return RandomSteps();
      case 1:
        return Smooth();
      case 2:
        return NegativeRudderSteps();
      default:
        return Tracking();
    }
  }

 private:
  double Throttle() {
    return Uniform(random_, o_.validation_throttle_min, o_.validation_throttle_max);
  }
  double Time(long k) const { return k * o_.sample_period; }

  // Both inputs stepped together to random values, holds 10-40 s.
  std::vector<Command> RandomSteps() {
    std::vector<Command> plan(samples_);
    Command command = {0.0, 0.0};
    double next = 0.0;
    for (long k = 0; k < samples_; ++k) {
      const double t = Time(k);
      if (t >= next) {
        command = {Throttle(), Uniform(random_, -1.0, 1.0)};
        next = t + Uniform(random_, 10.0, 40.0);
      }
      plan[k] = command;
    }
    return plan;
  }

  // Throttle steps every 20-60 s, rudder steps within [-1, 0] every 15-45 s, independently.
  std::vector<Command> NegativeRudderSteps() {
    std::vector<Command> plan(samples_);
    Command command = {0.0, 0.0};
    double next_throttle = 0.0, next_rudder = 0.0;
    for (long k = 0; k < samples_; ++k) {
      const double t = Time(k);
      if (t >= next_throttle) {
        command[0] = Throttle();
        next_throttle = t + Uniform(random_, 20.0, 60.0);
      }
      if (t >= next_rudder) {
        command[1] = Uniform(random_, -1.0, 0.0);
        next_rudder = t + Uniform(random_, 15.0, 45.0);
      }
      plan[k] = command;
    }
    return plan;
  }

  // Triangle-wave throttle, two-sinusoid rudder.
  std::vector<Command> Smooth() {
    const double lo = o_.validation_throttle_min, hi = o_.validation_throttle_max;
    const double period = Uniform(random_, 120.0, 240.0), phase = Uniform(random_, 0.0, 1.0);
    const double a = Uniform(random_, 0.5, 0.8);
    const double p1 = Uniform(random_, 60.0, 120.0), p2 = Uniform(random_, 12.0, 30.0);
    const double f1 = Uniform(random_, 0.0, 2.0 * M_PI), f2 = Uniform(random_, 0.0, 2.0 * M_PI);
    std::vector<Command> plan(samples_);
    for (long k = 0; k < samples_; ++k) {
      const double t = Time(k), s = std::fmod(t / period + phase, 1.0);
      const double triangle = s < 0.5 ? 2.0 * s : 2.0 - 2.0 * s;
      const double rudder =
          a * std::sin(2.0 * M_PI * t / p1 + f1) + (1.0 - a) * std::sin(2.0 * M_PI * t / p2 + f2);
      plan[k] = {lo + (hi - lo) * triangle, std::clamp(rudder, -1.0, 1.0)};
    }
    return plan;
  }

  // Piecewise linear through random knots 4-12 s apart.
  std::vector<Command> Tracking() {
    std::vector<Command> plan(samples_);
    double t0 = 0.0, t1 = Uniform(random_, 4.0, 12.0);
    Command from = {Throttle(), Uniform(random_, -1.0, 1.0)};
    Command to = {Throttle(), Uniform(random_, -1.0, 1.0)};
    for (long k = 0; k < samples_; ++k) {
      const double t = Time(k);
      while (t >= t1) {
        from = to;
        to = {Throttle(), Uniform(random_, -1.0, 1.0)};
        t0 = t1;
        t1 += Uniform(random_, 4.0, 12.0);
      }
      const double f = (t - t0) / (t1 - t0);
      plan[k] = {from[0] + f * (to[0] - from[0]), from[1] + f * (to[1] - from[1])};
    }
    return plan;
  }

  const CampaignOptions& o_;
  Random& random_;
  long samples_;
};

}  // namespace

bool CampaignOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    *error = "campaign: " + message;
    return false;
  };
  long count = 0;
  if (!(step > 0.0) || !(sample_period > 0.0) || !IntegerMultiple(sample_period, step, &count)) {
    return fail("sample_period must be a positive integer multiple of step (> 0)");
  }
  if (!(throttle_step > 0.0 && throttle_step <= 1.0) ||
      !IntegerMultiple(1.0, throttle_step, &count)) {
    return fail("1 / throttle_step must be a positive integer");
  }
  if (!(rudder_step > 0.0 && rudder_step <= 1.0) || !IntegerMultiple(1.0, rudder_step, &count)) {
    return fail("1 / rudder_step must be a positive integer");
  }
  for (double r : rudder_settings) {
    if (!(r >= -1.0 && r <= 1.0)) return fail("rudder_settings must lie in [-1, 1]");
  }
  for (double m : throttle_settings) {
    if (!(m >= 0.0 && m <= 1.0)) return fail("throttle_settings must lie in [0, 1]");
  }
  if (!(min_settle >= 0.0 && max_settle >= min_settle)) {
    return fail("need 0 <= min_settle <= max_settle");
  }
  if (!(settle_window >= 0.0 && settle_acceleration > 0.0 && settle_yaw_acceleration > 0.0)) {
    return fail("settle_window must be non-negative and the settle accelerations positive");
  }
  if (!(min_steady >= 0.0 && max_steady >= min_steady)) {
    return fail("need 0 <= min_steady <= max_steady");
  }
  if (validation_runs < 0 || !(validation_duration > 0.0)) {
    return fail("validation_runs must be non-negative and validation_duration positive");
  }
  if (!(validation_throttle_min >= 0.0 && validation_throttle_max >= validation_throttle_min &&
        validation_throttle_max <= 1.0)) {
    return fail("need 0 <= validation_throttle_min <= validation_throttle_max <= 1");
  }
  if (!(current_speed >= 0.0 && wind_speed >= 0.0 && gust_sd >= 0.0) ||
      !std::isfinite(current_direction) || !std::isfinite(wind_direction)) {
    return fail("current and wind speeds and gust_sd must be non-negative, directions finite");
  }
  if (!(gust_time_constant > 0.0)) return fail("gust_time_constant must be positive");
  if (!(warm_up >= 0.0 && run_gap >= sample_period)) {
    return fail("warm_up must be non-negative and run_gap at least sample_period");
  }
  if (!(position_noise >= 0.0 && course_noise >= 0.0 && sog_noise >= 0.0 && rot_noise >= 0.0)) {
    return fail("noise must be non-negative");
  }
  return true;
}

bool SimulateStepCampaign(const CraftParameters& parameters, const CampaignOptions& options,
                          Trajectory* out, std::string* error) {
  if (!options.IsValid(error)) return false;
  if (options.rudder_settings.empty() && options.throttle_settings.empty()) {
    *error = "campaign: rudder_settings and throttle_settings are both empty";
    return false;
  }
  Voyage voyage(parameters, options, 0);
  const std::vector<double> throttle_levels = UpAndDown(options.throttle_step);
  const std::vector<double> rudder_levels = UpAndDown(options.rudder_step);
  auto run = [&](const std::vector<Command>& levels) {
    if (!voyage.StartRun(levels.front(), error)) return false;
    for (const Command& command : levels) {
      if (!voyage.Level(command, error)) return false;
    }
    voyage.EndRun();
    return true;
  };
  for (double rudder : options.rudder_settings) {
    std::vector<Command> levels;
    for (double throttle : throttle_levels) levels.push_back({throttle, rudder});
    if (!run(levels)) return false;
  }
  for (double throttle : options.throttle_settings) {
    std::vector<Command> levels;
    for (double rudder : rudder_levels) levels.push_back({throttle, rudder});
    if (!run(levels)) return false;
  }
  *out = voyage.Release();
  out->source = "eriksen2dof step campaign, seed " + std::to_string(options.seed);
  return true;
}

bool SimulateValidationRuns(const CraftParameters& parameters, const CampaignOptions& options,
                            Trajectory* out, std::string* error) {
  if (!options.IsValid(error)) return false;
  if (options.validation_runs < 1) {
    *error = "campaign: validation_runs is 0";
    return false;
  }
  Voyage voyage(parameters, options, kStreams);
  std::seed_seq plan_seed{options.seed, unsigned(kStreams + kPlanStream)};
  Random random(plan_seed);
  ValidationPlan planner(options, &random);
  for (int i = 0; i < options.validation_runs; ++i) {
    const std::vector<Command> plan = planner.Make(i);
    if (!voyage.StartRun(plan.front(), error)) return false;
    for (const Command& command : plan) {
      if (!voyage.Sample(command, error)) return false;
    }
    voyage.EndRun();
  }
  *out = voyage.Release();
  out->source = "eriksen2dof validation runs, seed " + std::to_string(options.seed);
  return true;
}

}  // namespace vesselid::eriksen2dof
