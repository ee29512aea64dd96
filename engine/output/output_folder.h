// The folder a command writes into (`--out`), checked and locked before any work starts:
// it must be named (not empty, not the root folder), a folder (created if missing), writable, on a
// file system with room for the first files and under a file-size limit that admits them; and no
// other vesselid process may be writing into it. A second run into the same folder is refused with
// the first one's pid; the lock (an flock on OUT/.vesselid.lock) is released when the process ends,
// however it ends, so a killed run never blocks the next.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/run/run_config.h"

namespace vesselid {

class OutputFolder {
 public:
  // Files of at least this size must fit (free space and `ulimit -f`).
  static constexpr unsigned long long kFirstWriteBytes = 16ull << 20;

  // Creates (if needed), checks and locks `path`; null with a message naming the folder.
  static std::unique_ptr<OutputFolder> Open(const std::string& path, std::string* error);
  // Unlocks and removes the lock file; a folder Open created that holds nothing but the marker
  // (the command failed before publishing) is removed with it.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::string& path() const { return path_; }

 private:
  OutputFolder(std::string path, int lock_fd, bool created)
      : path_(std::move(path)), lock_fd_(lock_fd), created_(created) {}
  std::string path_;
  int lock_fd_;
  bool created_;
};

// What a command writes into its folder: files (relative names), folders it owns whole, and
// name prefixes of CSV files (e.g. "<stage>." for a step-regression stage's tables).
struct PlannedOutputs {
  std::vector<std::string> files;
  std::vector<std::string> folders;
  std::vector<std::string> csv_prefixes;
};

// The files `vesselid run` and `vesselid study` write into their folder for `config` (its
// step-regression stages add tables "<stage>.*.csv").
PlannedOutputs RunOutputs(const RunConfig& config);

// The folder a command writes into when --out is not given: `<run_dir>/<name>` (export,
// predict, design). False when that name is a link: the default stays inside the run's folder
// and a link planted there would lead the command's files elsewhere.
bool DefaultOutFolder(const std::string& run_dir, const std::string& name, std::string* out_dir,
                      std::string* error);

// What a run reads and no output may replace: its config file (unless `config_is_file` is
// false: a config given as text), every data file, and the results.json of its reference
// model (final_validation.reference).
std::vector<std::string> RunInputs(const RunConfig& config, bool config_is_file = true);

// False, naming both, when one of `inputs` is a file the command would write (or its
// temporary) in `out_dir` (an output never replaces an input), or lies in a subfolder of
// `out_dir` the command does not write (--out is a parent of the data); or when `out_dir`
// holds other files and is neither an earlier vesselid output (its marker OUT/.vesselid) nor
// the folder of one of `inputs`.
bool CheckInputsSurvive(const std::string& out_dir, const PlannedOutputs& planned,
                        const std::vector<std::string>& inputs, std::string* error);

}  // namespace vesselid
