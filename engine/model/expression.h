// A recording scalar: a model's templated right-hand side run on Expression instead of double
// or a Jet writes each operation into an ExpressionTape, from which the export emits the
// model as C code (export/c_program.h). The same source then defines the fit, the FMU and the
// exported code.
//
// Nodes are hash-consed (one node per distinct operation on the same operands), operations
// on constants are folded in double, exactly as the double instantiation computes them, and
// x + 0, x - 0, 0 - x, x * 1, x / 1 and - -x are reduced (exact but for the sign of a zero). A
// comparison or test on a non-constant (x > d, isnan(u), isfinite(s)) is a decision: its
// outcome comes from the tape's script (ExplorePaths, export/expression_paths.h, runs the
// right-hand side once per outcome sequence) and the condition is recorded with it. A condition
// decided earlier on the same path keeps its outcome.
//
// Not the hot path: the fit never instantiates a model on Expression. The type and its
// functions live in their own namespace, found by argument-dependent lookup only: an
// unqualified isnan(double) elsewhere in vesselid keeps meaning the <cmath> one.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace vesselid::symbolic {

enum class ExpressionOp {
  kConstant,
  kVariable,
  // Arithmetic (a, b).
  kAdd,
  kSubtract,
  kMultiply,
  kDivide,
  kNegate,
  // Functions of a (and b).
  kSin,
  kCos,
  kTan,
  kAsin,
  kAcos,
  kAtan,
  kAtan2,
  kSinh,
  kCosh,
  kTanh,
  kExp,
  kLog,
  kSqrt,
  kAbs,
  kPow,
  kFloor,
  kCeil,
  // Conditions (true or false; only ever decided, never a value).
  kLess,
  kLessEqual,
  kGreater,
  kGreaterEqual,
  kEqual,
  kNotEqual,
  kIsNan,
  kIsFinite,
  kIsInf,
};

struct ExpressionNode {
  ExpressionOp op = ExpressionOp::kConstant;
  int a = -1, b = -1;  // operand nodes
  double value = 0.0;  // kConstant
  std::string name;    // kVariable, e.g. "x[1]"
};

bool IsCondition(ExpressionOp op);

// One decision taken on a path: condition node and its outcome.
struct ExpressionDecision {
  int condition = -1;
  bool outcome = true;
};

class ExpressionTape {
 public:
  int Constant(double value);
  int Variable(const std::string& name);
  // The node of op on a (and b), folded when every operand is a constant.
  int Apply(ExpressionOp op, int a, int b = -1);
  // The outcome of condition `node`: folded for constants, else the script's next outcome
  // (true beyond its end), or the outcome this path already took for the same node.
  bool Decide(int node);

  const std::vector<ExpressionNode>& nodes() const { return nodes_; }
  bool IsConstant(int node) const { return nodes_[node].op == ExpressionOp::kConstant; }

  // Starts a path whose first decisions take `script`'s outcomes.
  void BeginPath(std::vector<bool> script);
  const std::vector<ExpressionDecision>& decisions() const { return decisions_; }

  // The tape that Expression operations record on (one per thread, set by TapeScope).
  static ExpressionTape* Current();

 private:
  friend class TapeScope;
  int Add(ExpressionNode node);
  double Fold(ExpressionOp op, double a, double b) const;

  std::vector<ExpressionNode> nodes_;
  std::map<std::tuple<int, int, int, std::uint64_t>, int> index_;  // op, a, b, constant bits
  std::map<std::string, int> variables_;
  std::vector<bool> script_;
  std::vector<ExpressionDecision> decisions_;
};

// Makes `tape` the current tape of this thread while in scope.
class TapeScope {
 public:
  explicit TapeScope(ExpressionTape* tape);
  ~TapeScope();
  TapeScope(const TapeScope&) = delete;
  TapeScope& operator=(const TapeScope&) = delete;

 private:
  ExpressionTape* previous_;
};

// A scalar node of the current tape; default-constructed it is no node (-1) until assigned.
class Expression {
 public:
  Expression() = default;
  Expression(double value) : id_(ExpressionTape::Current()->Constant(value)) {}  // NOLINT
  static Expression Node(int id) {
    Expression e;
    e.id_ = id;
    return e;
  }
  int id() const { return id_; }

  Expression& operator+=(const Expression& b) {
    return *this = Apply(ExpressionOp::kAdd, *this, b);
  }
  Expression& operator-=(const Expression& b) {
    return *this = Apply(ExpressionOp::kSubtract, *this, b);
  }
  Expression& operator*=(const Expression& b) {
    return *this = Apply(ExpressionOp::kMultiply, *this, b);
  }
  Expression& operator/=(const Expression& b) {
    return *this = Apply(ExpressionOp::kDivide, *this, b);
  }

  static Expression Apply(ExpressionOp op, const Expression& a) {
    return Node(ExpressionTape::Current()->Apply(op, a.id_));
  }
  static Expression Apply(ExpressionOp op, const Expression& a, const Expression& b) {
    return Node(ExpressionTape::Current()->Apply(op, a.id_, b.id_));
  }
  static bool Decide(ExpressionOp op, const Expression& a) {
    ExpressionTape* tape = ExpressionTape::Current();
    return tape->Decide(tape->Apply(op, a.id_));
  }
  static bool Decide(ExpressionOp op, const Expression& a, const Expression& b) {
    ExpressionTape* tape = ExpressionTape::Current();
    return tape->Decide(tape->Apply(op, a.id_, b.id_));
  }

 private:
  int id_ = -1;
};

inline Expression operator+(const Expression& a, const Expression& b) {
  return Expression::Apply(ExpressionOp::kAdd, a, b);
}
inline Expression operator-(const Expression& a, const Expression& b) {
  return Expression::Apply(ExpressionOp::kSubtract, a, b);
}
inline Expression operator*(const Expression& a, const Expression& b) {
  return Expression::Apply(ExpressionOp::kMultiply, a, b);
}
inline Expression operator/(const Expression& a, const Expression& b) {
  return Expression::Apply(ExpressionOp::kDivide, a, b);
}
inline Expression operator-(const Expression& a) {
  return Expression::Apply(ExpressionOp::kNegate, a);
}
inline Expression operator+(const Expression& a) { return a; }

inline bool operator<(const Expression& a, const Expression& b) {
  return Expression::Decide(ExpressionOp::kLess, a, b);
}
inline bool operator<=(const Expression& a, const Expression& b) {
  return Expression::Decide(ExpressionOp::kLessEqual, a, b);
}
inline bool operator>(const Expression& a, const Expression& b) {
  return Expression::Decide(ExpressionOp::kGreater, a, b);
}
inline bool operator>=(const Expression& a, const Expression& b) {
  return Expression::Decide(ExpressionOp::kGreaterEqual, a, b);
}
inline bool operator==(const Expression& a, const Expression& b) {
  return Expression::Decide(ExpressionOp::kEqual, a, b);
}
inline bool operator!=(const Expression& a, const Expression& b) {
  return Expression::Decide(ExpressionOp::kNotEqual, a, b);
}

// The <cmath> functions a model may call (found by argument-dependent lookup, as for Jets).
#define VESSELID_EXPRESSION_FUNCTION(name, op) \
  inline Expression name(const Expression& a) { return Expression::Apply(ExpressionOp::op, a); }
VESSELID_EXPRESSION_FUNCTION(sin, kSin)
VESSELID_EXPRESSION_FUNCTION(cos, kCos)
VESSELID_EXPRESSION_FUNCTION(tan, kTan)
VESSELID_EXPRESSION_FUNCTION(asin, kAsin)
VESSELID_EXPRESSION_FUNCTION(acos, kAcos)
VESSELID_EXPRESSION_FUNCTION(atan, kAtan)
VESSELID_EXPRESSION_FUNCTION(sinh, kSinh)
VESSELID_EXPRESSION_FUNCTION(cosh, kCosh)
VESSELID_EXPRESSION_FUNCTION(tanh, kTanh)
VESSELID_EXPRESSION_FUNCTION(exp, kExp)
VESSELID_EXPRESSION_FUNCTION(log, kLog)
VESSELID_EXPRESSION_FUNCTION(sqrt, kSqrt)
VESSELID_EXPRESSION_FUNCTION(abs, kAbs)
VESSELID_EXPRESSION_FUNCTION(fabs, kAbs)
VESSELID_EXPRESSION_FUNCTION(floor, kFloor)
VESSELID_EXPRESSION_FUNCTION(ceil, kCeil)
#undef VESSELID_EXPRESSION_FUNCTION

inline Expression atan2(const Expression& y, const Expression& x) {
  return Expression::Apply(ExpressionOp::kAtan2, y, x);
}
inline Expression pow(const Expression& a, const Expression& b) {
  return Expression::Apply(ExpressionOp::kPow, a, b);
}
inline bool isnan(const Expression& a) { return Expression::Decide(ExpressionOp::kIsNan, a); }
inline bool isfinite(const Expression& a) { return Expression::Decide(ExpressionOp::kIsFinite, a); }
inline bool isinf(const Expression& a) { return Expression::Decide(ExpressionOp::kIsInf, a); }

}  // namespace vesselid::symbolic
