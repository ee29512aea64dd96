#include "engine/export/c_model.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "engine/export/traced_function.h"
#include "engine/model/expression.h"

namespace vesselid {
namespace {

using symbolic::Expression;
using symbolic::ExpressionTape;
using symbolic::TapeScope;

// Paths through a model's decisions beyond which the export refuses (the shipped models take
// at most a few dozen: two dead zones of three branches, the 6-DOF model's absent inputs).
constexpr int kMaxPaths = 4096;

std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// {a, b, c} of `items` (at least one element: C has no empty arrays).
template <class T, class F>
std::string List(const std::vector<T>& items, F text, const std::string& empty) {
  if (items.empty()) return "{" + empty + "}";
  std::string out = "{";
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + text(items[i]);
  return out + "}";
}

std::string CNames(const std::vector<ModelVariable>& v) {
  return List(
      v, [](const ModelVariable& x) { return Quoted(x.name); }, "\"\"");
}
std::string CUnits(const std::vector<ModelVariable>& v) {
  return List(
      v, [](const ModelVariable& x) { return Quoted(x.unit); }, "\"\"");
}
std::string CNumbers(const std::vector<double>& v) {
  return List(
      v, [](double x) { return CDoubleLiteral(x); }, "0.0");
}

// The right-hand side or output map of `handle` traced on x, u, p.
bool Trace(const ModelHandle& handle, bool derivative, ExpressionTape* tape,
           TracedFunction* function, std::string* error) {
  const ModelInfo& info = handle.info();
  TapeScope scope(tape);
  auto variables = [&](const char* name, size_t n) {
    std::vector<Expression> v;
    for (size_t i = 0; i < n; ++i) {
      v.push_back(
          Expression::Node(tape->Variable(std::string(name) + "[" + std::to_string(i) + "]")));
    }
    return v;
  };
  const std::vector<Expression> x = variables("x", info.states.size());
  const std::vector<Expression> u = variables("u", info.inputs.size());
  const std::vector<Expression> p = variables("p", info.parameters.size());
  const size_t n = derivative ? info.states.size() : info.outputs.size();
  bool complete = true;
  auto trace = [&](std::vector<int>* results) {
    std::vector<Expression> out(n);
    bool ok = true;
    if (derivative) {
      ok = handle.Derivative(x.data(), u.data(), p.data(), out.data());
    } else {
      handle.Output(x.data(), u.data(), p.data(), out.data());
    }
    for (const Expression& e : out) {
      complete = complete && (!ok || e.id() >= 0);
      results->push_back(e.id());
    }
    return ok;
  };
  if (!TraceFunction(tape, trace, kMaxPaths, function, error)) return false;
  if (!complete) {
    *error = std::string("the model leaves ") + (derivative ? "a state's rate" : "an output") +
             " unset on some path";
    return false;
  }
  return true;
}

int InterpolationCode(const std::string& method) {
  return method == "zero_order_hold" ? 0 : method == "cubic" ? 2 : 1;
}

// The value the example holds an input at: 10 degrees of an angle, 5 m/s of a speed, else 0.5.
double ExampleInput(const ModelVariable& input) {
  if (input.unit == "rad") return 0.17453292519943295;
  if (input.unit == "m/s") return 5.0;
  return 0.5;
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// The record simulation and its helpers (P_ / p_ stand for the macro and function prefixes).
constexpr const char* kSimulation = R"(
int p_rk4_step(double x[], const double u0[], const double u_mid[], const double u1[],
               const double p[], double h) {
  double k1[P_NUM_STATES], k2[P_NUM_STATES], k3[P_NUM_STATES], k4[P_NUM_STATES];
  double xs[P_NUM_STATES];
  const double half_h = 0.5 * h, sixth_h = h / 6.0;
  int i;
  if (!p_derivative(x, u0, p, k1)) return 0;
  for (i = 0; i < P_NUM_STATES; ++i) xs[i] = x[i] + half_h * k1[i];
  if (!p_derivative(xs, u_mid, p, k2)) return 0;
  for (i = 0; i < P_NUM_STATES; ++i) xs[i] = x[i] + half_h * k2[i];
  if (!p_derivative(xs, u_mid, p, k3)) return 0;
  for (i = 0; i < P_NUM_STATES; ++i) xs[i] = x[i] + h * k3[i];
  if (!p_derivative(xs, u1, p, k4)) return 0;
  for (i = 0; i < P_NUM_STATES; ++i) x[i] += sixth_h * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  return 1;
}

/* Catmull-Rom slope of input i at sample k (one-sided at the ends). */
static double p_slope(int n, const double t[], const double u[], int i, int k) {
  const int lo = k == 0 ? 0 : k - 1, hi = k + 1 == n ? k : k + 1;
  return (u[hi * P_NUM_INPUTS + i] - u[lo * P_NUM_INPUTS + i]) / (t[hi] - t[lo]);
}

/* The inputs at tau: t[*k] <= tau < t[*k + 1] (with left: t[*k] < tau <= t[*k + 1], the value
   before a switch at tau), *k walking forward; the end values held outside the record. */
static void p_inputs_at(int n, const double t[], const double u[], double tau, int left, int* k,
                        double out[]) {
  int i;
  while (*k + 1 < n && (left ? t[*k + 1] < tau : t[*k + 1] <= tau)) ++*k;
  for (i = 0; i < P_NUM_INPUTS; ++i) {
    const int j = *k;
    if (tau <= t[0]) {
      out[i] = u[i];
    } else if (j + 1 == n) {
      out[i] = u[(n - 1) * P_NUM_INPUTS + i];
    } else {
      const double h = t[j + 1] - t[j], s = (tau - t[j]) / h;
      const double a = u[j * P_NUM_INPUTS + i], b = u[(j + 1) * P_NUM_INPUTS + i];
      if (p_interpolation[i] == 0) {
        out[i] = a;
      } else if (p_interpolation[i] == 1) {
        out[i] = a + s * (b - a);
      } else {
        const double s2 = s * s, s3 = s2 * s;
        out[i] = (2 * s3 - 3 * s2 + 1) * a + (s3 - 2 * s2 + s) * h * p_slope(n, t, u, i, j) +
                 (-2 * s3 + 3 * s2) * b + (s3 - s2) * h * p_slope(n, t, u, i, j + 1);
      }
    }
  }
}

static int p_compare(const void* a, const void* b) {
  const double x = *(const double*)a, y = *(const double*)b;
  return x < y ? -1 : x > y ? 1 : 0;
}

/* The upper median of the sample intervals (0 for one sample; -1 when out of memory). */
static double p_median_interval(int n, const double t[]) {
  double* intervals;
  double median;
  int k;
  if (n < 2) return 0.0;
  intervals = (double*)malloc((size_t)(n - 1) * sizeof(double));
  if (intervals == NULL) return -1.0;
  for (k = 0; k + 1 < n; ++k) intervals[k] = t[k + 1] - t[k];
  qsort(intervals, (size_t)(n - 1), sizeof(double), p_compare);
  median = intervals[(n - 1) / 2];
  free(intervals);
  return median;
}

int p_simulate(int n, const double t[], const double u[], const double x0[], const double p[],
               double max_step, double y[]) {
  double x[P_NUM_STATES], u0[P_NUM_INPUTS], u_mid[P_NUM_INPUTS], u1[P_NUM_INPUTS];
  int k, s, i, right = 0, left = 0;
  for (k = 0; k < n * P_NUM_OUTPUTS; ++k) y[k] = NAN;
  if (!(max_step > 0.0)) max_step = p_median_interval(n, t);
  if (max_step < 0.0) return -1;
  for (i = 0; i < P_NUM_STATES; ++i) x[i] = x0[i];
  for (k = 0; k < n; ++k) {
    double interval, h;
    int steps;
    for (i = 0; i < P_NUM_STATES; ++i) {
      if (!isfinite(x[i])) return k;
    }
    p_inputs_at(n, t, u, t[k], 0, &right, u0);
    p_output(x, u0, p, y + k * P_NUM_OUTPUTS);
    if (k + 1 == n) break;
    interval = t[k + 1] - t[k];
    steps = (int)ceil(interval / max_step - 1e-6);
    if (steps < 1) steps = 1;
    h = interval / steps;
    for (s = 0; s < steps; ++s) {
      p_inputs_at(n, t, u, t[k] + s * h, 0, &right, u0);
      p_inputs_at(n, t, u, t[k] + (s + 0.5) * h, 0, &right, u_mid);
      p_inputs_at(n, t, u, s + 1 == steps ? t[k + 1] : t[k] + (s + 1) * h, 1, &left, u1);
      if (!p_rk4_step(x, u0, u_mid, u1, p, h)) return k + 1;
    }
  }
  return n;
}

const double* p_member(int k) {
  if (k == 0) return p_parameters;
  if (k < 0 || k > P_NUM_MEMBERS) return NULL;
  return p_ensemble[k - 1];
}
)";

constexpr const char* kHeaderFunctions = R"(
/* x' = f(x, u, p): 1, or 0 where the model refuses the state or parameters (the engine's
   simulation stops there). */
int p_derivative(const double x[], const double u[], const double p[], double xdot[]);
/* y = g(x, u, p). */
void p_output(const double x[], const double u[], const double p[], double y[]);
/* One classical RK4 step of length h, the inputs given at its start, midpoint and end. */
int p_rk4_step(double x[], const double u0[], const double u_mid[], const double u1[],
               const double p[], double h);
/* A record as vesselid simulates it: n samples at increasing times t (s), the inputs u
   (n x P_NUM_INPUTS, row-major, interpolated between samples as p_interpolation says), from the
   state x0 at t[0]; y (n x P_NUM_OUTPUTS) gets the outputs at every sample. Each sample interval
   takes equal RK4 steps of at most max_step s (<= 0: the median sample interval). Returns the
   number of samples reached (n; fewer where the simulation stops: the rest are NaN), -1 when
   out of memory. */
int p_simulate(int n, const double t[], const double u[], const double x0[], const double p[],
               double max_step, double y[]);
/* Parameter vector of ensemble member k: 0 the estimate, 1..P_NUM_MEMBERS the draws; NULL
   beyond. */
const double* p_member(int k);
)";

constexpr const char* kExample = R"(#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "p.h"

#define SAMPLES 601 /* 60 s at 10 Hz */

int main(int argc, char** argv) {
  static double t[SAMPLES], u[SAMPLES * P_NUM_INPUTS], y[SAMPLES * P_NUM_OUTPUTS];
  double hold[P_NUM_INPUTS] = P_EXAMPLE_INPUTS, x0[P_NUM_STATES] = {0.0};
  double low[P_NUM_OUTPUTS], high[P_NUM_OUTPUTS];
  int k, i, m, diverged = 0;
  for (i = 0; i < P_NUM_INPUTS && i + 1 < argc; ++i) hold[i] = atof(argv[i + 1]);
  for (k = 0; k < SAMPLES; ++k) {
    t[k] = 0.1 * k;
    for (i = 0; i < P_NUM_INPUTS; ++i) u[k * P_NUM_INPUTS + i] = hold[i];
  }
  for (i = 0; i < P_NUM_OUTPUTS; ++i) low[i] = HUGE_VAL, high[i] = -HUGE_VAL;
  for (m = 0; m <= P_NUM_MEMBERS; ++m) {
    const double* end = y + (SAMPLES - 1) * P_NUM_OUTPUTS;
    if (p_simulate(SAMPLES, t, u, x0, p_member(m), P_MAX_STEP, y) < SAMPLES) {
      ++diverged;
      continue;
    }
    for (i = 0; i < P_NUM_OUTPUTS; ++i) {
      if (m == 0) printf("%-8s %14.6g %-7s", p_output_names[i], end[i], p_output_units[i]);
      if (m == 0) printf(P_NUM_MEMBERS > 0 ? "\n" : " (no ensemble)\n");
      if (m > 0 && end[i] < low[i]) low[i] = end[i];
      if (m > 0 && end[i] > high[i]) high[i] = end[i];
    }
  }
  printf("after %g s from rest; %d of %d members diverged\n", t[SAMPLES - 1], diverged,
         P_NUM_MEMBERS + 1);
  for (i = 0; i < P_NUM_OUTPUTS && P_NUM_MEMBERS > diverged; ++i) {
    printf("%-8s members from %g to %g\n", p_output_names[i], low[i], high[i]);
  }
  return 0;
}
)";

}  // namespace

std::string CIdentifier(const std::string& name) {
  std::string id;
  for (char c : name) {
    id += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '_';
  }
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id = "model_" + id;
  return id;
}

bool MakeCModel(const IdentifiedModel& model, const ModelHandle& handle,
                std::vector<CModelFile>* files, std::string* error) {
  ExpressionTape derivative_tape, output_tape;
  TracedFunction derivative, output;
  if (!Trace(handle, true, &derivative_tape, &derivative, error) ||
      !Trace(handle, false, &output_tape, &output, error)) {
    *error = model.model + ": " + *error;
    return false;
  }
  const std::string id = CIdentifier(model.model);
  std::string macro = id;
  for (char& c : macro) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  auto named = [&](std::string text) {
    text = Replace(std::move(text), "P_", macro + "_");
    text = Replace(std::move(text), "p_", id + "_");
    return Replace(std::move(text), "\"p.h\"", "\"" + id + ".h\"");
  };
  const int members = static_cast<int>(model.ensemble.size());
  const int estimated = static_cast<int>(model.covariance_names.size());
  std::vector<int> estimated_index;
  for (const std::string& name : model.covariance_names) {
    for (size_t i = 0; i < model.parameters.size(); ++i) {
      if (model.parameters[i].name == name) estimated_index.push_back(static_cast<int>(i));
    }
  }
  std::vector<int> interpolation;
  for (size_t i = 0; i < model.inputs.size(); ++i) {
    interpolation.push_back(
        InterpolationCode(i < model.interpolation.size() ? model.interpolation[i] : "linear"));
  }
  std::vector<double> example_inputs;
  for (const ModelVariable& input : model.inputs) {
    example_inputs.push_back(ExampleInput(input));
  }

  const std::string origin =
      "Generated by `vesselid export --format c` from " +
      (model.results.empty() ? std::string("a vesselid run") : model.results) + ".";
  std::string h = "/* " + id + ".h: the " + model.model + " model (" + model.family +
                  ") identified by vesselid, as C99.\n   " + origin +
                  "\n   Units are SI as named below; angles in rad. */\n";
  h += "#ifndef VESSELID_" + macro + "_H_\n#define VESSELID_" + macro + "_H_\n\n";
  h += "#ifdef __cplusplus\nextern \"C\" {\n#endif\n\n";
  auto define = [&](const std::string& name, const std::string& value, const std::string& note) {
    h += "#define " + macro + "_" + name + " " + value +
         (note.empty() ? "" : "  /* " + note + " */") + "\n";
  };
  define("NUM_STATES", std::to_string(model.states.size()), "");
  define("NUM_INPUTS", std::to_string(model.inputs.size()), "");
  define("NUM_OUTPUTS", std::to_string(model.outputs.size()), "");
  define("NUM_PARAMETERS", std::to_string(model.parameters.size()), "");
  define("NUM_ESTIMATED", std::to_string(estimated), "parameters with a covariance");
  define("NUM_MEMBERS", std::to_string(members), "ensemble draws besides the estimate");
  define("MAX_STEP", CDoubleLiteral(model.max_step),
         "s: the run's RK4 step bound; 0: the median sample interval");
  define("EXAMPLE_INPUTS", CNumbers(example_inputs), "the example's held inputs");
  h += "\n";
  // The data, each array declared in the header and defined in the source (C has no empty
  // arrays: a size of at least one, the count macros say how many are real).
  auto size = [](size_t n) { return std::to_string(std::max<size_t>(n, 1)); };
  auto rows = [&](const std::vector<std::vector<double>>& r, const std::vector<double>& empty) {
    std::string text = "{";
    for (size_t k = 0; k < r.size(); ++k)
      text += std::string(k ? "," : "") + "\n    " + CNumbers(r[k]);
    return r.empty() ? "{" + CNumbers(empty) + "}" : text + "}";
  };
  std::vector<std::vector<double>> covariance(estimated);
  for (int r = 0; r < estimated; ++r) {
    for (int k = 0; k < model.covariance.cols(); ++k)
      covariance[r].push_back(model.covariance(r, k));
  }
  auto indices = [](const std::vector<int>& v, const std::string& empty) {
    return List(
        v, [](int k) { return std::to_string(k); }, empty);
  };
  const std::string ensemble_note =
      "Ensemble members 1.." + macro + "_NUM_MEMBERS: full parameter vectors, " +
      (model.ensemble_source == "bootstrap"
           ? std::string("the estimates of the run's bootstrap replicates")
           : "drawn from N(" + id + "_parameters, " + id + "_covariance) (seed " +
                 std::to_string(model.ensemble_seed) + ")") +
      ".";
  struct CArray {
    std::string type, name, size, value, note;
  };
  const std::string names = "const char* const";
  const std::vector<CArray> arrays = {
      {names, "state_names", size(model.states.size()), CNames(model.states), ""},
      {names, "state_units", size(model.states.size()), CUnits(model.states), ""},
      {names, "input_names", size(model.inputs.size()), CNames(model.inputs), ""},
      {names, "input_units", size(model.inputs.size()), CUnits(model.inputs), ""},
      {names, "output_names", size(model.outputs.size()), CNames(model.outputs), ""},
      {names, "output_units", size(model.outputs.size()), CUnits(model.outputs), ""},
      {names, "parameter_names", size(model.parameters.size()), CNames(model.parameters), ""},
      {names, "parameter_units", size(model.parameters.size()), CUnits(model.parameters), ""},
      {"const int", "interpolation", size(model.inputs.size()), indices(interpolation, "1"),
       "Per input: 0 zero-order hold, 1 linear, 2 cubic Hermite (as the run read it)."},
      {"const double", "parameters", size(model.parameters.size()), CNumbers(model.values),
       "The estimate (the run's final values; the model's defaults where not estimated)."},
      {"const double", "std_errors", size(model.parameters.size()), CNumbers(model.std_errors),
       "Standard errors; NaN where not estimated."},
      {"const int", "estimated", size(estimated), indices(estimated_index, "-1"),
       "The estimated parameters (indices into " + id + "_parameters) and their covariance."},
      {"const double", "covariance", size(estimated) + "][" + size(estimated),
       rows(covariance, {0.0}), ""},
      {"const double", "ensemble", size(members) + "][" + size(model.parameters.size()),
       rows(model.ensemble, model.values), ensemble_note},
  };
  std::string data;
  for (const CArray& a : arrays) {
    if (!a.note.empty()) h += "/* " + a.note + " */\n";
    h += "extern " + a.type + " " + id + "_" + a.name + "[" + a.size + "];\n";
    data += a.type + " " + id + "_" + a.name + "[" + a.size + "] = " + a.value + ";\n";
  }
  h += named(kHeaderFunctions);
  h += "\n#ifdef __cplusplus\n}\n#endif\n\n#endif\n";

  std::string c = "/* " + id + ".c: " + origin + " */\n";
  c += "#include \"" + id + ".h\"\n\n#include <math.h>\n#include <stdlib.h>\n\n" + data;
  c += "\nint " + id +
       "_derivative(const double x[], const double u[], const double p[], double xdot[]) "
       "{\n";
  c += "  (void)x, (void)u, (void)p;\n";
  c += TracedFunctionToC(derivative_tape, derivative, "xdot", true, 1);
  c += "}\n\nvoid " + id +
       "_output(const double x[], const double u[], const double p[], double y[]) {\n";
  c += "  (void)x, (void)u, (void)p;\n";
  c += TracedFunctionToC(output_tape, output, "y", false, 1);
  c += "}\n";
  c += named(kSimulation);

  const std::string example = "/* " + id + "_example.c: the " + model.model +
                              " model's response from rest to inputs held constant (" + macro +
                              "_EXAMPLE_INPUTS, or one value per input on the command line), for "
                              "the estimate and each ensemble member.\n   Build: cc "
                              "-std=c99 -Wall -Werror -O2 " +
                              id + "_example.c " + id + ".c -lm */\n" + named(kExample);
  files->clear();
  files->push_back({id + ".h", h});
  files->push_back({id + ".c", c});
  files->push_back({id + "_example.c", example});
  return true;
}

}  // namespace vesselid
