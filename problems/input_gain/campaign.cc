#include "problems/input_gain/campaign.h"

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "engine/base/nan.h"
#include "engine/model/rk4.h"

namespace vesselid::input_gain {
namespace {

using Random = std::mt19937;

enum class Manoeuvre {
  kForwardConstant,
  kForwardVarying,
  kZigzag,
  kCircleConstant,
  kCircleVarying
};

// Share of each type, in Manoeuvre order: forward 35 %, zigzag 15 %, circles 50 %.
const double kShares[] = {0.175, 0.175, 0.15, 0.25, 0.25};

// Output columns after t.
enum Column { kSegment, kNorth, kEast, kHeading, kPwmL, kPwmR, kUTrue, kVTrue, kRTrue, kColumns };
const char* const kColumnNames[] = {"segment", "n",      "e",      "heading", "pwm_L",
                                    "pwm_R",   "u_true", "v_true", "r_true"};

double Uniform(Random& random, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(random);
}

double Sign(Random& random) { return Uniform(random, 0.0, 1.0) < 0.5 ? -1.0 : 1.0; }

bool Coin(Random& random) { return Uniform(random, 0.0, 1.0) < 0.5; }

// One joystick axis over segment time: piecewise linear through knots (a repeated knot time
// is a step) plus sum_i amplitude_i sin(2 pi t / period_i + phase_i).
struct Profile {
  std::vector<double> t, value;
  double amplitude[2] = {0.0, 0.0}, period[2] = {1.0, 1.0}, phase[2] = {0.0, 0.0};

  double operator()(double time) const {
    double y = Knots(time);
    for (int i = 0; i < 2; ++i) {
      y += amplitude[i] * std::sin(2.0 * M_PI * time / period[i] + phase[i]);
    }
    return y;
  }

  // Linear interpolation between the knots around `time`, held beyond the ends.
  double Knots(double time) const {
    const size_t k = std::upper_bound(t.begin(), t.end(), time) - t.begin();  // first knot > time
    if (k == 0) return value.front();
    if (k == t.size()) return value.back();
    return value[k - 1] + (value[k] - value[k - 1]) * (time - t[k - 1]) / (t[k] - t[k - 1]);
  }
};

Profile Ramp(double duration, double from, double to) {
  Profile p;
  p.t = {0.0, duration};
  p.value = {from, to};
  return p;
}

Profile Constant(double value) { return Ramp(1.0, value, value); }

// Slow steering corrections: bias + two sinusoids, |u_d| <= 0.01 + 2 x 0.015 = 0.04.
Profile Wander(Random& random) {
  Profile p = Constant(Uniform(random, -0.01, 0.01));
  for (int i = 0; i < 2; ++i) {
    p.amplitude[i] = Uniform(random, 0.0, 0.015);
    p.period[i] = Uniform(random, 8.0, 30.0);
    p.phase[i] = Uniform(random, 0.0, 2.0 * M_PI);
  }
  return p;
}

// Speed held 3-8 s, then stepped or ramped (over 2-8 s) to a new level in [0.2, 1.0].
Profile SpeedSteps(Random& random, double duration) {
  Profile p;
  double time = 0.0, level = Uniform(random, 0.2, 1.0);
  p.t.push_back(time);
  p.value.push_back(level);
  while (time < duration) {
    time += Uniform(random, 3.0, 8.0);
    p.t.push_back(time);
    p.value.push_back(level);
    level = Uniform(random, 0.2, 1.0);
    if (Coin(random)) time += Uniform(random, 2.0, 8.0);
    p.t.push_back(time);
    p.value.push_back(level);
  }
  return p;
}

// u_m = lo + (hi - lo) s^2, s uniform: low means dominate so that the inner propeller
// (u_m - |u_d| < 0) often reverses.
double CircleMean(Random& random, double lo, double hi) {
  const double s = Uniform(random, 0.0, 1.0);
  return lo + (hi - lo) * s * s;
}

// Turn rate ramped (reversing the turn one time in four) or oscillating about a mean turn,
// always within +-0.55.
Profile CircleDifference(Random& random, double duration) {
  const double sign = Sign(random);
  if (Coin(random)) {
    const double end_sign = Uniform(random, 0.0, 1.0) < 0.75 ? sign : -sign;
    return Ramp(duration, sign * Uniform(random, 0.3, 0.55), end_sign * Uniform(random, 0.3, 0.55));
  }
  const double mean = Uniform(random, 0.3, 0.4);
  Profile p = Constant(sign * mean);
  p.amplitude[0] = Uniform(random, 0.1, 0.55 - mean);
  p.period[0] = Uniform(random, 10.0, 40.0);
  p.phase[0] = Uniform(random, 0.0, 2.0 * M_PI);
  return p;
}

struct Segment {
  Manoeuvre type = Manoeuvre::kForwardConstant;
  long begin = 0, end = 0;      // logged RK4 steps [begin, end)
  Profile mean, difference;     // u_m, u_d (zigzag: u_d's initial value, switched in flight)
  double zigzag_heading = 0.0;  // rad
};

// Segment types in random order, type i on round(count x cumulative share) - (previous)
// segments, so the shares hold for every seed rather than on average.
std::vector<Manoeuvre> ShuffledTypes(int count, Random& random) {
  std::vector<Manoeuvre> types;
  double cumulative = 0.0;
  for (int i = 0; i < 5; ++i) {
    cumulative += kShares[i];
    const long last = i == 4 ? count : std::lround(cumulative * count);
    while (static_cast<long>(types.size()) < last) types.push_back(static_cast<Manoeuvre>(i));
  }
  std::shuffle(types.begin(), types.end(), random);
  return types;
}

// Operator commands of one segment of the given type and duration.
void PlanCommands(double duration, Random& random, Segment* s) {
  switch (s->type) {
    case Manoeuvre::kForwardConstant:
      s->mean = Constant(Uniform(random, 0.3, 0.9));
      s->difference = Wander(random);
      break;
    case Manoeuvre::kForwardVarying:
      s->mean = SpeedSteps(random, duration);
      s->difference = Wander(random);
      break;
    case Manoeuvre::kZigzag:
      s->mean = Constant(Uniform(random, 0.4, 0.8));
      s->difference = Constant(Sign(random) * Uniform(random, 0.15, 0.3));
      s->zigzag_heading = Uniform(random, 15.0, 25.0) * M_PI / 180.0;
      break;
    case Manoeuvre::kCircleConstant:
      s->mean = Constant(CircleMean(random, 0.15, 0.5));
      s->difference = Constant(Sign(random) * Uniform(random, 0.25, 0.55));
      break;
    case Manoeuvre::kCircleVarying: {
      const double from = CircleMean(random, 0.15, 0.6);
      s->mean = Coin(random) ? Constant(from) : Ramp(duration, from, CircleMean(random, 0.15, 0.6));
      s->difference = CircleDifference(random, duration);
      break;
    }
  }
}

// Durations d_i = clamp(w_i + c, lo, hi), w_i uniform in [lo, hi]; sum_i d_i is monotone in
// the shift c, which bisection sets so that the durations add up to total_duration.
std::vector<double> Durations(const CampaignOptions& o, Random& random) {
  std::vector<double> w(o.segments), d(o.segments);
  for (double& wi : w) wi = Uniform(random, o.min_segment, o.max_segment);
  double lo = o.min_segment - o.max_segment, hi = -lo;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double c = 0.5 * (lo + hi);
    double sum = 0.0;
    for (int i = 0; i < o.segments; ++i) {
      d[i] = std::clamp(w[i] + c, o.min_segment, o.max_segment);
      sum += d[i];
    }
    (sum < o.total_duration ? lo : hi) = c;
  }
  return d;
}

// Segment i is logged over steps [begin, end), after i + 1 gaps; boundaries are rounded
// cumulative sums so that the logged total matches total_duration to one step.
std::vector<Segment> PlanSegments(const CampaignOptions& o, Random& random) {
  const std::vector<double> durations = Durations(o, random);
  const std::vector<Manoeuvre> types = ShuffledTypes(o.segments, random);
  const long gap = std::lround(o.gap / o.step);
  std::vector<Segment> segments(o.segments);
  double logged = 0.0;
  for (int i = 0; i < o.segments; ++i) {
    Segment& s = segments[i];
    s.begin = (i + 1) * gap + std::lround(logged / o.step);
    logged += durations[i];
    s.end = (i + 1) * gap + std::lround(logged / o.step);
    s.type = types[i];
    PlanCommands(durations[i], random, &s);
  }
  return segments;
}

// True when value = count x step for an integer count >= 0 (within rounding).
bool MultipleOfStep(double value, double step, long* count) {
  *count = std::lround(value / step);
  return *count >= 0 && std::abs(*count * step - value) <= 1e-9 * std::max(1.0, value);
}

// Sensor timing in RK4 steps: sample k is due when k = offset (mod period).
struct Clock {
  long period = 1, offset = 0;
  bool Due(long k) const { return (k - offset) % period == 0 && k >= offset; }
};

struct CatamaranRhs {
  static constexpr int kNumStates = kCatamaranStates;
  const CatamaranParameters* parameters;
  bool operator()(const double* x, const double* pwm, const double*, double* xdot) const {
    return CatamaranDerivative(*parameters, x, pwm, xdot);
  }
};

struct QuadraticUsvRhs {
  static constexpr int kNumStates = kQuadraticUsvStates;
  const QuadraticUsvParameters* parameters;
  bool operator()(const double* x, const double* pwm, const double*, double* xdot) const {
    return QuadraticUsvDerivative(*parameters, x, pwm, xdot);
  }
};

// Wraps an angle to (-pi, pi].
double WrapAngle(double angle) {
  const double wrapped = std::remainder(angle, 2.0 * M_PI);
  return wrapped <= -M_PI ? wrapped + 2.0 * M_PI : wrapped;
}

// The voyage as it runs: vessel state, joystick command held until the next PWM sample, and
// the log being written. `Rhs` is the vessel (x' of its state, n e psi u v r first).
template <class Rhs>
class Voyage {
 public:
  Voyage(const Rhs& rhs, const CampaignOptions& options) : rhs_(rhs), options_(options) {
    std::seed_seq noise_seed{options.seed, 1u};
    noise_.seed(noise_seed);
    MultipleOfStep(options.gnss_period, options.step, &gnss_.period);
    MultipleOfStep(options.gnss_offset, options.step, &gnss_.offset);
    MultipleOfStep(options.ahrs_period, options.step, &ahrs_.period);
    MultipleOfStep(options.pwm_period, options.step, &pwm_.period);
    MultipleOfStep(options.pwm_offset, options.step, &pwm_.offset);
    out_.names.assign(kColumnNames, kColumnNames + (options.truth_columns ? kColumns : kUTrue));
    out_.columns.assign(out_.names.size(), {});
  }

  // Unlogged transition up to step `end`: the command ramps linearly from the last one to
  // the segment's first, (u_m, u_d) = last + (k - k0) / (end - k0) (first - last).
  bool Transition(long end, double mean, double difference, std::string* error) {
    if (abrupt_) {  // the command stays until the segment starts: it begins mid-manoeuvre
      while (k_ < end) {
        if (!Step(error)) return false;
      }
      return true;
    }
    const long k0 = k_;
    const double mean0 = mean_, difference0 = difference_;
    while (k_ < end) {
      if (pwm_.Due(k_)) {
        const double f = double(k_ - k0) / double(end - k0);
        Command(mean0 + f * (mean - mean0), difference0 + f * (difference - difference0));
      }
      if (!Step(error)) return false;
    }
    return true;
  }

  // Unlogged lead-in up to step `end` on a held command (a planned experiment's approach).
  bool Hold(long end, double mean, double difference, std::string* error) {
    Command(mean, difference);
    while (k_ < end) {
      if (!Step(error)) return false;
    }
    return true;
  }

  // Logged segment; a zigzag flips u_d when psi - psi0 passes +-zigzag_heading in the
  // direction u_d turns (u_d > 0 turns to starboard, r > 0).
  bool Run(int id, const Segment& s, std::string* error) {
    const double psi0 = x_[kPsi];
    double sign = 1.0;
    while (k_ < s.end) {
      if (pwm_.Due(k_)) {
        const double time = (k_ - s.begin) * options_.step;
        const double d = sign * s.difference(time), turned = x_[kPsi] - psi0;
        if (s.type == Manoeuvre::kZigzag &&
            (d > 0 ? turned >= s.zigzag_heading : turned <= -s.zigzag_heading)) {
          sign = -sign;
        }
        Command(s.mean(time), sign * s.difference(time));
      }
      Log(id);
      if (!Step(error)) return false;
    }
    return true;
  }

  Trajectory Release() { return std::move(out_); }

  void SetAbrupt(bool abrupt) { abrupt_ = abrupt; }
  void SetGlitch(bool glitch) { glitch_ = glitch; }

 private:
  // u_L = clamp(u_m + u_d, -1, 1), u_R = clamp(u_m - u_d, -1, 1), held until the next sample.
  void Command(double mean, double difference) {
    mean_ = mean;
    difference_ = difference;
    const double lowest = options_.forward_only ? 0.0 : -1.0;
    pwm_value_[0] = std::clamp(mean + difference, lowest, 1.0);
    pwm_value_[1] = std::clamp(mean - difference, lowest, 1.0);
  }

  bool Step(std::string* error) {
    if (!Rk4Step<Rhs, double>(rhs_, pwm_value_, pwm_value_, pwm_value_, nullptr, options_.step,
                              x_)) {
      *error = "campaign: simulation failed at t = " + std::to_string(k_ * options_.step) + " s";
      return false;
    }
    ++k_;
    return true;
  }

  // One row at step k_ if any sensor is due; times rounded to 1e-6 s so that the CSV holds
  // them exactly. Noise is drawn for every sample, even at zero SD, to keep streams aligned.
  void Log(int id) {
    const bool gnss = gnss_.Due(k_), ahrs = ahrs_.Due(k_), pwm = pwm_.Due(k_);
    if (!gnss && !ahrs && !pwm) return;
    double row[kColumns];
    std::fill(row, row + kColumns, kNaN);
    std::normal_distribution<double> unit(0.0, 1.0);
    row[kSegment] = id;
    if (gnss) {
      row[kNorth] = x_[kN] + options_.gnss_noise * unit(noise_);
      row[kEast] = x_[kE] + options_.gnss_noise * unit(noise_);
      if (glitch_ && ++gnss_in_segment_ == 40) {  // one fix thrown off, 8 s in
        row[kNorth] += options_.defects.glitch_offset;
        row[kEast] -= 0.5 * options_.defects.glitch_offset;
      }
    }
    if (ahrs) {
      row[kHeading] = WrapAngle(x_[kPsi] + options_.heading_noise * unit(noise_));
      row[kUTrue] = x_[kU];
      row[kVTrue] = x_[kV];
      row[kRTrue] = x_[kR];
    }
    if (pwm) {
      row[kPwmL] = pwm_value_[0];
      row[kPwmR] = pwm_value_[1];
    }
    out_.t.push_back(std::round(k_ * options_.step * 1e6) / 1e6);
    for (size_t c = 0; c < out_.columns.size(); ++c) out_.columns[c].push_back(row[c]);
  }

  Rhs rhs_;
  const CampaignOptions& options_;
  Random noise_;
  Clock gnss_, ahrs_, pwm_;
  double x_[Rhs::kNumStates] = {};
  bool abrupt_ = false, glitch_ = false;
  int gnss_in_segment_ = 0;
  double mean_ = 0.0, difference_ = 0.0, pwm_value_[2] = {0.0, 0.0};
  long k_ = 0;
  Trajectory out_;
};

}  // namespace

bool CampaignOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    *error = "campaign: " + message;
    return false;
  };
  if (!(step > 0.0)) return fail("step must be positive");
  if (!planned_t.empty()) {
    if (planned_t.size() < 2 || planned_left.size() != planned_t.size() ||
        planned_right.size() != planned_t.size() || !(lead_in >= 0.0)) {
      return fail("a planned experiment needs two samples or more and lead_in >= 0");
    }
  } else if (segments < 1) {
    return fail("segments must be at least 1");
  }
  if (!(min_segment >= step && max_segment >= min_segment)) {
    return fail("need step <= min_segment <= max_segment");
  }
  if (planned_t.empty() &&
      !(total_duration >= segments * min_segment && total_duration <= segments * max_segment)) {
    return fail("total_duration must lie within segments x [min_segment, max_segment]");
  }
  if (!(gap >= 0.0)) return fail("gap must be non-negative");
  if (!(gnss_noise >= 0.0 && heading_noise >= 0.0)) return fail("noise must be non-negative");
  const struct {
    const char* name;
    double period, offset;
  } clocks[] = {{"gnss", gnss_period, gnss_offset},
                {"ahrs", ahrs_period, 0.0},
                {"pwm", pwm_period, pwm_offset}};
  for (const auto& c : clocks) {
    long n = 0, k = 0;
    if (!(c.period > 0.0) || !MultipleOfStep(c.period, step, &n) || n < 1 ||
        !MultipleOfStep(c.offset, step, &k) || k >= n) {
      return fail(std::string(c.name) + "_period must be a positive multiple of step and " +
                  c.name + " offset a multiple of step within [0, period)");
    }
  }
  return true;
}

namespace {

template <class Rhs>
bool Simulate(const Rhs& rhs, const CampaignOptions& options, const std::string& vessel,
              Trajectory* out, std::string* error) {
  if (!options.IsValid(error)) return false;
  std::seed_seq plan_seed{options.seed, 0u};
  Random random(plan_seed);
  Voyage<Rhs> voyage(rhs, options);
  if (!options.planned_t.empty()) {  // one segment, the plan: u_m, u_d through its samples
    Segment s;
    s.begin = std::lround(options.lead_in / options.step);
    s.end = s.begin +
            std::lround((options.planned_t.back() - options.planned_t.front()) / options.step) + 1;
    for (size_t k = 0; k < options.planned_t.size(); ++k) {
      const double t = options.planned_t[k] - options.planned_t.front();
      s.mean.t.push_back(t);
      s.difference.t.push_back(t);
      s.mean.value.push_back(0.5 * (options.planned_left[k] + options.planned_right[k]));
      s.difference.value.push_back(0.5 * (options.planned_left[k] - options.planned_right[k]));
    }
    if (!voyage.Hold(s.begin, s.mean(0.0), s.difference(0.0), error) || !voyage.Run(0, s, error)) {
      return false;
    }
    *out = voyage.Release();
    out->source =
        "input_gain planned experiment (" + vessel + "), seed " + std::to_string(options.seed);
    return true;
  }
  const std::vector<Segment> segments = PlanSegments(options, random);
  for (int i = 0; i < options.segments; ++i) {
    const Segment& s = segments[i];
    voyage.SetAbrupt(i == options.defects.abrupt_start_segment);
    voyage.SetGlitch(i == options.defects.glitch_segment);
    if (!voyage.Transition(s.begin, s.mean(0.0), s.difference(0.0), error) ||
        !voyage.Run(i, s, error)) {
      return false;
    }
  }
  *out = voyage.Release();
  out->source = "input_gain campaign (" + vessel + "), seed " + std::to_string(options.seed);
  return true;
}

}  // namespace

bool SimulateCampaign(const CatamaranParameters& parameters, const CampaignOptions& options,
                      Trajectory* out, std::string* error) {
  return Simulate(CatamaranRhs{&parameters}, options, "catamaran", out, error);
}

bool SimulateCampaign(const QuadraticUsvParameters& parameters, const CampaignOptions& options,
                      Trajectory* out, std::string* error) {
  return Simulate(QuadraticUsvRhs{&parameters}, options, "quadratic-thrust USV", out, error);
}

}  // namespace vesselid::input_gain
