#include "engine/model/expression.h"

#include <cmath>
#include <cstring>

#include "engine/base/check.h"

namespace vesselid::symbolic {
namespace {

thread_local ExpressionTape* current_tape = nullptr;

std::uint64_t Bits(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof(bits));
  return bits;
}

}  // namespace

bool IsCondition(ExpressionOp op) { return op >= ExpressionOp::kLess; }

ExpressionTape* ExpressionTape::Current() {
  VESSELID_CHECK(current_tape != nullptr);
  return current_tape;
}

TapeScope::TapeScope(ExpressionTape* tape) : previous_(current_tape) { current_tape = tape; }
TapeScope::~TapeScope() { current_tape = previous_; }

int ExpressionTape::Add(ExpressionNode node) {
  const auto key = std::make_tuple(static_cast<int>(node.op), node.a, node.b,
                                   node.op == ExpressionOp::kConstant ? Bits(node.value) : 0);
  const auto found = index_.find(key);
  if (found != index_.end()) return found->second;
  nodes_.push_back(std::move(node));
  const int id = static_cast<int>(nodes_.size()) - 1;
  index_.emplace(key, id);
  return id;
}

int ExpressionTape::Constant(double value) {
  ExpressionNode node;
  node.value = value;
  return Add(std::move(node));
}

int ExpressionTape::Variable(const std::string& name) {
  const auto found = variables_.find(name);
  if (found != variables_.end()) return found->second;
  ExpressionNode node;
  node.op = ExpressionOp::kVariable;
  node.name = name;
  nodes_.push_back(std::move(node));
  const int id = static_cast<int>(nodes_.size()) - 1;
  variables_.emplace(name, id);
  return id;
}

// The operation in double, as <cmath> and the double instantiation compute it; a condition
// gives 1 or 0.
double ExpressionTape::Fold(ExpressionOp op, double a, double b) const {
  switch (op) {
    case ExpressionOp::kAdd:
      return a + b;
    case ExpressionOp::kSubtract:
      return a - b;
    case ExpressionOp::kMultiply:
      return a * b;
    case ExpressionOp::kDivide:
      return a / b;
    case ExpressionOp::kNegate:
      return -a;
    case ExpressionOp::kSin:
      return std::sin(a);
    case ExpressionOp::kCos:
      return std::cos(a);
    case ExpressionOp::kTan:
      return std::tan(a);
    case ExpressionOp::kAsin:
      return std::asin(a);
    case ExpressionOp::kAcos:
      return std::acos(a);
    case ExpressionOp::kAtan:
      return std::atan(a);
    case ExpressionOp::kAtan2:
      return std::atan2(a, b);
    case ExpressionOp::kSinh:
      return std::sinh(a);
    case ExpressionOp::kCosh:
      return std::cosh(a);
    case ExpressionOp::kTanh:
      return std::tanh(a);
    case ExpressionOp::kExp:
      return std::exp(a);
    case ExpressionOp::kLog:
      return std::log(a);
    case ExpressionOp::kSqrt:
      return std::sqrt(a);
    case ExpressionOp::kAbs:
      return std::abs(a);
    case ExpressionOp::kPow:
      return std::pow(a, b);
    case ExpressionOp::kFloor:
      return std::floor(a);
    case ExpressionOp::kCeil:
      return std::ceil(a);
    case ExpressionOp::kLess:
      return a < b;
    case ExpressionOp::kLessEqual:
      return a <= b;
    case ExpressionOp::kGreater:
      return a > b;
    case ExpressionOp::kGreaterEqual:
      return a >= b;
    case ExpressionOp::kEqual:
      return a == b;
    case ExpressionOp::kNotEqual:
      return a != b;
    case ExpressionOp::kIsNan:
      return std::isnan(a);
    case ExpressionOp::kIsFinite:
      return std::isfinite(a);
    case ExpressionOp::kIsInf:
      return std::isinf(a);
    case ExpressionOp::kConstant:
    case ExpressionOp::kVariable:
      break;
  }
  VESSELID_CHECK(false);
  return 0.0;
}

int ExpressionTape::Apply(ExpressionOp op, int a, int b) {
  VESSELID_CHECK(a >= 0 && a < static_cast<int>(nodes_.size()));
  VESSELID_CHECK(b < static_cast<int>(nodes_.size()));
  if (IsConstant(a) && (b < 0 || IsConstant(b))) {
    const double folded = Fold(op, nodes_[a].value, b < 0 ? 0.0 : nodes_[b].value);
    if (!IsCondition(op)) return Constant(folded);
  }
  // Identities exact in double but for the sign of a zero result (x + 0, x * 1, 0 - x, - -x):
  // the operations with a zero or one that an inactive term leaves in the equations.
  auto is = [&](int node, double value) {
    return node >= 0 && IsConstant(node) && nodes_[node].value == value;
  };
  switch (op) {
    case ExpressionOp::kAdd:
      if (is(b, 0.0)) return a;
      if (is(a, 0.0)) return b;
      break;
    case ExpressionOp::kSubtract:
      if (is(b, 0.0)) return a;
      if (is(a, 0.0)) return Apply(ExpressionOp::kNegate, b);
      break;
    case ExpressionOp::kMultiply:
      if (is(b, 1.0)) return a;
      if (is(a, 1.0)) return b;
      break;
    case ExpressionOp::kDivide:
      if (is(b, 1.0)) return a;
      break;
    case ExpressionOp::kNegate:
      if (nodes_[a].op == ExpressionOp::kNegate) return nodes_[a].a;
      break;
    default:
      break;
  }
  ExpressionNode node;
  node.op = op;
  node.a = a;
  node.b = b;
  return Add(std::move(node));
}

bool ExpressionTape::Decide(int node) {
  const ExpressionNode& n = nodes_[node];
  VESSELID_CHECK(IsCondition(n.op));
  if (IsConstant(n.a) && (n.b < 0 || IsConstant(n.b))) {
    return Fold(n.op, nodes_[n.a].value, n.b < 0 ? 0.0 : nodes_[n.b].value) != 0.0;
  }
  for (const ExpressionDecision& d : decisions_) {
    if (d.condition == node) return d.outcome;
  }
  const size_t k = decisions_.size();
  const bool outcome = k < script_.size() ? script_[k] : true;
  decisions_.push_back({node, outcome});
  return outcome;
}

void ExpressionTape::BeginPath(std::vector<bool> script) {
  script_ = std::move(script);
  decisions_.clear();
}

}  // namespace vesselid::symbolic
