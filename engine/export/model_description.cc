#include "engine/export/model_description.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "engine/export/fmu_layout.h"

namespace vesselid {
namespace {

// Text for an XML attribute value.
std::string Escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// A double as xs:double text that reads back to the same value.
std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", v);
  return text;
}

std::string UnitAttribute(const std::string& unit) {
  return unit.empty() ? "" : " unit=\"" + Escaped(unit) + "\"";
}

}  // namespace

std::string ModelDescriptionXml(const IdentifiedModel& m, const std::string& guid) {
  const FmuLayout layout(m);
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"" << Escaped(m.model)
      << "\" guid=\"" << guid << "\" description=\"" << Escaped(m.family) << " model identified by vesselid ("
      << Escaped(m.results) << ")\" generationTool=\"vesselid 0.1.0\""
      << " variableNamingConvention=\"flat\" numberOfEventIndicators=\"0\">\n"
      << "  <CoSimulation modelIdentifier=\"" << kFmuModelIdentifier
      << "\" canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"true\""
      << " maxOutputDerivativeOrder=\"0\" canGetAndSetFMUstate=\"false\""
      << " canSerializeFMUstate=\"false\" providesDirectionalDerivative=\"false\"/>\n";
  std::set<std::string> units = {"s"};  // max_step's
  for (const auto* list : {&m.states, &m.inputs, &m.outputs, &m.parameters}) {
    for (const ModelVariable& v : *list) {
      if (!v.unit.empty()) units.insert(v.unit);
    }
  }
  if (!units.empty()) {
    xml << "  <UnitDefinitions>\n";
    for (const std::string& unit : units) xml << "    <Unit name=\"" << Escaped(unit) << "\"/>\n";
    xml << "  </UnitDefinitions>\n";
  }
  xml << "  <DefaultExperiment startTime=\"0\"";
  if (m.max_step > 0.0) xml << " stepSize=\"" << Number(m.max_step) << "\"";
  xml << "/>\n  <ModelVariables>\n";
  int index = 0;  // 1-based position of each variable (ModelStructure refers to it)
  std::vector<int> outputs;
  auto variable = [&](const std::string& name, int reference, const std::string& causality,
                      const std::string& variability, const std::string& initial,
                      const std::string& description, const std::string& type) {
    ++index;
    xml << "    <ScalarVariable name=\"" << Escaped(name) << "\" valueReference=\"" << reference
        << "\" causality=\"" << causality << "\" variability=\"" << variability << "\"";
    if (!initial.empty()) xml << " initial=\"" << initial << "\"";
    xml << " description=\"" << Escaped(description) << "\">\n      " << type
        << "\n    </ScalarVariable>\n";
  };
  for (size_t i = 0; i < m.inputs.size(); ++i) {
    variable(m.inputs[i].name, layout.first_input + static_cast<int>(i), "input", "continuous", "",
             "model input", "<Real start=\"0\"" + UnitAttribute(m.inputs[i].unit) + "/>");
  }
  for (size_t i = 0; i < m.outputs.size(); ++i) {
    variable(m.outputs[i].name, layout.first_output + static_cast<int>(i), "output",
             "continuous", "calculated", "model output",
             "<Real" + UnitAttribute(m.outputs[i].unit) + "/>");
    outputs.push_back(index);
  }
  for (size_t k = 0; k < layout.state_outputs.size(); ++k) {
    const ModelVariable& state = m.states[layout.state_outputs[k]];
    variable(state.name, layout.first_state_output + static_cast<int>(k), "output", "continuous",
             "calculated", "model state", "<Real" + UnitAttribute(state.unit) + "/>");
    outputs.push_back(index);
  }
  for (size_t i = 0; i < m.parameters.size(); ++i) {
    std::string description = "identified parameter";
    if (std::isfinite(m.std_errors[i])) description += ", standard error " + Number(m.std_errors[i]);
    variable(m.parameters[i].name, layout.first_parameter + static_cast<int>(i), "parameter",
             "tunable", "exact", description,
             "<Real start=\"" + Number(m.values[i]) + "\"" + UnitAttribute(m.parameters[i].unit) +
                 "/>");
  }
  for (size_t i = 0; i < m.states.size(); ++i) {
    variable("initial_" + m.states[i].name, layout.first_initial_state + static_cast<int>(i),
             "parameter", "fixed", "exact", "initial value of the state " + m.states[i].name,
             "<Real start=\"0\"" + UnitAttribute(m.states[i].unit) + "/>");
  }
  variable("max_step", layout.max_step, "parameter", "fixed", "exact",
           "RK4 steps of at most this length within a communication step (0: one step)",
           "<Real start=\"" + Number(m.max_step) + "\" unit=\"s\"/>");
  variable("ensemble_member", FmuLayout::kEnsembleMember, "parameter", "fixed", "exact",
           "0: the estimate; k: the k-th parameter draw from the covariance (a parameter the "
           "master sets to a value of its own keeps it, set before or after)",
           "<Integer start=\"0\" min=\"0\" max=\"" + std::to_string(m.ensemble.size()) + "\"/>");
  xml << "  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n";
  for (int i : outputs) xml << "      <Unknown index=\"" << i << "\"/>\n";
  xml << "    </Outputs>\n    <InitialUnknowns>\n";
  for (int i : outputs) xml << "      <Unknown index=\"" << i << "\"/>\n";
  xml << "    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n";
  return xml.str();
}

}  // namespace vesselid
