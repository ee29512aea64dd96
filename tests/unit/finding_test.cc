// The finding catalogue (engine/base/finding.h): one entry per kind in enum order, names that
// round-trip, the verdict rule (failure > warning > info), sorting severity first and the
// line a person reads.
#include "engine/base/finding.h"

#include <set>

#include "gtest/gtest.h"

namespace vesselid {
namespace finding_test {

TEST(Finding, CatalogueHasEveryKindOnceWithARuleAndAdvice) {
  const std::vector<FindingRule>& catalogue = FindingCatalogue();
  std::set<std::string> names;
  for (size_t i = 0; i < catalogue.size(); ++i) {
    const FindingRule& rule = catalogue[i];
    EXPECT_EQ(static_cast<size_t>(rule.kind), i) << "catalogue out of enum order at " << i;
    const std::string name = FindingKindToString(rule.kind);
    EXPECT_NE(name, "?");
    EXPECT_TRUE(names.insert(name).second) << name;
    FindingKind back;
    ASSERT_TRUE(StringToFindingKind(name, &back)) << name;
    EXPECT_EQ(back, rule.kind);
    EXPECT_GT(std::string(rule.rule).size(), 40u) << name;
    EXPECT_GT(std::string(rule.advice).size(), 3u) << name;
    EXPECT_NE(FindingCatalogueMarkdown().find("| `" + name + "` | "), std::string::npos) << name;
  }
  FindingKind kind;
  EXPECT_FALSE(StringToFindingKind("no_such_kind", &kind));
  EXPECT_EQ(RuleOf(FindingKind::kFailedFit).severity, FindingSeverity::kFailure);
  EXPECT_EQ(RuleOf(FindingKind::kAtBound).severity, FindingSeverity::kWarning);
  EXPECT_EQ(RuleOf(FindingKind::kResampled).severity, FindingSeverity::kInfo);
}

TEST(Finding, VerdictIsTheWorstSeverity) {
  std::vector<Finding> findings;
  EXPECT_EQ(VerdictOf(findings), Verdict::kGood);
  findings.push_back(MakeFinding(FindingKind::kResampled, "grid"));
  EXPECT_EQ(VerdictOf(findings), Verdict::kGood);
  findings.push_back(MakeFinding(FindingKind::kAtBound, "bound"));
  EXPECT_EQ(VerdictOf(findings), Verdict::kDoubtful);
  findings.push_back(MakeFinding(FindingKind::kFailedFit, "missed"));
  EXPECT_EQ(VerdictOf(findings), Verdict::kFailed);
  EXPECT_EQ(Worse(Verdict::kGood, Verdict::kDoubtful), Verdict::kDoubtful);
  EXPECT_EQ(Worse(Verdict::kFailed, Verdict::kDoubtful), Verdict::kFailed);
  for (Verdict v : {Verdict::kGood, Verdict::kDoubtful, Verdict::kFailed}) {
    Verdict back;
    ASSERT_TRUE(StringToVerdict(VerdictToString(v), &back));
    EXPECT_EQ(back, v);
  }
  SortFindings(&findings);
  EXPECT_EQ(findings[0].kind, FindingKind::kFailedFit);
  EXPECT_EQ(findings[2].kind, FindingKind::kResampled);
}

TEST(Finding, DescriptionNamesWhereAndCounts) {
  Finding f = MakeFinding(FindingKind::kColouredResiduals, "the residuals of psi are coloured");
  f.stage = "yaw";
  f.experiment = "zz1";
  f.output = "psi";
  f.count = 41;
  EXPECT_EQ(DescribeFinding(f),
            "info [coloured_residuals] stage 'yaw', experiment 'zz1', output psi: the residuals "
            "of psi are coloured (x41)");
  f.stage = "final";
  f.experiment.clear();
  f.count = 1;
  EXPECT_EQ(DescribeFinding(f),
            "info [coloured_residuals] stage final, output psi: the residuals of psi are coloured");
}

}  // namespace finding_test
}  // namespace vesselid
