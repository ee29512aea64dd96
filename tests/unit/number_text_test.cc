// The number syntax shared by the CSV and YAML readers (engine/base/number_text.h).
#include "engine/base/number_text.h"

#include <cmath>
#include <limits>

#include "engine/config/yaml_reader.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace number_text_test {

bool Parses(const char* text, double expected) {
  double value = -7.0;
  return ParseFiniteNumber(text, &value) && value == expected;
}

bool Rejects(const char* text) {
  double value = -7.0;
  return !ParseFiniteNumber(text, &value) && value == -7.0;  // and leaves *value alone
}

TEST(NumberText, DecimalAndExponentFormsWithOneOptionalSign) {
  EXPECT_TRUE(Parses("0", 0.0));
  EXPECT_TRUE(Parses("-2.5", -2.5));
  EXPECT_TRUE(Parses("+2.5", 2.5));
  EXPECT_TRUE(Parses(".5", 0.5));
  EXPECT_TRUE(Parses("1.", 1.0));
  EXPECT_TRUE(Parses("1e3", 1000.0));
  EXPECT_TRUE(Parses("-1.5E-2", -0.015));
  EXPECT_TRUE(Parses("1.7976931348623157e308", std::numeric_limits<double>::max()));
}

TEST(NumberText, SubnormalValuesAreNumbers) {
  EXPECT_TRUE(Parses("4.9e-324", std::numeric_limits<double>::denorm_min()));
  EXPECT_TRUE(Parses("-2.2250738585072e-310", -2.2250738585072e-310));
}

// A value below the smallest subnormal reads as the nearest double, zero of its sign; one
// beyond the largest double is not a finite number (1e-999 was refused as "not finite").
TEST(NumberText, UnderflowIsZeroOverflowIsNotANumber) {
  for (const char* text : {"1e-999", "+1e-999", "0.000001e-330", "123e-400", "2e-325",
                           "1e-99999999999999999999"}) {
    double value = -7.0;
    EXPECT_TRUE(ParseFiniteNumber(text, &value) && value == 0.0 && !std::signbit(value)) << text;
  }
  double value = 7.0;
  EXPECT_TRUE(ParseFiniteNumber("-1e-999", &value) && value == 0.0 && std::signbit(value));
  for (const char* text : {"1e999", "-1e999", "1000e306", "0.0001e313", "1e99999999999999999999",
                           "1e-999x", "1e-"}) {
    EXPECT_TRUE(Rejects(text)) << "'" << text << "'";
  }
}

TEST(NumberText, RejectsWhatIsNotOneFiniteNumber) {
  for (const char* text : {"", "+", "-", "+-1", "-+1", "++1", "1e", "1e400", "-1e400", "nan",
                           "inf", "-inf", "0x10", " 1", "1 ", "1,5", "1.5.2", "one"}) {
    EXPECT_TRUE(Rejects(text)) << "'" << text << "'";
  }
}

TEST(NumberText, YamlReaderUsesTheSameSyntaxAndAllowsInfiniteBounds) {
  const YamlReader reader("config.yaml");
  EXPECT_EQ(reader.Double(YAML::Load("4.9e-324"), "k"), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(reader.Double(YAML::Load("+3"), "k"), 3.0);
  EXPECT_EQ(reader.Double(YAML::Load(".inf"), "k"), INFINITY);
  EXPECT_EQ(reader.Double(YAML::Load("-inf"), "k"), -INFINITY);
  try {
    reader.Double(YAML::Load("+-1"), "stages[0].start");
    ADD_FAILURE() << "'+-1' was accepted";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "config.yaml:1: stages[0].start: '+-1' is not a finite number");
  }
}

}  // namespace number_text_test
}  // namespace vesselid
