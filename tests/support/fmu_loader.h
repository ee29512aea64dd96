// A minimal FMI 2.0 co-simulation master for the tests: unpacks an FMU (libzip), reads the
// variables of its modelDescription.xml, dlopens binaries/linux64/<modelIdentifier>.so and
// calls its fmi2* functions as any master would (Instantiate, SetupExperiment, Enter/Exit
// InitializationMode, SetReal, SetRealInputDerivatives, DoStep, GetReal, Terminate,
// FreeInstance).
#pragma once

#include <dlfcn.h>
#include <zip.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "engine/export/fmi2.h"

namespace vesselid::testing {

struct FmuVariable {
  std::string name, causality, variability, type;
  unsigned reference = 0;
};

class FmuLoader {
 public:
  ~FmuLoader() {
    if (instance_ != nullptr) free_instance_(instance_);
    if (library_ != nullptr) dlclose(library_);
  }

  // Unpacks `fmu` into `folder` and loads its library; false with a message.
  bool Open(const std::string& fmu, const std::string& folder, std::string* error) {
    namespace fs = std::filesystem;
    fs::remove_all(folder);
    fs::create_directories(folder);
    int code = 0;
    zip_t* archive = zip_open(fmu.c_str(), ZIP_RDONLY, &code);
    if (archive == nullptr) {
      *error = fmu + ": not a zip archive";
      return false;
    }
    for (zip_int64_t i = 0; i < zip_get_num_entries(archive, 0); ++i) {
      zip_stat_t stat;
      zip_stat_index(archive, i, 0, &stat);
      const fs::path target = fs::path(folder) / stat.name;
      if (std::string(stat.name).back() == '/') continue;
      fs::create_directories(target.parent_path());
      zip_file_t* file = zip_fopen_index(archive, i, 0);
      std::string bytes(stat.size, '\0');
      zip_fread(file, bytes.data(), stat.size);
      zip_fclose(file);
      std::ofstream(target, std::ios::binary) << bytes;
    }
    zip_close(archive);
    std::ifstream in(fs::path(folder) / "modelDescription.xml");
    std::stringstream text;
    text << in.rdbuf();
    description_ = text.str();
    std::smatch match;
    if (!std::regex_search(description_, match, std::regex("modelIdentifier=\"([^\"]+)\""))) {
      *error = "modelDescription.xml: no modelIdentifier";
      return false;
    }
    const std::string library =
        (fs::path(folder) / "binaries" / "linux64" / (match[1].str() + ".so")).string();
    const std::regex variable(
        "<ScalarVariable name=\"([^\"]+)\" valueReference=\"([0-9]+)\" causality=\"([a-z]+)\" "
        "variability=\"([a-z]+)\"[^>]*>\\s*<(Real|Integer)");
    for (auto it = std::sregex_iterator(description_.begin(), description_.end(), variable);
         it != std::sregex_iterator(); ++it) {
      variables_.push_back({(*it)[1], (*it)[3], (*it)[4], (*it)[5],
                            static_cast<unsigned>(std::stoul((*it)[2]))});
    }
    resources_ = "file://" + (fs::absolute(folder) / "resources").string();
    library_ = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (library_ == nullptr) {
      *error = library + ": " + dlerror();
      return false;
    }
    bool found = true;
    auto get = [&](auto* function, const char* name) {
      *function = reinterpret_cast<std::remove_pointer_t<decltype(function)>>(dlsym(library_, name));
      found &= *function != nullptr;
    };
    get(&instantiate_, "fmi2Instantiate");
    get(&free_instance_, "fmi2FreeInstance");
    get(&setup_, "fmi2SetupExperiment");
    get(&enter_, "fmi2EnterInitializationMode");
    get(&exit_, "fmi2ExitInitializationMode");
    get(&terminate_, "fmi2Terminate");
    get(&set_real_, "fmi2SetReal");
    get(&get_real_, "fmi2GetReal");
    get(&set_integer_, "fmi2SetInteger");
    get(&derivatives_, "fmi2SetRealInputDerivatives");
    get(&do_step_, "fmi2DoStep");
    get(&version_, "fmi2GetVersion");
    if (!found) {
      *error = library + ": an fmi2 function is missing";
      return false;
    }
    return true;
  }

  const std::string& description() const { return description_; }
  const std::vector<FmuVariable>& variables() const { return variables_; }
  const char* Version() const { return version_(); }

  // The Real (or Integer) variable `name`'s value reference; -1 when there is none.
  int Reference(const std::string& name) const {
    for (const FmuVariable& v : variables_) {
      if (v.name == name) return static_cast<int>(v.reference);
    }
    return -1;
  }

  bool Instantiate() {
    static const fmi2CallbackFunctions callbacks = {nullptr, nullptr, nullptr, nullptr, nullptr};
    instance_ = instantiate_("test", fmi2CoSimulation, "", resources_.c_str(), &callbacks,
                             fmi2False, fmi2False);
    return instance_ != nullptr;
  }
  fmi2Status Setup(double start) { return setup_(instance_, fmi2False, 0.0, start, fmi2False, 0.0); }
  fmi2Status EnterInitialization() { return enter_(instance_); }
  fmi2Status ExitInitialization() { return exit_(instance_); }
  fmi2Status Terminate() { return terminate_(instance_); }
  fmi2Status SetReal(unsigned reference, double value) {
    return set_real_(instance_, &reference, 1, &value);
  }
  double GetReal(unsigned reference) {
    double value = 0.0;
    get_real_(instance_, &reference, 1, &value);
    return value;
  }
  fmi2Status SetInteger(unsigned reference, int value) {
    return set_integer_(instance_, &reference, 1, &value);
  }
  fmi2Status SetDerivative(unsigned reference, int order, double value) {
    return derivatives_(instance_, &reference, 1, &order, &value);
  }
  fmi2Status DoStep(double t, double h) { return do_step_(instance_, t, h, fmi2True); }

 private:
  void* library_ = nullptr;
  fmi2Component instance_ = nullptr;
  std::string description_, resources_;
  std::vector<FmuVariable> variables_;
  fmi2Component (*instantiate_)(fmi2String, fmi2Type, fmi2String, fmi2String,
                                const fmi2CallbackFunctions*, fmi2Boolean, fmi2Boolean) = nullptr;
  void (*free_instance_)(fmi2Component) = nullptr;
  fmi2Status (*setup_)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean,
                       fmi2Real) = nullptr;
  fmi2Status (*enter_)(fmi2Component) = nullptr;
  fmi2Status (*exit_)(fmi2Component) = nullptr;
  fmi2Status (*terminate_)(fmi2Component) = nullptr;
  fmi2Status (*set_real_)(fmi2Component, const fmi2ValueReference[], size_t,
                          const fmi2Real[]) = nullptr;
  fmi2Status (*get_real_)(fmi2Component, const fmi2ValueReference[], size_t, fmi2Real[]) = nullptr;
  fmi2Status (*set_integer_)(fmi2Component, const fmi2ValueReference[], size_t,
                             const fmi2Integer[]) = nullptr;
  fmi2Status (*derivatives_)(fmi2Component, const fmi2ValueReference[], size_t,
                             const fmi2Integer[], const fmi2Real[]) = nullptr;
  fmi2Status (*do_step_)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean) = nullptr;
  const char* (*version_)(void) = nullptr;
};

}  // namespace vesselid::testing
