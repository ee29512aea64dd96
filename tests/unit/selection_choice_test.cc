// The one-standard-error rule of structure selection (engine/select/selection_choice.h).
#include "engine/select/selection_choice.h"

#include <cmath>

#include "gtest/gtest.h"

namespace vesselid {
namespace selection_choice_test {

SelectionCandidate Candidate(const std::string& name, int complexity, double score, double se,
                             bool usable = true) {
  SelectionCandidate c;
  c.name = name;
  c.complexity = complexity;
  c.score = score;
  c.score_se = se;
  c.usable = usable;
  return c;
}

TEST(SelectionChoice, SimplerOfTwoNearEqualCandidatesIsChosen) {
  SelectionResult s;
  s.candidates = {Candidate("rich", 12, 95.0, 0.8), Candidate("plain", 4, 94.5, 1.0)};
  ChooseByOneStandardError(&s);
  EXPECT_EQ(s.best, 0);
  EXPECT_EQ(s.chosen, 1);  // 94.5 >= 95.0 - 0.8
  EXPECT_TRUE(s.candidates[0].within_one_se);
  EXPECT_TRUE(s.candidates[1].within_one_se);
  EXPECT_NE(s.reason.find("'plain'"), std::string::npos) << s.reason;
  EXPECT_NE(s.reason.find("simplest"), std::string::npos) << s.reason;
}

TEST(SelectionChoice, SimplerCandidateBeyondOneStandardErrorIsNotChosen) {
  SelectionResult s;
  s.candidates = {Candidate("plain", 4, 93.9, 0.2), Candidate("rich", 12, 95.0, 1.0)};
  ChooseByOneStandardError(&s);
  EXPECT_EQ(s.best, 1);
  EXPECT_EQ(s.chosen, 1);  // 93.9 < 95.0 - 1.0
  EXPECT_FALSE(s.candidates[0].within_one_se);
  EXPECT_NE(s.reason.find("best cross-validated score"), std::string::npos) << s.reason;
}

TEST(SelectionChoice, EqualComplexityTakesTheHigherScoreAndUnusableAreSkipped) {
  SelectionResult s;
  s.candidates = {Candidate("a", 5, 90.0, 2.0), Candidate("b", 5, 91.0, 2.0),
                  Candidate("broken", 1, std::nan(""), std::nan(""), false),
                  Candidate("c", 7, 91.5, 2.0)};
  ChooseByOneStandardError(&s);
  EXPECT_EQ(s.best, 3);
  EXPECT_EQ(s.chosen, 1);
  EXPECT_FALSE(s.candidates[2].within_one_se);
}

TEST(SelectionChoice, NoUsableCandidateChoosesNothing) {
  SelectionResult s;
  s.candidates = {Candidate("broken", 1, std::nan(""), std::nan(""), false)};
  ChooseByOneStandardError(&s);
  EXPECT_EQ(s.chosen, -1);
  EXPECT_EQ(s.reason, "no candidate could be scored");
}

}  // namespace selection_choice_test
}  // namespace vesselid
