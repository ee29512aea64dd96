#include "engine/output/step_regression_writer.h"

#include <cstdio>
#include <filesystem>

#include "engine/base/atomic_file.h"
#include "engine/base/file_name.h"
#include "engine/base/json_number.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string Row(std::initializer_list<double> values) {
  std::string out;
  char field[32];
  for (double v : values) {
    std::snprintf(field, sizeof(field), "%.10g", v);
    out += (out.empty() ? "" : ",") + std::string(field);
  }
  return out + "\n";
}

std::string DampingCsv(const StepSamples& s, const std::vector<std::string>& names) {
  std::string out = "t," + names[0] + "," + names[1] +
                    ",sigma_0,sigma_1,duration,turns,weight,group,mirrored\n";
  for (const DampingSample& d : s.damping) {
    out += Row({d.t, d.x[0], d.x[1], d.sigma[0], d.sigma[1], d.duration, d.turns, d.weight,
                static_cast<double>(d.group), d.mirrored ? 1.0 : 0.0});
  }
  return out;
}

std::string InertiaCsv(const StepSamples& s, const std::vector<std::string>& names) {
  std::string out = "term,t," + names[0] + "," + names[1] +
                    ",inertia,gain,time_constant,fit_rms,group,mirrored\n";
  for (int i = 0; i < 2; ++i) {
    for (const InertiaSample& m : s.inertia[i]) {
      out += Row({static_cast<double>(i), m.t, m.x[0], m.x[1], m.inertia, m.gain,
                  m.time_constant, m.rms, static_cast<double>(m.group), m.mirrored ? 1.0 : 0.0});
    }
  }
  return out;
}

std::string PathCsv(const TermRegression& t) {
  std::string out = "lambda,cv_error,cv_standard_error,nonzero";
  for (int k = 0; k < t.path.beta.cols(); ++k) out += ",b" + std::to_string(k);
  out += "\n";
  char field[32];
  for (size_t p = 0; p < t.path.lambda.size(); ++p) {
    std::string row = Row({t.path.lambda[p], t.path.cv_error[p], t.path.cv_standard_error[p],
                           static_cast<double>(t.path.nonzero[p])});
    row.pop_back();
    for (int k = 0; k < t.path.beta.cols(); ++k) {
      std::snprintf(field, sizeof(field), ",%.10g", t.path.beta(p, k));
      row += field;
    }
    out += row + "\n";
  }
  return out;
}

std::string AsymptoteCsv(const TermRegression& t) {
  std::string out = "a,b,cv_error,lambda\n";
  for (const TermRegression::AsymptoteCv& g : t.asymptote_grid) {
    out += Row({g.a, g.b, g.cv_error, g.lambda});
  }
  return out;
}

// sigma_i and m_i on the grid, one row per point, the second state varying fastest.
std::string SurfacesCsv(const DampingInertiaForm& form, const std::vector<std::string>& names,
                        const double* p, const SurfaceGrid& grid) {
  std::string out = names[0] + "," + names[1];
  for (const std::string& name : form.term_names) out += "," + name;
  out += "\n";
  for (int i = 0; i < grid.points[0]; ++i) {
    for (int j = 0; j < grid.points[1]; ++j) {
      double x[2];
      const int at[2] = {i, j};
      for (int c = 0; c < 2; ++c) {
        x[c] = grid.points[c] == 1 ? grid.lower[c]
                                   : grid.lower[c] + (grid.upper[c] - grid.lower[c]) * at[c] /
                                                         (grid.points[c] - 1);
      }
      double sigma[2], m[2];
      EvaluateDampingInertia(form, p, x, sigma, m);
      out += Row({x[0], x[1], sigma[0], sigma[1], m[0], m[1]});
    }
  }
  return out;
}

}  // namespace

json StepRegressionToJson(const StepRegressionReport& report) {
  json terms = json::array();
  for (const TermRegression& t : report.terms) {
    json j = {{"name", t.name},
              {"samples", t.samples},
              {"groups", t.groups},
              {"normalisation",
               {{"mean_x", {t.mean_x[0], t.mean_x[1]}},
                {"sd_x", {t.sd_x[0], t.sd_x[1]}},
                {"mean_y", t.mean_y},
                {"sd_y", t.sd_y}}},
              {"lambda", t.lambda},
              {"cv_error", JsonNumber(t.path.cv_error[t.path.best])},
              {"cv_standard_error", JsonNumber(t.path.cv_standard_error[t.path.best])},
              {"nonzero", t.path.nonzero[t.path.best]},
              {"path_points", t.path.lambda.size()},
              {"r2", JsonNumber(t.r2)},
              {"rms", t.rms},
              {"seconds", t.seconds}};
    if (!t.asymptote_grid.empty()) {
      j["a"] = t.a;
      j["b"] = t.b;
      j["asymptote_grid_points"] = t.asymptote_grid.size();
    }
    terms.push_back(j);
  }
  const StepSamples& s = report.samples;
  return {{"damping_samples", s.damping.size()},
          {"inertia_samples", {s.inertia[0].size(), s.inertia[1].size()}},
          {"intervals", s.intervals},
          {"steady_intervals", s.steady},
          {"steps", s.steps},
          {"terms", terms},
          {"seconds",
           {{"steady_state_windows", s.window_seconds},
            {"step_fits", s.fit_seconds},
            {"normalisation", report.normalisation_seconds},
            {"lasso_cross_validation", report.regression_seconds}}}};
}

bool WriteStepRegressionFiles(const RunConfig& config, const RunResult& result,
                              const std::string& out_dir, std::string* error) {
  const ModelHandle& model = *config.model;
  const DampingInertiaForm* form = model.damping_inertia_form();
  if (form == nullptr) return true;
  const ModelInfo& info = model.info();
  const std::vector<std::string> names = {info.states[form->states[0]],
                                          info.states[form->states[1]]};
  auto write = [&](const std::string& name, const std::string& text) {
    return WriteFileAtomically((fs::path(out_dir) / name).string(), text, error);
  };
  for (const StageResult& stage : result.stages) {
    if (!stage.step_regression) continue;
    const StepRegressionReport& r = *stage.step_regression;
    const std::string prefix = FileNameOf(stage.name);
    if (!write(prefix + ".damping_samples.csv", DampingCsv(r.samples, names)) ||
        !write(prefix + ".inertia_samples.csv", InertiaCsv(r.samples, names))) {
      return false;
    }
    for (const TermRegression& t : r.terms) {
      if (!write(prefix + ".lasso_" + t.name + ".csv", PathCsv(t))) return false;
      if (!t.asymptote_grid.empty() &&
          !write(prefix + ".asymptote_" + t.name + ".csv", AsymptoteCsv(t))) {
        return false;
      }
    }
  }
  if (!config.surfaces.enabled()) return true;
  std::error_code ec;
  fs::create_directories(fs::path(out_dir) / "surfaces", ec);
  if (ec) {
    *error = out_dir + "/surfaces: cannot create folder: " + ec.message();
    return false;
  }
  for (const StageResult& stage : result.stages) {
    const std::vector<double> values = StageParameterValues(info, stage);
    if (values.size() != info.parameters.size()) continue;
    if (!write("surfaces/" + FileNameOf(stage.name) + ".csv",
               SurfacesCsv(*form, names, values.data(), config.surfaces))) {
      return false;
    }
  }
  std::vector<double> final_values;
  for (const FinalParameter& f : result.parameters) final_values.push_back(f.value);
  return final_values.size() != info.parameters.size() ||
         write("surfaces/final.csv",
               SurfacesCsv(*form, names, final_values.data(), config.surfaces));
}

}  // namespace vesselid
