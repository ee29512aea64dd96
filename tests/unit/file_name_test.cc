// Names that become file names (engine/base/file_name.h).
#include "engine/base/file_name.h"

#include <set>
#include <string>

#include "gtest/gtest.h"

namespace vesselid {
namespace file_name_test {

TEST(FileName, KeepsPlainNamesAndEscapesTheRest) {
  EXPECT_EQ(FileNameOf("zz10s_a"), "zz10s_a");
  EXPECT_EQ(FileNameOf("run@3#2-x+y=z,w"), "run@3#2-x+y=z,w");
  EXPECT_EQ(FileNameOf("a/b"), "a%2Fb");
  EXPECT_EQ(FileNameOf("a.b c"), "a%2Eb%20c");
  EXPECT_EQ(FileNameOf("100%"), "100%25");
  EXPECT_EQ(FileNameOf("\xC3\xA6"), "%C3%A6");  // UTF-8 bytes
}

// Names that differ give file names that differ (the escape is reversible).
TEST(FileName, DistinctNamesGiveDistinctFileNames) {
  const std::set<std::string> names = {"a/b", "a_b", "a b", "a%2Fb", "a.b", "a%2Eb", "a", "a."};
  std::set<std::string> files;
  for (const std::string& name : names) files.insert(FileNameOf(name));
  EXPECT_EQ(files.size(), names.size());
}

TEST(FileName, NameProblems) {
  EXPECT_EQ(NameProblem("zz10s_a"), "");
  EXPECT_EQ(NameProblem(""), "is empty");
  EXPECT_EQ(NameProblem("a\nb"), "holds a control character (0x0a)");
  EXPECT_EQ(NameProblem(std::string(kMaxFileNameBytes, 'x')), "");
  EXPECT_NE(NameProblem(std::string(kMaxFileNameBytes + 1, 'x')), "");
  // 40 bytes that escape to 120.
  EXPECT_NE(NameProblem(std::string(40, '/')).find("(120 in a file name)"), std::string::npos);
}

}  // namespace file_name_test
}  // namespace vesselid
