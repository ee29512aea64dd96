// The partition study as text and JSON (partition_study.h): a split's case record and back,
// and tables (a), (b) and the parameter spread of a least-squares or output-error stage.
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "engine/base/format_numbers.h"
#include "engine/base/json_number.h"
#include "engine/base/nan.h"
#include "engine/base/statistics.h"
#include "engine/study/partition_study.h"

namespace vesselid {
namespace {

using nlohmann::json;

bool OutputError(const StudyResult& result) { return result.kind == "output_error"; }

const std::vector<ChannelMetrics>& Metrics(const PartitionOutcome& o, const std::string& part) {
  return part == "training"      ? o.training
         : part == "validation"  ? o.validation
         : part == "persistence" ? o.persistence
                                 : o.free_run;
}

// mae, rmse, r2 or fit_percent of a channel; NaN without samples.
double MetricValue(const ChannelMetrics& m, const std::string& metric) {
  if (m.samples == 0) return kNaN;
  return metric == "mae" ? m.mae : metric == "rmse" ? m.rmse : metric == "r2" ? m.r2 : m.fit_percent;
}

// A metric of one channel in one part over the usable splits of `outcomes`: mean and SD of
// the finite values.
MeanSd MetricSpread(const std::vector<const PartitionOutcome*>& outcomes, const std::string& part,
                    const std::string& channel, const std::string& metric) {
  std::vector<double> values;
  for (const PartitionOutcome* o : outcomes) {
    if (!o->usable) continue;
    for (const ChannelMetrics& m : Metrics(*o, part)) {
      if (m.output == channel) values.push_back(MetricValue(m, metric));
    }
  }
  return Summarise(values);
}

MeanSd ParameterSpread(const std::vector<const PartitionOutcome*>& outcomes, size_t index) {
  std::vector<double> values;
  for (const PartitionOutcome* o : outcomes) {
    if (o->usable) values.push_back(o->parameters[index]);
  }
  return Summarise(values);
}

std::vector<const PartitionOutcome*> OfMethod(const std::vector<PartitionOutcome>& outcomes,
                                              const std::string& method) {
  std::vector<const PartitionOutcome*> selected;
  for (const PartitionOutcome& o : outcomes) {
    if (o.method == method) selected.push_back(&o);
  }
  return selected;
}

std::string MeanSdText(const MeanSd& s) {
  if (s.n == 0) return "-";
  return FormatNumbers("%.4g", s.mean) + (std::isfinite(s.sd) ? FormatNumbers(" ± %.2g", s.sd) : "");
}

std::string Pad(const std::string& text, size_t width) {
  // The width counts characters; "±" takes two bytes.
  size_t length = 0;
  for (char ch : text) length += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
  return text + std::string(width > length ? width - length : 1, ' ');
}

double DoubleOr(const json& j, const char* key, double fallback) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

json SpreadToJson(const MeanSd& s) {
  return {{"n", s.n}, {"mean", JsonNumber(s.mean)}, {"sd", JsonNumber(s.sd)}};
}

// Metrics of a least-squares split: mae, rmse, r2; of an output-error one also fit %.
json MetricsToJson(const std::vector<ChannelMetrics>& metrics, bool fit_percent) {
  json j = json::object();
  for (const ChannelMetrics& m : metrics) {
    j[m.output] = {{"samples", m.samples},
                   {"mae", JsonNumber(MetricValue(m, "mae"))},
                   {"rmse", JsonNumber(MetricValue(m, "rmse"))},
                   {"r2", JsonNumber(MetricValue(m, "r2"))}};
    if (fit_percent) j[m.output]["fit_percent"] = JsonNumber(MetricValue(m, "fit_percent"));
  }
  return j;
}

// The channels of `result` present in `j` (MetricsToJson), labelled `label`.
std::vector<ChannelMetrics> MetricsFromJson(const StudyResult& result, const json& j,
                                            const std::string& label) {
  std::vector<ChannelMetrics> metrics;
  if (!j.is_object()) return metrics;
  for (const std::string& channel : result.channels) {
    if (!j.contains(channel)) continue;
    const json& c = j[channel];
    ChannelMetrics m;
    m.experiment = label;
    m.output = channel;
    m.samples = c.value("samples", 0);
    m.mae = DoubleOr(c, "mae", kNaN);
    m.rmse = DoubleOr(c, "rmse", kNaN);
    m.r2 = DoubleOr(c, "r2", kNaN);
    m.fit_percent = DoubleOr(c, "fit_percent", kNaN);
    metrics.push_back(m);
  }
  return metrics;
}

// Part of a split's record: {part: {key: metrics}} or null.
const json& PartOf(const json& j, const char* part, const char* key) {
  static const json none;
  if (!j.is_object() || !j.contains(part) || !j[part].is_object()) return none;
  const json& p = j[part];
  return p.contains(key) ? p[key] : none;
}

// Split rows, failures and parameter spread shared by both kinds ----------------------------

void FailedSplits(const StudyResult& result, std::vector<std::string>* failures) {
  for (const std::string& method : result.options.methods) {
    for (const PartitionOutcome* a : OfMethod(result.repeated, method)) {
      if (!a->message.empty()) {
        failures->push_back("(a) " + method + " seed " + std::to_string(a->seed) + ": " +
                            a->message);
      }
    }
  }
  for (const PartitionOutcome& b : result.shares) {
    if (!b.message.empty() && b.usable) {
      failures->push_back("(b) " + b.method + FormatNumbers(" share %.2f: ", b.training_share) +
                          b.message);
    }
  }
}

void ParameterTable(const StudyResult& result, std::ostringstream& out) {
  const StudyOptions& o = result.options;
  out << "\nparameters over the partitions of (a): mean ± SD (SD relative to |mean|)\n";
  out << Pad("parameter", 12);
  for (const std::string& method : o.methods) out << Pad(method, 32);
  out << "\n";
  for (size_t i = 0; i < result.parameters.size(); ++i) {
    out << Pad(result.parameters[i], 12);
    for (const std::string& method : o.methods) {
      const MeanSd s = ParameterSpread(OfMethod(result.repeated, method), i);
      std::string cell = result.held[i] ? FormatNumbers("%.4g (held)", s.mean) : MeanSdText(s);
      if (!result.held[i] && std::isfinite(s.sd)) {  // beyond 100 %: not even the sign
        const double relative = 100.0 * s.sd / std::abs(s.mean);
        cell += relative < 100.0 ? FormatNumbers(" (%.1f %%)", relative) : " (>100 %)";
      }
      out << Pad(cell, 32);
    }
    out << "\n";
  }
}

std::string PoolNames(const StudyOptions& o) {
  std::string pool;
  for (const std::string& name : o.experiments) pool += (pool.empty() ? "" : ", ") + name;
  return pool;
}

// Least squares --------------------------------------------------------------------------------

void LeastSquaresTables(const StudyResult& result, std::ostringstream& out) {
  const StudyOptions& o = result.options;
  out << "Partition study of stage '" << o.stage << "' (model " << result.model << ")\n"
      << "pool: " << PoolNames(o) << ": " << result.records << " records, " << result.samples
      << " samples; seed " << o.seed << "\n";
  if (result.duplicates > 0) {
    out << result.duplicates << " records listed twice in the pool (same file and window) "
        << "counted once\n";
  }
  out << "one-step: x(k+1) predicted from the data at k, each equation on its own regions;\n"
      << "free-run: held-out segments simulated whole; x(k+1)=x(k): one-step without a model\n";

  // (a)
  out << "\n(a) " << o.partitions << " random partitions, training "
      << FormatNumbers("%.0f %%", 100.0 * (1.0 - o.validation_share)) << " / validation "
      << FormatNumbers("%.0f %%", 100.0 * o.validation_share)
      << ": validation metrics, mean ± SD over the partitions\n";
  out << Pad("method", 10) << Pad("metric", 13) << Pad("n", 4);
  for (const char* metric : {"MAE", "R2"}) {
    for (const std::string& s : result.channels) out << Pad(std::string(metric) + " " + s, 20);
  }
  out << "\n";
  for (const std::string& method : o.methods) {
    const auto outcomes = OfMethod(result.repeated, method);
    for (const std::string part : {"validation", "free_run", "persistence"}) {
      if (part == "free_run" && method != "segments") continue;
      const MeanSd count = MetricSpread(outcomes, part, result.channels.front(), "r2");
      const std::string label = part == "validation" ? "one-step"
                                : part == "free_run" ? "free-run"
                                                     : "x(k+1)=x(k)";
      out << Pad(method, 10) << Pad(label, 13) << Pad(std::to_string(count.n), 4);
      for (const char* metric : {"mae", "r2"}) {
        for (const std::string& s : result.channels) {
          out << Pad(MeanSdText(MetricSpread(outcomes, part, s, metric)), 20);
        }
      }
      out << "\n";
    }
  }

  // (b)
  out << "\n(b) training share, validation " << FormatNumbers("%.0f %%", 100.0 * o.validation_share)
      << " (seed " << o.seed << "): one-step metrics\n";
  out << Pad("share", 7) << Pad("method", 10) << Pad("part", 12) << Pad("n", 7);
  for (const char* metric : {"MAE", "R2"}) {
    for (const std::string& s : result.channels) out << Pad(std::string(metric) + " " + s, 10);
  }
  out << "\n";
  for (const PartitionOutcome& b : result.shares) {
    for (const char* part : {"training", "validation"}) {
      out << Pad(FormatNumbers("%.2f", b.training_share), 7) << Pad(b.method, 10) << Pad(part, 12);
      if (!b.usable) {
        out << "failed: " << b.message << "\n";
        break;
      }
      out << Pad(std::to_string(std::string(part) == "training" ? b.training_samples
                                                                : b.validation_samples),
                 7);
      for (const char* metric : {"mae", "r2"}) {
        for (const std::string& s : result.channels) {
          double value = kNaN;
          for (const ChannelMetrics& m : Metrics(b, part)) {
            if (m.output == s) value = MetricValue(m, metric);
          }
          out << Pad(std::isfinite(value) ? FormatNumbers("%.4g", value) : "-", 10);
        }
      }
      out << "\n";
    }
  }
  out << "n: grid samples of the part; each equation is measured on those in its regions\n";
}

// Output error ---------------------------------------------------------------------------------

const char* const kOutputErrorMetrics[] = {"rmse", "mae", "r2", "fit_percent"};

void OutputErrorTables(const StudyResult& result, std::ostringstream& out) {
  const StudyOptions& o = result.options;
  out << "Partition study of output-error stage '" << o.stage << "' (model " << result.model
      << ")\n"
      << "pool: " << PoolNames(o) << ": " << result.records << " experiments (segments), "
      << result.samples << " samples; seed " << o.seed << "\n";
  if (result.duplicates > 0) {
    out << result.duplicates << " experiments listed twice in the pool (same file and window) "
        << "counted once\n";
  }
  out << "training: the stage solved on the training part as configured, metrics of its fit;\n"
      << "validation: segments: held-out experiments simulated with the fitted parameters "
         "(free initial\n"
      << "states estimated with them held); points: held-out samples of the fitted "
         "simulation\n";

  // (a)
  out << "\n(a) " << o.partitions << " random partitions, training "
      << FormatNumbers("%.0f %%", 100.0 * (1.0 - o.validation_share)) << " / validation "
      << FormatNumbers("%.0f %%", 100.0 * o.validation_share)
      << ": metrics, mean ± SD over the partitions\n";
  out << Pad("method", 10) << Pad("part", 12) << Pad("output", 8) << Pad("n", 4);
  for (const char* header : {"RMSE", "MAE", "R2", "fit %"}) out << Pad(header, 20);
  out << "\n";
  for (const std::string& method : o.methods) {
    const auto outcomes = OfMethod(result.repeated, method);
    for (const std::string part : {"training", "validation"}) {
      for (const std::string& c : result.channels) {
        out << Pad(method, 10) << Pad(part, 12) << Pad(c, 8)
            << Pad(std::to_string(MetricSpread(outcomes, part, c, "rmse").n), 4);
        for (const char* metric : kOutputErrorMetrics) {
          out << Pad(MeanSdText(MetricSpread(outcomes, part, c, metric)), 20);
        }
        out << "\n";
      }
    }
  }

  // (b)
  out << "\n(b) training share, validation " << FormatNumbers("%.0f %%", 100.0 * o.validation_share)
      << " (seed " << o.seed << ")\n";
  out << Pad("share", 7) << Pad("method", 10) << Pad("part", 12) << Pad("output", 8)
      << Pad("n", 8);
  for (const char* header : {"RMSE", "MAE", "R2", "fit %"}) out << Pad(header, 11);
  out << "\n";
  for (const PartitionOutcome& b : result.shares) {
    if (!b.usable) {
      out << Pad(FormatNumbers("%.2f", b.training_share), 7) << Pad(b.method, 10) << "failed: "
          << b.message << "\n";
      continue;
    }
    for (const char* part : {"training", "validation"}) {
      for (const std::string& c : result.channels) {
        const ChannelMetrics* found = nullptr;
        for (const ChannelMetrics& m : Metrics(b, part)) {
          if (m.output == c) found = &m;
        }
        out << Pad(FormatNumbers("%.2f", b.training_share), 7) << Pad(b.method, 10) << Pad(part, 12)
            << Pad(c, 8) << Pad(found != nullptr ? std::to_string(found->samples) : "-", 8);
        for (const char* metric : kOutputErrorMetrics) {
          const double value = found != nullptr ? MetricValue(*found, metric) : kNaN;
          out << Pad(std::isfinite(value) ? FormatNumbers("%.4g", value) : "-", 11);
        }
        out << "\n";
      }
    }
  }
  out << "n: compared samples of the part\n";
}

}  // namespace

namespace partition_internal {

json OutcomeToJson(const StudyResult& result, const PartitionOutcome& o) {
  json j = {{"method", o.method},
            {"seed", o.seed},
            {"training_share", o.training_share},
            {"usable", o.usable},
            {"message", o.message},
            {"time_seconds", o.time_seconds}};
  if (OutputError(result)) {
    j["training"] = {{"experiments", o.training_records},
                     {"samples", o.training_samples},
                     {"fit", MetricsToJson(o.training, true)},
                     {"cost", JsonNumber(o.cost)}};
    j["validation"] = {{"experiments", o.validation_records},
                       {"samples", o.validation_samples},
                       {"free_run", MetricsToJson(o.validation, true)}};
  } else {
    j["training"] = {{"records", o.training_records},
                     {"samples", o.training_samples},
                     {"one_step", MetricsToJson(o.training, false)}};
    j["validation"] = {{"records", o.validation_records},
                       {"samples", o.validation_samples},
                       {"one_step", MetricsToJson(o.validation, false)}};
    if (o.method == "segments") j["validation"]["free_run"] = MetricsToJson(o.free_run, false);
    j["validation"]["persistence"] = MetricsToJson(o.persistence, false);
  }
  json parameters = json::object();
  for (size_t i = 0; i < o.parameters.size(); ++i) {
    parameters[result.parameters[i]] = JsonNumber(o.parameters[i]);
  }
  j["parameters"] = parameters;
  return j;
}

PartitionOutcome OutcomeFromJson(const StudyResult& result, const json& j) {
  PartitionOutcome o;
  if (!j.is_object()) return o;
  o.method = j.value("method", "");
  o.seed = j.value("seed", 0u);
  o.training_share = DoubleOr(j, "training_share", kNaN);
  o.usable = j.value("usable", false);
  o.message = j.value("message", "");
  o.time_seconds = DoubleOr(j, "time_seconds", kNaN);
  const char* count = OutputError(result) ? "experiments" : "records";
  for (const char* part : {"training", "validation"}) {
    const json& p = j.contains(part) ? j[part] : json();
    const bool training = std::string(part) == "training";
    (training ? o.training_records : o.validation_records) = p.is_object() ? p.value(count, 0) : 0;
    (training ? o.training_samples : o.validation_samples) =
        p.is_object() ? p.value("samples", 0) : 0;
  }
  if (OutputError(result)) {
    o.training = MetricsFromJson(result, PartOf(j, "training", "fit"), "training");
    o.validation = MetricsFromJson(result, PartOf(j, "validation", "free_run"), "validation");
    o.cost = DoubleOr(j.contains("training") ? j["training"] : json(), "cost", kNaN);
  } else {
    o.training = MetricsFromJson(result, PartOf(j, "training", "one_step"), "training");
    o.validation = MetricsFromJson(result, PartOf(j, "validation", "one_step"), "validation");
    o.free_run = MetricsFromJson(result, PartOf(j, "validation", "free_run"), "free_run");
    o.persistence =
        MetricsFromJson(result, PartOf(j, "validation", "persistence"), "persistence");
  }
  const json& parameters = j.contains("parameters") ? j["parameters"] : json();
  if (parameters.is_object() && !parameters.empty()) {
    for (const std::string& name : result.parameters) {
      o.parameters.push_back(DoubleOr(parameters, name.c_str(), kNaN));
    }
  }
  return o;
}

}  // namespace partition_internal

std::string StudyResultToText(const StudyResult& result) {
  std::ostringstream out;
  if (OutputError(result)) {
    OutputErrorTables(result, out);
  } else {
    LeastSquaresTables(result, out);
  }
  ParameterTable(result, out);
  std::vector<std::string> failures;
  FailedSplits(result, &failures);
  if (!failures.empty()) {
    out << "\nfailed or incomplete splits:\n";
    for (const std::string& f : failures) out << "  " << f << "\n";
  }
  out << FormatNumbers("\ntime %.1f s\n", result.time_seconds);
  return out.str();
}

json StudyResultToJson(const StudyResult& result) {
  const StudyOptions& o = result.options;
  const bool oe = OutputError(result);
  json j;
  j["stage"] = o.stage;
  j["kind"] = result.kind;
  j["model"] = result.model;
  j["options"] = {{"experiments", o.experiments},
                  {"partitions", o.partitions},
                  {"validation_share", o.validation_share},
                  {"training_shares", o.training_shares},
                  {"methods", o.methods},
                  {"seed", o.seed}};
  j["pool"] = {{oe ? "experiments" : "records", result.records},
               {"samples", result.samples},
               {"duplicates", result.duplicates}};
  j[oe ? "outputs" : "states"] = result.channels;
  json parameters = json::array();
  for (size_t i = 0; i < result.parameters.size(); ++i) {
    parameters.push_back(
        {{"name", result.parameters[i]}, {"held", static_cast<bool>(result.held[i])}});
  }
  j["parameters"] = parameters;
  // Summary parts: (name in the outcome, key in the summary).
  const std::vector<std::pair<std::string, std::string>> parts =
      oe ? std::vector<std::pair<std::string, std::string>>{{"training", "training_fit"},
                                                            {"validation", "validation_free_run"}}
         : std::vector<std::pair<std::string, std::string>>{
               {"training", "training_one_step"},
               {"validation", "validation_one_step"},
               {"free_run", "free_run"},
               {"persistence", "persistence"}};
  const std::vector<std::string> metrics =
      oe ? std::vector<std::string>{"mae", "rmse", "r2", "fit_percent"}
         : std::vector<std::string>{"mae", "r2"};
  json repeated = json::object();
  for (const std::string& method : o.methods) {
    const auto outcomes = OfMethod(result.repeated, method);
    json m;
    json partitions = json::array();
    int failed = 0;
    for (const PartitionOutcome* a : outcomes) {
      partitions.push_back(partition_internal::OutcomeToJson(result, *a));
      failed += !a->usable;
    }
    m["partitions"] = partitions;
    m["failed"] = failed;
    json summary = json::object();
    for (const auto& [part, key] : parts) {
      if (part == "free_run" && method != "segments") continue;
      json channels = json::object();
      for (const std::string& c : result.channels) {
        for (const std::string& metric : metrics) {
          channels[c][metric] = SpreadToJson(MetricSpread(outcomes, part, c, metric));
        }
      }
      summary[key] = channels;
    }
    json spread = json::object();
    for (size_t i = 0; i < result.parameters.size(); ++i) {
      spread[result.parameters[i]] = SpreadToJson(ParameterSpread(outcomes, i));
    }
    summary["parameters"] = spread;
    m["summary"] = summary;
    repeated[method] = m;
  }
  j["repeated"] = repeated;
  json shares = json::array();
  for (const PartitionOutcome& b : result.shares) {
    shares.push_back(partition_internal::OutcomeToJson(result, b));
  }
  j["shares"] = shares;
  j["time_seconds"] = result.time_seconds;
  return j;
}

}  // namespace vesselid
