// Measured against predicted for the zigzags a run held out (results.json `zigzags`), with a
// 95 % prediction interval: does the interval cover the measurement? In report.txt and
// report.html (zigzag sections) and `vesselid predict`.
//
// The prediction of a held-out run's overshoot is the run's simulation of that record (its
// own rudder and, where the run estimates one, its own bias). Its error on the training
// zigzags, e_i = measured_i - simulated_i over the n training runs, holds what the model
// leaves out (unmodelled dynamics, the disturbance, the compass's resolution) and the
// parameters' error as far as it shows on such runs; with mean m and standard deviation s
// the interval is
//
//   simulated + m +- t_{0.975, n-1} s sqrt(1 + 1/n)
//
// (a new run's error drawn like the training runs' ones; m is the model's bias on this
// figure). Per figure (first and second overshoot) separately, with the n training runs that
// have it; none with fewer than three.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "nlohmann/json.hpp"

namespace vesselid {

struct HeldOutZigzag {
  std::string experiment;
  std::string test;    // "10.0/10.4": rudder/heading change in degrees
  std::string figure;  // "first_overshoot", "second_overshoot"
  double measured = 0.0, predicted = 0.0, low = 0.0, high = 0.0;  // deg
  bool covered = false;
};

struct HeldOutZigzagCheck {
  std::string stage;  // whose simulations the held-out runs have
  std::vector<HeldOutZigzag> rows;
  // Per figure: training runs, their error's mean and SD (deg), the t factor; held-out runs
  // with the figure and how many of them the interval covers.
  struct Error {
    std::string figure;
    int runs = 0;
    double mean = 0.0, sd = 0.0, t = 0.0;
    int held_out = 0, covered = 0;
  };
  std::vector<Error> errors;
  std::string note;  // why there is no check (no held-out or too few training zigzags)
};

// A zigzag as results.json records it (zigzag_report.h writes it, run_document.h reads it):
// its test and overshoots in degrees, NaN where unknown.
struct ZigzagEntry {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::string stage, experiment;
  bool held_out = false;
  double rudder_deg = kNaN, heading_deg = kNaN;
  double measured_first = kNaN, measured_second = kNaN;    // first and second overshoot
  double simulated_first = kNaN, simulated_second = kNaN;
};

// The check of a run's zigzags (results.json `zigzags`, or a run's own in memory).
HeldOutZigzagCheck CheckHeldOutZigzags(const std::vector<ZigzagEntry>& zigzags);

std::string HeldOutZigzagsText(const HeldOutZigzagCheck& check);
nlohmann::json HeldOutZigzagsToJson(const HeldOutZigzagCheck& check);

}  // namespace vesselid
