// Bad input to the steering models for course-unstable ships and their speed input, through
// the command line: a message naming the file, line and key (config) or the experiment,
// column and time (data), a non-zero exit and no results file.
#include <string>

#include "gtest/gtest.h"
#include "tests/support/bad_input_fixture.h"

namespace vesselid {
namespace bad_input_steering_test {

using testing::BadInput;

// The fixture's record with a speed column U = 5 m/s (one sample `bad` at row `row`), and a
// config identifying it in the n1-form with a length.
class BadSpeedInput : public BadInput {
 protected:
  void AddSpeed(int row, const std::string& bad) {
    std::ifstream in(dir_ / "data.csv");
    std::string all, line;
    for (int n = 1; std::getline(in, line); ++n) {
      all += line + "," + (n == 1 ? "U" : n == row ? bad : "5") + "\n";
    }
    std::ofstream(dir_ / "data.csv") << all;
  }
  static std::string Config(const std::string& model, const std::string& inputs) {
    return "model: " + model + R"(
experiments:
  - name: run
    file: data.csv
    inputs: )" +
           inputs + R"(
    outputs: {psi: psi}
stages:
  - name: fit
    parameters:
      T_nd: {start: 0.5, role: fixed}
      K_nd: {start: -0.5, lower: -5, upper: -0.01}
      n1: {start: 0.5, lower: -5, upper: 5}
    free_initial_states: [psi]
)";
  }
};

TEST_F(BadSpeedInput, GoodConfigRuns) {
  AddSpeed(0, "");
  WriteConfig(Config("{family: nomoto, type: first_order_n1, length: 20}", "{delta: delta, U: U}"));
  const testing::Outcome outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
}

TEST_F(BadSpeedInput, SpeedNotMapped) {
  AddSpeed(0, "");
  WriteConfig(Config("{family: nomoto, type: first_order_n1, length: 20}", "{delta: delta}"));
  ExpectRejected("experiment 'run'.*input 'U' is not mapped to a column");
}

TEST_F(BadSpeedInput, ZeroSpeedInTheData) {
  AddSpeed(42, "0");
  WriteConfig(Config("{family: nomoto, type: first_order_n1, length: 20}", "{delta: delta, U: U}"));
  ExpectRejected(
      "experiment 'run' \\(.*data\\.csv\\): input 'U' \\(column 'U'\\) is 0 at "
      "t = 4 s: the model needs it > 0");
}

TEST_F(BadSpeedInput, LengthNotPositive) {
  WriteConfig(
      Config("{family: nomoto, type: first_order_n1, length: -20}", "{delta: delta, U: U}"));
  ExpectRejected("config\\.yaml:1: model\\.length: must be > 0");
}

TEST_F(BadSpeedInput, LengthOfAModelWithoutSpeed) {
  WriteConfig(Config("{family: nomoto, type: second_order_rates, length: 20}", "{delta: delta}"));
  ExpectRejected("config\\.yaml:1: model\\.length: only the n1-form models");
}

}  // namespace bad_input_steering_test
}  // namespace vesselid
