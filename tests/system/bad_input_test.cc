// Bad input through the command line: each case gets a message naming the file, line and
// key, a non-zero exit status, and no results file.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "engine/data/trajectory.h"
#include "gtest/gtest.h"
#include "tests/support/bad_input_fixture.h"

namespace vesselid {
namespace bad_input_test {

namespace fs = std::filesystem;
using testing::BadInput;
using testing::kGoodConfig;
using testing::Outcome;

TEST_F(BadInput, GoodConfigRuns) {
  Outcome outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "results.json"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "traces" / "fit.run.csv"));
}

TEST_F(BadInput, MissingDataFile) {
  EditConfig("file: data.csv", "file: nowhere.csv");
  ExpectRejected("nowhere\\.csv: cannot open file");
}

TEST_F(BadInput, MissingColumn) {
  EditConfig("outputs: {psi: psi}", "outputs: {psi: heading}");
  ExpectRejected("experiment 'run'.*no column 'heading' for output 'psi'");
}

TEST_F(BadInput, FilePatternWithoutMatch) {
  EditConfig("name: run\n    file: data.csv", "files: \"zz_*.csv\"");
  ExpectRejected("config\\.yaml:3: experiments\\[0\\]\\.files: no file matches 'zz_\\*\\.csv' in ");
}

TEST_F(BadInput, UnknownParameter) {
  EditConfig("      K: {", "      K9: {");
  ExpectRejected(
      "config\\.yaml:11: stages\\[0\\]\\.parameters\\.K9: unknown key \\(allowed: T, K, "
      "delta_0\\)");
}

TEST_F(BadInput, UnknownModelType) {
  EditConfig("type: first_order", "type: third_order");
  ExpectRejected("config\\.yaml:1: model\\.type: unknown Nomoto model 'third_order'");
}

TEST_F(BadInput, UnknownModelFamily) {
  EditConfig("family: nomoto", "family: submarine");
  ExpectRejected("config\\.yaml:1: model\\.family: unknown model family 'submarine'");
}

TEST_F(BadInput, InvertedBounds) {
  EditConfig("lower: 0.1, upper: 50.0", "lower: 50.0, upper: 0.1");
  ExpectRejected("config\\.yaml:10: stages\\[0\\]\\.parameters\\.T: .*bounds inverted");
}

TEST_F(BadInput, StartOutsideBounds) {
  EditConfig("start: 3.0", "start: 80.0");
  ExpectRejected("config\\.yaml:10: stages\\[0\\]\\.parameters\\.T: .*start 80 outside bounds");
}

TEST_F(BadInput, NonIncreasingTime) {
  EditDataLine(5, "0.1,0,0,0,0,0,0,0");
  ExpectRejected("data\\.csv:5: time 0\\.1 is not after the previous time");
}

TEST_F(BadInput, NanInData) {
  EditConfig("file: data.csv", "file: data.csv\n    bad_cells: 0");
  EditDataLine(7, "0.5,0,0,0,nan,0,0,0");
  ExpectRejected("data\\.csv:7: column 'psi': 'nan' is not a finite number");
}

TEST_F(BadInput, TextInData) {
  EditConfig("file: data.csv", "file: data.csv\n    bad_cells: 0");
  EditDataLine(7, "0.5,0,0,0,abc,0,0,0");
  ExpectRejected("data\\.csv:7: column 'psi': 'abc' is not a finite number");
}

// Past the experiment's bad_cells share (default 5 %) the file is refused at the first one,
// with the count and the key.
TEST_F(BadInput, MangledCellsAboveTheShareAreRefused) {
  for (int line = 10; line < 10 + 40; ++line) EditDataLine(line, "x,0,0,0,jan.68,0,0,0");
  // The time is mangled too on those lines: refused at the first, whatever the share.
  ExpectRejected("data\\.csv:10: column 't': 'x' is not a finite number");
  std::ifstream in(dir_ / "data.csv");
  std::string all, row;
  for (int n = 1; std::getline(in, row); ++n) {
    if (n >= 10 && n < 50) row = std::to_string(0.1 * (n - 2)) + ",0,0,0,jan.68,0,0,0";
    all += row + "\n";
  }
  in.close();
  std::ofstream(dir_ / "data.csv") << all;
  ExpectRejected("data\\.csv:10: column 'psi': 'jan\\.68' is not a finite number \\(40 of the "
                 "column's 601 cells are not numbers, more than the 5 % an experiment's "
                 "bad_cells accepts\\)");
}

TEST_F(BadInput, WrongFieldCount) {
  EditDataLine(3, "0.2,0,0");
  ExpectRejected("data\\.csv:3: expected 8 fields, found 3");
}

TEST_F(BadInput, UnknownYamlKey) {
  EditConfig("    free_initial_states", "    free_initial_state");
  ExpectRejected("config\\.yaml:12: stages\\[0\\]\\.free_initial_state: unknown key");
}

TEST_F(BadInput, UnknownTopLevelKey) {
  WriteConfig(std::string(kGoodConfig) + "stagez: []\n");
  ExpectRejected("config\\.yaml:13: stagez: unknown key");
}

TEST_F(BadInput, YamlSyntaxError) {
  WriteConfig(std::string(kGoodConfig) + "  - name: [unclosed\n");
  ExpectRejected("config\\.yaml:1[34]: YAML syntax error");
}

TEST_F(BadInput, NotANumber) {
  EditConfig("start: 3.0", "start: three");
  ExpectRejected(
      "config\\.yaml:10: stages\\[0\\]\\.parameters\\.T\\.start: 'three' is not a finite number");
}

TEST_F(BadInput, UnknownInterpolation) {
  EditConfig("inputs: {delta: delta}", "inputs: {delta: delta}\n    interpolation: quintic");
  ExpectRejected(
      "config\\.yaml:6: experiments\\[0\\]\\.interpolation: unknown interpolation 'quintic'");
}

TEST_F(BadInput, ContinuationNotIncreasing) {
  EditConfig("    free_initial_states: [psi]", "    free_initial_states: [psi]\n    continuation: [10, 5]");
  ExpectRejected("config\\.yaml:13: stages\\[0\\]\\.continuation\\[1\\]: segment lengths must be > "
                 "0 and increasing");
}

TEST_F(BadInput, UnknownFusionRule) {
  WriteConfig(std::string(kGoodConfig) + "fusion: median\n");
  ExpectRejected("config\\.yaml:13: fusion: unknown rule 'median' \\(inverse_variance, mean, "
                 "information\\)");
}

TEST_F(BadInput, UnknownStateInFinalValidation) {
  WriteConfig(std::string(kGoodConfig) +
              "final_validation: {experiments: [run], free_initial_states: [heading]}\n");
  ExpectRejected("config\\.yaml:13: final_validation\\.free_initial_states: unknown state "
                 "'heading'");
}

TEST_F(BadInput, DivergentSimulationFailsCleanly) {
  // Norrbin with a negative cubic term grows without bound from this start.
  std::string text = kGoodConfig;
  text.replace(text.find("first_order"), 11, "norrbin");
  text.replace(text.find("    free_initial_states"), 0,
               "      alpha: {start: -1.0e6, lower: -1.0e7, upper: 0.0}\n");
  WriteConfig(text);
  ExpectRejected("stage 'fit': .*diverges");
}

}  // namespace bad_input_test
}  // namespace vesselid

namespace vesselid {
namespace bad_input_test {

// A least-squares stage in front of the good config's output-error stage.
const char* kLeastSquaresStage = R"(stages:
  - name: regression
    type: least_squares
    least_squares: {robust: true}
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 50.0}
      K: {start: -0.1, lower: -1.0, upper: -0.001}
  - name: fit)";

TEST_F(BadInput, LeastSquaresStageStartsTheNext) {
  EditConfig("stages:\n  - name: fit", kLeastSquaresStage);
  Outcome outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
  std::ifstream in(dir_ / "out" / "report.txt");
  const std::string report((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("equation r'"), std::string::npos) << report;
}

TEST_F(BadInput, UnknownStageType) {
  EditConfig("  - name: fit\n", "  - name: fit\n    type: least_square\n");
  ExpectRejected("config\\.yaml:\\d+: stages\\[0\\]\\.type: unknown stage type 'least_square'");
}

TEST_F(BadInput, LeastSquaresStageNeedsAnEquationErrorForm) {
  EditConfig("type: first_order}", "type: second_order}");
  std::string text;
  {
    std::ifstream in(dir_ / "config.yaml");
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  text.replace(text.find("  - name: fit\n"), 14, "  - name: fit\n    type: least_squares\n");
  text.replace(text.find("      T: {"), 10, "      T1: {");
  WriteConfig(text);
  ExpectRejected("stages\\[0\\]\\.type: model nomoto_second_order has no equation-error form");
}

TEST_F(BadInput, UnknownRegion) {
  EditConfig("stages:\n  - name: fit", std::string(kLeastSquaresStage));
  std::ifstream in(dir_ / "config.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  text.replace(text.find("{robust: true}"), 14, "{regions: {r: [ff]}}");
  WriteConfig(text);
  ExpectRejected("stages\\[0\\]\\.least_squares\\.regions\\.r\\[0\\]: unknown region 'ff' \\(all\\)");
}

TEST_F(BadInput, MissingSegmentColumn) {
  EditConfig("    outputs: {psi: psi}\n", "    outputs: {psi: psi}\n    segments: {column: leg}\n");
  ExpectRejected("experiment 'run'.*no segment column 'leg'");
}

TEST_F(BadInput, StepRegressionNeedsADampingInertiaForm) {
  EditConfig("  - name: fit\n", "  - name: fit\n    type: step_regression\n");
  ExpectRejected("config\\.yaml:9: stages\\[0\\]\\.type: model nomoto_first_order has no "
                 "damping-inertia form");
}

TEST_F(BadInput, UnknownInputInInputRange) {
  EditConfig("    outputs: {psi: psi}\n",
             "    outputs: {psi: psi}\n    input_range: {rudder: [-0.1, 0.1]}\n");
  ExpectRejected("config\\.yaml:7: experiments\\[0\\]\\.input_range\\.rudder: unknown key");
}

TEST_F(BadInput, InvertedInputRange) {
  EditConfig("    outputs: {psi: psi}\n",
             "    outputs: {psi: psi}\n    input_range: {delta: [0.1, -0.1]}\n");
  ExpectRejected("experiments\\[0\\]\\.input_range\\.delta: expected \\[lower, upper\\]");
}

TEST_F(BadInput, SurfacesNeedADampingInertiaForm) {
  WriteConfig(std::string(kGoodConfig) + "surfaces: {U: [0, 18, 10], r: [-1, 1, 5]}\n");
  ExpectRejected("config\\.yaml:13: surfaces: model nomoto_first_order has no damping and "
                 "inertia terms");
}

TEST_F(BadInput, InitialStateOfASegmentedRecord) {
  EditConfig("    outputs: {psi: psi}\n",
             "    outputs: {psi: psi}\n    segments: {column: t}\n    initial_state: {psi: 0}\n");
  ExpectRejected(
      "config\\.yaml:8: experiments\\[0\\]\\.initial_state: cannot be combined with "
      "'segments'");
}

TEST_F(BadInput, WrapOfAnOutputThatIsNotAnAngle) {
  EditConfig("    outputs: {psi: psi}\n", "    outputs: {psi: psi}\n    wrap: [r]\n");
  ExpectRejected("experiments\\[0\\]\\.wrap\\[0\\]: output 'r' is not an angle");
}

TEST_F(BadInput, UnknownFinalChoice) {
  WriteConfig(std::string(kGoodConfig) + "final: best\n");
  ExpectRejected("config\\.yaml:13: final: unknown choice 'best' \\(best_validation, last\\)");
}

// A heading that jumps by more than the sampling can resolve cannot be unwrapped.
TEST_F(BadInput, HeadingJumpTooLargeToUnwrap) {
  EditDataLine(30, "");
  std::ifstream in(dir_ / "data.csv");
  std::string header, row, all;
  std::getline(in, header);
  all = header + "\n";
  const int psi = [&] {
    std::stringstream names(header);
    std::string name;
    for (int i = 0; std::getline(names, name, ','); ++i) {
      if (name == "psi") return i;
    }
    return -1;
  }();
  ASSERT_GE(psi, 0);
  for (int n = 2; std::getline(in, row); ++n) {
    if (row.empty()) continue;
    if (n >= 30) {  // from here on the heading is 2 rad further round
      std::stringstream fields(row);
      std::string field, out;
      for (int i = 0; std::getline(fields, field, ','); ++i) {
        if (i == psi) field = std::to_string(std::stod(field) + 2.0);
        out += (i > 0 ? "," : "") + field;
      }
      row = out;
    }
    all += row + "\n";
  }
  in.close();
  std::ofstream(dir_ / "data.csv") << all;
  ExpectRejected(
      "angle output 'psi' \\(column 'psi'\\) changes by 115 deg between t = .*"
      "list 'psi' in the experiment's wrap:");
}

}  // namespace bad_input_test
}  // namespace vesselid
