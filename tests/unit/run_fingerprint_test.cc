// The checkpoint's fingerprint tells a resumed run whether its config and data are the ones
// the checkpoint came from: any changed byte, a moved line, an appended row or data swapped
// between experiments is a different fingerprint; the same bytes are the same one.
#include <algorithm>
#include <string>

#include "engine/base/content_hash.h"
#include "engine/output/checkpoint.h"
#include "gtest/gtest.h"
#include "tests/support/temp_file.h"

namespace vesselid {
namespace run_fingerprint_test {

using testing::WriteTemp;

// A logged record several hash stripes and read blocks long.
std::string Log(int rows, double bias) {
  std::string text = "t,delta,psi\n";
  for (int k = 0; k < rows; ++k) {
    text += std::to_string(k) + "," + std::to_string(bias + 0.01 * (k % 17)) + "," +
            std::to_string(0.5 * k) + "\n";
  }
  return text;
}

std::string Fingerprint(const RunConfig& config) {
  std::string fingerprint, error;
  EXPECT_TRUE(RunFingerprint(config, &fingerprint, &error)) << error;
  return fingerprint;
}

TEST(RunFingerprint, ChangesWithEveryChangeOfTheData) {
  const std::string a = Log(30000, 0.25), b = Log(20000, -0.5);
  RunConfig config;
  config.path = WriteTemp("vesselid_fingerprint.yaml", "model: {family: nomoto}\n");
  ExperimentSpec first, second;
  first.name = "a";
  first.file = WriteTemp("vesselid_fingerprint_a.csv", a);
  second.name = "b";
  second.file = WriteTemp("vesselid_fingerprint_b.csv", b);
  config.experiments = {first, second};
  const std::string original = Fingerprint(config);
  EXPECT_EQ(original.size(), 16u);
  EXPECT_EQ(Fingerprint(config), original);

  auto with_a = [&](const std::string& text) {
    WriteTemp("vesselid_fingerprint_a.csv", text);
    return Fingerprint(config);
  };
  std::string edited = a;
  edited[edited.size() / 2] = edited[edited.size() / 2] == '1' ? '2' : '1';  // one digit
  EXPECT_NE(with_a(edited), original);
  edited = a;
  edited[8] ^= 0x80;  // one high bit, and the same bit one word later
  edited[16] ^= 0x80;
  EXPECT_NE(with_a(edited), original);
  const size_t line = a.find('\n', 1000) + 1, next = a.find('\n', line) + 1;
  edited = a;  // two lines swapped
  std::rotate(edited.begin() + line, edited.begin() + next,
              edited.begin() + a.find('\n', next) + 1);
  EXPECT_NE(with_a(edited), original);
  EXPECT_NE(with_a(a + "30000,0.25,15000\n"), original);   // a row appended
  EXPECT_NE(with_a(a.substr(0, a.size() - 1)), original);  // the last newline removed
  EXPECT_EQ(with_a(a), original);                          // the same bytes again

  // The data of the two experiments swapped, or one experiment renamed.
  WriteTemp("vesselid_fingerprint_a.csv", b);
  WriteTemp("vesselid_fingerprint_b.csv", a);
  EXPECT_NE(Fingerprint(config), original);
  WriteTemp("vesselid_fingerprint_a.csv", a);
  WriteTemp("vesselid_fingerprint_b.csv", b);
  config.experiments[1].name = "c";
  EXPECT_NE(Fingerprint(config), original);
}

TEST(ContentHash, DoesNotDependOnHowTheStreamIsCut) {
  const std::string text = Log(500, 1.0);
  ContentHash whole;
  whole.Add(text);
  for (size_t piece : {1, 5, 31, 32, 33, 1000}) {
    ContentHash cut;
    for (size_t at = 0; at < text.size(); at += piece) cut.Add(text.substr(at, piece));
    EXPECT_EQ(cut.Digest(), whole.Digest()) << piece;
  }
  ContentHash shorter;
  shorter.Add(text.data(), text.size() - 1);
  EXPECT_NE(shorter.Digest(), whole.Digest());
}

}  // namespace run_fingerprint_test
}  // namespace vesselid
