#include "engine/export/traced_function.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <set>

#include "engine/base/check.h"

namespace vesselid {

using symbolic::ExpressionDecision;
using symbolic::ExpressionNode;
using symbolic::ExpressionOp;
using symbolic::ExpressionTape;

bool TraceFunction(ExpressionTape* tape,
                   const std::function<bool(std::vector<int>* results)>& trace, int max_paths,
                   TracedFunction* function, std::string* error) {
  function->paths.clear();
  std::vector<bool> script;
  while (true) {
    if (static_cast<int>(function->paths.size()) == max_paths) {
      *error = "more than " + std::to_string(max_paths) + " paths through the model's decisions";
      return false;
    }
    tape->BeginPath(script);
    TracedPath path;
    path.ok = trace(&path.results);
    if (!path.ok) path.results.clear();
    path.decisions = tape->decisions();
    function->paths.push_back(path);
    // Next: the last decision taken as true, taken as false (depth first over the outcomes).
    int last = static_cast<int>(path.decisions.size()) - 1;
    while (last >= 0 && !path.decisions[last].outcome) --last;
    if (last < 0) return true;
    script.clear();
    for (int k = 0; k < last; ++k) script.push_back(path.decisions[k].outcome);
    script.push_back(false);
  }
}

std::string CDoubleLiteral(double value) {
  if (std::isnan(value)) return "NAN";
  if (std::isinf(value)) return value > 0 ? "INFINITY" : "(-INFINITY)";
  char text[40];
  std::snprintf(text, sizeof(text), "%.17g", value);
  std::string s = text;
  // The shortest of %.15g, %.16g, %.17g that reads back exactly (fewer spurious digits).
  for (int digits = 15; digits < 17; ++digits) {
    std::snprintf(text, sizeof(text), "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) {
      s = text;
      break;
    }
  }
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return std::signbit(value) ? "(" + s + ")" : s;
}

namespace {

// The decision tree of a traced function's paths.
struct TreeNode {
  int condition = -1;       // branch: the decision's condition node
  int child[2] = {-1, -1};  // outcome false, true
  bool leaf = false, ok = true;
  std::vector<int> results;
  std::vector<int> required;  // sorted: nodes needed below (operands' closure)
};

class Emitter {
 public:
  Emitter(const ExpressionTape& tape, const TracedFunction& function, std::string out, bool status)
      : tape_(tape), out_(std::move(out)), status_(status) {
    tree_.emplace_back();
    for (const TracedPath& path : function.paths) Insert(path);
    Require(0);
  }

  std::string Body(int indent) {
    std::vector<char> emitted(tape_.nodes().size(), 0);
    std::string text;
    Emit(0, &emitted, indent, &text);
    return text;
  }

 private:
  void Insert(const TracedPath& path) {
    int at = 0;
    for (const ExpressionDecision& d : path.decisions) {
      if (tree_[at].condition < 0) tree_[at].condition = d.condition;
      VESSELID_CHECK(tree_[at].condition == d.condition);
      const int side = d.outcome ? 1 : 0;
      if (tree_[at].child[side] < 0) {
        tree_[at].child[side] = static_cast<int>(tree_.size());
        tree_.emplace_back();  // (invalidates references into tree_)
      }
      at = tree_[at].child[side];
    }
    tree_[at].leaf = true;
    tree_[at].ok = path.ok;
    tree_[at].results = path.results;
  }

  // Adds `node` and the nodes it is computed from (not constants or variables) to `set`.
  void Closure(int node, std::set<int>* set) const {
    const ExpressionNode& n = tape_.nodes()[node];
    if (n.op == ExpressionOp::kConstant || n.op == ExpressionOp::kVariable) return;
    if (!set->insert(node).second) return;
    if (n.a >= 0) Closure(n.a, set);
    if (n.b >= 0) Closure(n.b, set);
  }

  // The operands' closure of a condition (the condition itself is written inline).
  std::set<int> ConditionClosure(int condition) const {
    std::set<int> set;
    const ExpressionNode& n = tape_.nodes()[condition];
    if (n.a >= 0) Closure(n.a, &set);
    if (n.b >= 0) Closure(n.b, &set);
    return set;
  }

  // Whether every path below `at` refuses (one `return 0;`, no decision written).
  bool Refusal(int at) const {
    const TreeNode& t = tree_[at];
    return t.leaf ? !t.ok : Refusal(t.child[0]) && Refusal(t.child[1]);
  }

  void Require(int at) {
    TreeNode& t = tree_[at];
    std::set<int> set;
    if (Refusal(at)) {
      // Nothing needed.
    } else if (t.leaf) {
      for (int r : t.results) Closure(r, &set);
    } else {
      VESSELID_CHECK(t.child[0] >= 0 && t.child[1] >= 0);
      set = ConditionClosure(t.condition);
      for (int c : t.child) {
        Require(c);
        set.insert(tree_[c].required.begin(), tree_[c].required.end());
      }
    }
    tree_[at].required.assign(set.begin(), set.end());
  }

  std::string Ref(int node) const {
    const ExpressionNode& n = tape_.nodes()[node];
    if (n.op == ExpressionOp::kConstant) return CDoubleLiteral(n.value);
    if (n.op == ExpressionOp::kVariable) return n.name;
    return "t" + std::to_string(node);
  }

  std::string Value(int node) const {
    const ExpressionNode& n = tape_.nodes()[node];
    const std::string a = n.a >= 0 ? Ref(n.a) : "", b = n.b >= 0 ? Ref(n.b) : "";
    auto call = [&](const char* f) { return std::string(f) + "(" + a + ")"; };
    switch (n.op) {
      case ExpressionOp::kAdd:
        return a + " + " + b;
      case ExpressionOp::kSubtract:
        return a + " - " + b;
      case ExpressionOp::kMultiply:
        return a + " * " + b;
      case ExpressionOp::kDivide:
        return a + " / " + b;
      case ExpressionOp::kNegate:
        return "-" + a;
      case ExpressionOp::kSin:
        return call("sin");
      case ExpressionOp::kCos:
        return call("cos");
      case ExpressionOp::kTan:
        return call("tan");
      case ExpressionOp::kAsin:
        return call("asin");
      case ExpressionOp::kAcos:
        return call("acos");
      case ExpressionOp::kAtan:
        return call("atan");
      case ExpressionOp::kAtan2:
        return "atan2(" + a + ", " + b + ")";
      case ExpressionOp::kSinh:
        return call("sinh");
      case ExpressionOp::kCosh:
        return call("cosh");
      case ExpressionOp::kTanh:
        return call("tanh");
      case ExpressionOp::kExp:
        return call("exp");
      case ExpressionOp::kLog:
        return call("log");
      case ExpressionOp::kSqrt:
        return call("sqrt");
      case ExpressionOp::kAbs:
        return call("fabs");
      case ExpressionOp::kPow:
        return "pow(" + a + ", " + b + ")";
      case ExpressionOp::kFloor:
        return call("floor");
      case ExpressionOp::kCeil:
        return call("ceil");
      case ExpressionOp::kLess:
        return a + " < " + b;
      case ExpressionOp::kLessEqual:
        return a + " <= " + b;
      case ExpressionOp::kGreater:
        return a + " > " + b;
      case ExpressionOp::kGreaterEqual:
        return a + " >= " + b;
      case ExpressionOp::kEqual:
        return a + " == " + b;
      case ExpressionOp::kNotEqual:
        return a + " != " + b;
      case ExpressionOp::kIsNan:
        return call("isnan");
      case ExpressionOp::kIsFinite:
        return call("isfinite");
      case ExpressionOp::kIsInf:
        return call("isinf");
      case ExpressionOp::kConstant:
      case ExpressionOp::kVariable:
        break;
    }
    return Ref(node);
  }

  // Declares the temporaries of `nodes` not yet emitted, in tape order (operands first).
  void Declare(const std::vector<int>& nodes, std::vector<char>* emitted, const std::string& pad,
               std::string* text) const {
    for (int node : nodes) {
      if ((*emitted)[node]) continue;
      (*emitted)[node] = 1;
      *text += pad + "const double t" + std::to_string(node) + " = " + Value(node) + ";\n";
    }
  }

  void Emit(int at, std::vector<char>* emitted, int indent, std::string* text) const {
    const TreeNode& t = tree_[at];
    const std::string pad(2 * indent, ' ');
    if (Refusal(at)) {
      VESSELID_CHECK(status_);
      *text += pad + "return 0;\n";
      return;
    }
    if (t.leaf) {
      Declare(t.required, emitted, pad, text);
      for (size_t i = 0; i < t.results.size(); ++i) {
        *text += pad + out_ + "[" + std::to_string(i) + "] = " + Ref(t.results[i]) + ";\n";
      }
      if (status_) *text += pad + "return 1;\n";
      return;
    }
    // Before the decision: its operands and what both branches need.
    const std::vector<int>& r0 = tree_[t.child[0]].required;
    const std::vector<int>& r1 = tree_[t.child[1]].required;
    std::set<int> hoist = ConditionClosure(t.condition);
    std::set_intersection(r0.begin(), r0.end(), r1.begin(), r1.end(),
                          std::inserter(hoist, hoist.end()));
    Declare(std::vector<int>(hoist.begin(), hoist.end()), emitted, pad, text);
    const std::string condition = Value(t.condition);
    if (Refusal(t.child[0]) && !Refusal(t.child[1])) {
      *text += pad + "if (!(" + condition + ")) return 0;\n";
      Emit(t.child[1], emitted, indent, text);
      return;
    }
    if (Refusal(t.child[1]) && !Refusal(t.child[0])) {
      *text += pad + "if (" + condition + ") return 0;\n";
      Emit(t.child[0], emitted, indent, text);
      return;
    }
    *text += pad + "if (" + condition + ") {\n";
    std::vector<char> inner = *emitted;
    Emit(t.child[1], &inner, indent + 1, text);
    *text += pad + "} else {\n";
    inner = *emitted;
    Emit(t.child[0], &inner, indent + 1, text);
    *text += pad + "}\n";
  }

  const ExpressionTape& tape_;
  std::string out_;
  bool status_;
  std::vector<TreeNode> tree_;
};

}  // namespace

std::string TracedFunctionToC(const ExpressionTape& tape, const TracedFunction& function,
                              const std::string& out, bool status, int indent) {
  return Emitter(tape, function, out, status).Body(indent);
}

}  // namespace vesselid
