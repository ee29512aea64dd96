// An exported C model (export/c_model.h) as a user builds it: its files written to a folder,
// the model compiled by the system's C compiler with `-std=c99 -Wall -Werror` into a shared
// object that the test loads (dlopen), and the example program compiled and linked the same
// way.
#pragma once

#include <dlfcn.h>

#include <fstream>
#include <string>
#include <vector>

#include "engine/export/c_model.h"
#include "tests/support/run_command.h"

namespace vesselid::testing {

class CModelLoader {
 public:
  using Rk4Step = int (*)(double*, const double*, const double*, const double*, const double*,
                          double);
  using OutputMap = void (*)(const double*, const double*, const double*, double*);
  using Simulate = int (*)(int, const double*, const double*, const double*, const double*, double,
                           double*);
  using Member = const double* (*)(int);

  ~CModelLoader() {
    if (library_ != nullptr) dlclose(library_);
  }

  // Writes `files` into `dir`, compiles and loads the model (named `id`) and compiles the
  // example. False with the compiler's message.
  bool Build(const std::vector<CModelFile>& files, const std::string& id, const std::string& dir,
             std::string* error) {
    for (const CModelFile& file : files) {
      std::ofstream(dir + "/" + file.name) << file.text;
    }
    const std::string flags = "cc -std=c99 -Wall -Werror -O2 ";
    const std::string source = dir + "/" + id + ".c";
    library_path_ = dir + "/lib" + id + ".so";
    example_ = dir + "/" + id + "_example";
    for (const std::string& command :
         {flags + "-fPIC -shared -o " + library_path_ + " " + source + " -lm",
          flags + "-o " + example_ + " " + dir + "/" + id + "_example.c " + source + " -lm"}) {
      const CommandOutcome outcome = RunCommand(command);
      if (outcome.status != 0) {
        *error = command + "\n" + outcome.output;
        return false;
      }
    }
    library_ = dlopen(library_path_.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (library_ == nullptr) {
      *error = dlerror();
      return false;
    }
    rk4_step = reinterpret_cast<Rk4Step>(dlsym(library_, (id + "_rk4_step").c_str()));
    output = reinterpret_cast<OutputMap>(dlsym(library_, (id + "_output").c_str()));
    simulate = reinterpret_cast<Simulate>(dlsym(library_, (id + "_simulate").c_str()));
    member = reinterpret_cast<Member>(dlsym(library_, (id + "_member").c_str()));
    if (rk4_step == nullptr || output == nullptr || simulate == nullptr || member == nullptr) {
      *error = "a function of " + id + " is missing from " + library_path_;
      return false;
    }
    return true;
  }

  const std::string& example() const { return example_; }

  Rk4Step rk4_step = nullptr;
  OutputMap output = nullptr;
  Simulate simulate = nullptr;
  Member member = nullptr;

 private:
  void* library_ = nullptr;
  std::string library_path_, example_;
};

}  // namespace vesselid::testing
