// The recording scalar and the C it is written as: operations on the same operands are one
// node, constants fold as double computes them, a condition decided once keeps its outcome on
// the path, every outcome sequence is traced, and the C function computes what the traced one
// does (checked here on the text; tests/system/model_export_test.cc compiles and runs it).
#include "engine/export/traced_function.h"

#include <cmath>
#include <string>
#include <vector>

#include "engine/model/expression.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace traced_function_test {

using symbolic::Expression;
using symbolic::ExpressionOp;
using symbolic::ExpressionTape;
using symbolic::TapeScope;

Expression Variable(ExpressionTape* tape, const std::string& name) {
  return Expression::Node(tape->Variable(name));
}

TEST(Expression, SharesNodesAndFoldsConstants) {
  ExpressionTape tape;
  TapeScope scope(&tape);
  const Expression x = Variable(&tape, "x[0]");
  EXPECT_EQ((x * 2.0 + 1.0).id(), (x * 2.0 + 1.0).id());
  EXPECT_NE((x * 2.0).id(), (2.0 * x).id());  // the operand order is kept: same arithmetic
  const Expression folded = Expression(0.1) * Expression(3.0) + Expression(std::sin(0.5));
  ASSERT_TRUE(tape.IsConstant(folded.id()));
  EXPECT_EQ(tape.nodes()[folded.id()].value, 0.1 * 3.0 + std::sin(0.5));
  EXPECT_TRUE(Expression(1.0) > 0.0);  // a constant condition is no decision
  EXPECT_TRUE(tape.decisions().empty());
}

TEST(Expression, AConditionKeepsItsOutcomeOnThePath) {
  ExpressionTape tape;
  TapeScope scope(&tape);
  const Expression u = Variable(&tape, "u[0]");
  tape.BeginPath({false});
  EXPECT_FALSE(u > 0.0);
  EXPECT_FALSE(u > 0.0);  // the same node: no second decision
  EXPECT_TRUE(isnan(u));  // a new one: true beyond the script
  ASSERT_EQ(tape.decisions().size(), 2u);
  EXPECT_FALSE(tape.decisions()[0].outcome);
}

// A dead zone of three branches and a refusal, as the input-gain thrust law and the Nomoto
// time constant have them.
bool DeadZone(const Expression* x, const Expression* p, Expression* out) {
  if (!(p[0] > 0.0)) return false;
  if (x[0] > p[1]) {
    out[0] = (x[0] - p[1]) / p[0];
  } else if (x[0] < -p[1]) {
    out[0] = (x[0] + p[1]) / p[0];
  } else {
    out[0] = Expression(0.0);
  }
  out[1] = x[0] * p[0];
  return true;
}

TEST(TracedFunction, TracesEveryPathAndWritesTheDecisionsAsC) {
  ExpressionTape tape;
  TapeScope scope(&tape);
  const Expression x[1] = {Variable(&tape, "x[0]")};
  const Expression p[2] = {Variable(&tape, "p[0]"), Variable(&tape, "p[1]")};
  TracedFunction function;
  std::string error;
  ASSERT_TRUE(TraceFunction(
      &tape,
      [&](std::vector<int>* results) {
        Expression out[2];
        if (!DeadZone(x, p, out)) return false;
        *results = {out[0].id(), out[1].id()};
        return true;
      },
      100, &function, &error))
      << error;
  // Refused, and the three branches.
  ASSERT_EQ(function.paths.size(), 4u);
  int refused = 0;
  for (const TracedPath& path : function.paths) refused += path.ok ? 0 : 1;
  EXPECT_EQ(refused, 1);
  const std::string c = TracedFunctionToC(tape, function, "y", true, 1);
  EXPECT_NE(c.find("if (!(p[0] > 0.0)) return 0;"), std::string::npos) << c;
  EXPECT_NE(c.find("if (x[0] > p[1]) {"), std::string::npos) << c;
  // x * p is needed on every branch: computed once, before the dead zone's decisions.
  const size_t product = c.find("x[0] * p[0]");
  ASSERT_NE(product, std::string::npos) << c;
  EXPECT_EQ(c.find("x[0] * p[0]", product + 1), std::string::npos) << c;
  EXPECT_LT(product, c.find("if (x[0] > p[1])")) << c;
  EXPECT_NE(c.find("y[0] = 0.0;"), std::string::npos) << c;

  // Too many paths for the limit: refused with a message.
  EXPECT_FALSE(TraceFunction(
      &tape,
      [&](std::vector<int>* results) {
        Expression out[2];
        return DeadZone(x, p, out) && (results->push_back(out[0].id()), true);
      },
      3, &function, &error));
  EXPECT_NE(error.find("more than 3 paths"), std::string::npos) << error;
}

TEST(TracedFunction, LiteralsReadBackExactly) {
  for (double v : {0.1, -2.5, 1e-300, 3.0, 1.0 / 3.0, -0.0}) {
    const std::string text = CDoubleLiteral(v);
    std::string digits = text;
    if (digits.front() == '(') digits = digits.substr(1, digits.size() - 2);
    EXPECT_EQ(std::strtod(digits.c_str(), nullptr), v) << text;
    EXPECT_EQ(std::signbit(std::strtod(digits.c_str(), nullptr)), std::signbit(v)) << text;
  }
  EXPECT_EQ(CDoubleLiteral(NAN), "NAN");
  EXPECT_EQ(CDoubleLiteral(-INFINITY), "(-INFINITY)");
  EXPECT_EQ(CDoubleLiteral(2.0), "2.0");
}

}  // namespace traced_function_test
}  // namespace vesselid
