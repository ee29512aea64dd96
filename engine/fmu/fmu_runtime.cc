// The FMI 2.0 co-simulation runtime of every exported vesselid FMU (libvesselid_fmu.so, copied
// into the FMU as binaries/linux64/<modelIdentifier>.so). fmi2Instantiate reads the FMU's
// resources/model.json (export/model_json.h) and makes the model with the families the
// vesselid program knows; fmi2DoStep integrates it as a run simulates a record: RK4 steps of
// at most max_step, equal within the communication step, the inputs at each step's start,
// midpoint and end taken from the value set at the communication point and its first three
// derivatives d1, d2, d3 there (fmi2SetRealInputDerivatives, orders 1-3; unset: zero, the
// value held): u(t + tau) = u + d1 tau + d2 tau^2 / 2 + d3 tau^3 / 6. The run's interpolations
// are such polynomials between samples (zero-order hold, linear, cubic Hermite), so a master
// that steps from sample to sample and gives each input's polynomial reproduces the run's
// simulation.
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "engine/export/model_json.h"
#include "engine/export/fmi2.h"
#include "engine/export/fmu_layout.h"
#include "problems/registry.h"

namespace vesselid {
namespace {

enum class Phase { kInstantiated, kInitialization, kStepping, kTerminated, kError };

struct Instance {
  std::string name;
  fmi2CallbackLogger logger = nullptr;
  fmi2ComponentEnvironment environment = nullptr;
  IdentifiedModel exported;
  std::shared_ptr<const ModelHandle> model;
  std::unique_ptr<FmuLayout> layout;
  std::vector<double> p, x, x0, u;
  // Parameters the master set to a value of its own: ensemble_member leaves them as set,
  // whichever comes first (fmpy sets start values in modelDescription order, the parameters
  // before ensemble_member). Setting a parameter to the value it holds (its start value, as a
  // master applying every start value does) is no choice of its own.
  std::vector<bool> p_chosen;
  std::vector<double> du[3];  // the inputs' first, second and third derivatives
  std::vector<double> k1, k2, k3, k4, xs, u0, u_mid, u1;  // a step's scratch, sized once
  int member = 0;
  double max_step = 0.0;
  double time = 0.0;
  Phase phase = Phase::kInstantiated;
  std::string last_error;
};

fmi2Status Fail(Instance* instance, fmi2Status status, const std::string& message) {
  instance->last_error = message;
  if (status == fmi2Error || status == fmi2Fatal) instance->phase = Phase::kError;
  if (instance->logger != nullptr) {
    instance->logger(instance->environment, instance->name.c_str(), status, "logStatusError",
                     "%s", message.c_str());
  }
  return status;
}

// "file:///a/b%20c" -> "/a/b c" (RFC 3986 percent-decoding; "file:/a" too).
std::string PathOfUri(const std::string& uri) {
  std::string path = uri;
  if (path.rfind("file://", 0) == 0) {
    path = path.substr(7);
  } else if (path.rfind("file:", 0) == 0) {
    path = path.substr(5);
  }
  std::string decoded;
  for (size_t i = 0; i < path.size(); ++i) {
    if (path[i] == '%' && i + 2 < path.size()) {
      decoded += static_cast<char>(std::stoi(path.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += path[i];
    }
  }
  return decoded;
}

// The inputs at `t` within the step that started at instance->time (Horner form).
void InputsAt(const Instance& instance, double t, std::vector<double>* u) {
  const double tau = t - instance.time;
  for (size_t i = 0; i < u->size(); ++i) {
    (*u)[i] = instance.u[i] +
              tau * (instance.du[0][i] +
                     tau * (instance.du[1][i] / 2.0 + tau * (instance.du[2][i] / 6.0)));
  }
}

// One RK4 step of the state from the inputs u0, u_mid, u1, as engine/model/rk4.h takes it
// (the same arithmetic, in double).
bool Rk4(Instance* instance, double h) {
  std::vector<double>* x = &instance->x;
  std::vector<double>&k1 = instance->k1, &k2 = instance->k2, &k3 = instance->k3,
                      &k4 = instance->k4, &xs = instance->xs;
  const double *u0 = instance->u0.data(), *u_mid = instance->u_mid.data(),
               *u1 = instance->u1.data();
  const size_t n = x->size();
  const double* p = instance->p.data();
  const ModelHandle& model = *instance->model;
  if (!model.Derivative(x->data(), u0, p, k1.data())) return false;
  const double half_h = 0.5 * h;
  for (size_t i = 0; i < n; ++i) xs[i] = (*x)[i] + half_h * k1[i];
  if (!model.Derivative(xs.data(), u_mid, p, k2.data())) return false;
  for (size_t i = 0; i < n; ++i) xs[i] = (*x)[i] + half_h * k2[i];
  if (!model.Derivative(xs.data(), u_mid, p, k3.data())) return false;
  for (size_t i = 0; i < n; ++i) xs[i] = (*x)[i] + h * k3[i];
  if (!model.Derivative(xs.data(), u1, p, k4.data())) return false;
  const double sixth_h = h / 6.0;
  for (size_t i = 0; i < n; ++i) (*x)[i] += sixth_h * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  return true;
}

Instance* Of(fmi2Component c) { return static_cast<Instance*>(c); }

// The instance as fmi2Instantiate leaves it (and fmi2Reset): the run's parameter values and
// step bound, states and inputs zero, ensemble member 0.
void Start(Instance* instance) {
  const IdentifiedModel& m = instance->exported;
  instance->p = m.values;
  instance->p_chosen.assign(m.values.size(), false);
  instance->x0.assign(m.states.size(), 0.0);
  instance->u.assign(m.inputs.size(), 0.0);
  for (std::vector<double>& d : instance->du) d.assign(m.inputs.size(), 0.0);
  instance->max_step = m.max_step;
  instance->member = 0;
  instance->time = 0.0;
  instance->phase = Phase::kInstantiated;
}

}  // namespace
}  // namespace vesselid

using vesselid::FmuLayout;
using vesselid::Instance;
using vesselid::Phase;

extern "C" {

const char* fmi2GetTypesPlatform(void) { return "default"; }
const char* fmi2GetVersion(void) { return "2.0"; }

fmi2Status fmi2SetDebugLogging(fmi2Component, fmi2Boolean, size_t, const fmi2String[]) {
  return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions* functions, fmi2Boolean, fmi2Boolean) {
  auto instance = std::make_unique<Instance>();
  instance->name = instanceName != nullptr ? instanceName : "vesselid";
  if (functions != nullptr) {
    instance->logger = functions->logger;
    instance->environment = functions->componentEnvironment;
  }
  if (fmuType != fmi2CoSimulation) {
    vesselid::Fail(instance.get(), fmi2Error, "only co-simulation is supported");
    return nullptr;
  }
  if (fmuResourceLocation == nullptr) {
    vesselid::Fail(instance.get(), fmi2Error, "no resource location");
    return nullptr;
  }
  const std::string path = vesselid::PathOfUri(fmuResourceLocation) + "/model.json";
  std::ifstream in(path);
  std::string error;
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !vesselid::IdentifiedModelFromJson(j, &instance->exported, &error)) {
    vesselid::Fail(instance.get(), fmi2Error, path + ": " + (error.empty() ? "not JSON" : error));
    return nullptr;
  }
  const vesselid::IdentifiedModel& m = instance->exported;
  instance->model = vesselid::DefaultRegistry().MakeModel(m.family, m.options, &error);
  if (instance->model == nullptr) {
    vesselid::Fail(instance.get(), fmi2Error, path + ": " + error);
    return nullptr;
  }
  instance->layout = std::make_unique<FmuLayout>(m);
  for (auto* v : {&instance->k1, &instance->k2, &instance->k3, &instance->k4, &instance->xs}) {
    v->assign(m.states.size(), 0.0);
  }
  for (auto* v : {&instance->u0, &instance->u_mid, &instance->u1}) v->assign(m.inputs.size(), 0.0);
  vesselid::Start(instance.get());
  return instance.release();
}

void fmi2FreeInstance(fmi2Component c) { delete vesselid::Of(c); }

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean, fmi2Real, fmi2Real startTime,
                               fmi2Boolean, fmi2Real) {
  vesselid::Of(c)->time = startTime;
  return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  vesselid::Of(c)->phase = Phase::kInitialization;
  return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  Instance* instance = vesselid::Of(c);
  instance->x = instance->x0;
  instance->phase = Phase::kStepping;
  return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c) {
  vesselid::Of(c)->phase = Phase::kTerminated;
  return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c) {
  vesselid::Start(vesselid::Of(c));
  return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[]) {
  Instance* instance = vesselid::Of(c);
  const FmuLayout& l = *instance->layout;
  const std::vector<double>& x = instance->phase == Phase::kStepping ||
                                         instance->phase == Phase::kTerminated
                                     ? instance->x
                                     : instance->x0;
  std::vector<double> y(instance->exported.outputs.size());
  instance->model->Output(x.data(), instance->u.data(), instance->p.data(), y.data());
  for (size_t k = 0; k < nvr; ++k) {
    const int r = static_cast<int>(vr[k]);
    if (r < l.first_output) {
      value[k] = instance->u[r - l.first_input];
    } else if (r < l.first_state_output) {
      value[k] = y[r - l.first_output];
    } else if (r < l.first_parameter) {
      value[k] = x[l.state_outputs[r - l.first_state_output]];
    } else if (r < l.first_initial_state) {
      value[k] = instance->p[r - l.first_parameter];
    } else if (r < l.max_step) {
      value[k] = instance->x0[r - l.first_initial_state];
    } else if (r == l.max_step) {
      value[k] = instance->max_step;
    } else {
      return vesselid::Fail(instance, fmi2Error, "no Real of value reference " + std::to_string(r));
    }
  }
  return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[]) {
  Instance* instance = vesselid::Of(c);
  const FmuLayout& l = *instance->layout;
  for (size_t k = 0; k < nvr; ++k) {
    const int r = static_cast<int>(vr[k]);
    if (r < l.first_output) {
      instance->u[r - l.first_input] = value[k];
      // A new value holds until its derivatives are set.
      for (std::vector<double>& d : instance->du) d[r - l.first_input] = 0.0;
    } else if (r >= l.first_parameter && r < l.first_initial_state) {
      const size_t i = r - l.first_parameter;
      if (value[k] != instance->p[i]) instance->p_chosen[i] = true;
      instance->p[i] = value[k];
    } else if (r >= l.first_initial_state && r < l.max_step &&
               instance->phase != Phase::kStepping) {
      instance->x0[r - l.first_initial_state] = value[k];
    } else if (r == l.max_step && instance->phase != Phase::kStepping) {
      instance->max_step = value[k];
    } else {
      return vesselid::Fail(instance, fmi2Error,
                            "value reference " + std::to_string(r) + " cannot be set now");
    }
  }
  return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[]) {
  Instance* instance = vesselid::Of(c);
  for (size_t k = 0; k < nvr; ++k) {
    if (vr[k] != FmuLayout::kEnsembleMember) {
      return vesselid::Fail(instance, fmi2Error, "no Integer of value reference " +
                                                     std::to_string(vr[k]));
    }
    value[k] = instance->member;
  }
  return fmi2OK;
}

// ensemble_member k > 0 sets every parameter the master has not chosen (p_chosen) to the k-th
// draw, 0 to the estimate.
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[]) {
  Instance* instance = vesselid::Of(c);
  const vesselid::IdentifiedModel& m = instance->exported;
  for (size_t k = 0; k < nvr; ++k) {
    if (vr[k] != FmuLayout::kEnsembleMember || instance->phase == Phase::kStepping) {
      return vesselid::Fail(instance, fmi2Error, "Integer " + std::to_string(vr[k]) +
                                                     " cannot be set now");
    }
    if (value[k] < 0 || value[k] > static_cast<int>(m.ensemble.size())) {
      return vesselid::Fail(instance, fmi2Error,
                            "ensemble_member " + std::to_string(value[k]) + " is not in [0, " +
                                std::to_string(m.ensemble.size()) + "]");
    }
    instance->member = value[k];
    const std::vector<double>& source = value[k] == 0 ? m.values : m.ensemble[value[k] - 1];
    for (size_t i = 0; i < source.size(); ++i) {
      if (!instance->p_chosen[i]) instance->p[i] = source[i];
    }
  }
  return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr,
                          fmi2Boolean[]) {
  return nvr == 0 ? fmi2OK : vesselid::Fail(vesselid::Of(c), fmi2Error, "no Boolean variables");
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr,
                          const fmi2Boolean[]) {
  return nvr == 0 ? fmi2OK : vesselid::Fail(vesselid::Of(c), fmi2Error, "no Boolean variables");
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2String[]) {
  return nvr == 0 ? fmi2OK : vesselid::Fail(vesselid::Of(c), fmi2Error, "no String variables");
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference[], size_t nvr,
                         const fmi2String[]) {
  return nvr == 0 ? fmi2OK : vesselid::Fail(vesselid::Of(c), fmi2Error, "no String variables");
}

// Not offered (canGetAndSetFMUstate and providesDirectionalDerivative are false).
fmi2Status fmi2GetFMUstate(fmi2Component, fmi2FMUstate*) { return fmi2Error; }
fmi2Status fmi2SetFMUstate(fmi2Component, fmi2FMUstate) { return fmi2Error; }
fmi2Status fmi2FreeFMUstate(fmi2Component, fmi2FMUstate*) { return fmi2Error; }
fmi2Status fmi2SerializedFMUstateSize(fmi2Component, fmi2FMUstate, size_t*) { return fmi2Error; }
fmi2Status fmi2SerializeFMUstate(fmi2Component, fmi2FMUstate, fmi2Byte[], size_t) {
  return fmi2Error;
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component, const fmi2Byte[], size_t, fmi2FMUstate*) {
  return fmi2Error;
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component, const fmi2ValueReference[], size_t,
                                        const fmi2ValueReference[], size_t, const fmi2Real[],
                                        fmi2Real[]) {
  return fmi2Error;
}

// Derivatives of orders 1 to 3 of the inputs at the communication point (canInterpolateInputs).
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
  Instance* instance = vesselid::Of(c);
  const FmuLayout& l = *instance->layout;
  for (size_t k = 0; k < nvr; ++k) {
    const int r = static_cast<int>(vr[k]);
    if (r >= l.first_output || order[k] < 1 || order[k] > 3) {
      return vesselid::Fail(instance, fmi2Error,
                            "derivatives of orders 1 to 3 of inputs only can be set");
    }
    instance->du[order[k] - 1][r - l.first_input] = value[k];
  }
  return fmi2OK;
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                        const fmi2Integer[], fmi2Real[]) {
  return vesselid::Fail(vesselid::Of(c), fmi2Error, "output derivatives are not provided");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean) {
  Instance* instance = vesselid::Of(c);
  if (instance->phase != Phase::kStepping) {
    return vesselid::Fail(instance, fmi2Error, "fmi2DoStep before fmi2ExitInitializationMode");
  }
  const double H = communicationStepSize;
  if (!(H > 0.0)) return vesselid::Fail(instance, fmi2Error, "communication step must be > 0");
  instance->time = currentCommunicationPoint;
  // Equal steps of at most max_step (engine/model/experiment.cc, BuildExperiment).
  const int m = instance->max_step > 0.0
                    ? static_cast<int>(std::max(1.0, std::ceil(H / instance->max_step - 1e-6)))
                    : 1;
  const double h = H / m;
  for (int s = 0; s < m; ++s) {
    const double t = instance->time + s * h;
    vesselid::InputsAt(*instance, t, &instance->u0);
    vesselid::InputsAt(*instance, instance->time + (s + 0.5) * h, &instance->u_mid);
    vesselid::InputsAt(*instance, s + 1 == m ? instance->time + H : t + h, &instance->u1);
    if (!vesselid::Rk4(instance, h)) {
      return vesselid::Fail(instance, fmi2Error, "the model rejects its state at t = " +
                                                     std::to_string(t) + " s");
    }
  }
  for (double v : instance->x) {
    if (!std::isfinite(v)) {
      return vesselid::Fail(instance, fmi2Error,
                            "the state is not finite at t = " +
                                std::to_string(instance->time + H) + " s (the simulation diverged)");
    }
  }
  // The inputs now stand at the end of the step, held until the master sets the next ones.
  vesselid::InputsAt(*instance, instance->time + H, &instance->u);
  for (std::vector<double>& d : instance->du) std::fill(d.begin(), d.end(), 0.0);
  instance->time += H;
  return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component) { return fmi2Error; }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status* value) {
  *value = vesselid::Of(c)->phase == Phase::kError ? fmi2Error : fmi2OK;
  return fmi2OK;
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  if (s != fmi2LastSuccessfulTime) return fmi2Discard;
  *value = vesselid::Of(c)->time;
  return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component, const fmi2StatusKind, fmi2Integer*) {
  return fmi2Discard;
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  if (s != fmi2Terminated) return fmi2Discard;
  *value = vesselid::Of(c)->phase == Phase::kTerminated ? fmi2True : fmi2False;
  return fmi2OK;
}
fmi2Status fmi2GetStringStatus(fmi2Component, const fmi2StatusKind, fmi2String*) {
  return fmi2Discard;
}

}  // extern "C"
