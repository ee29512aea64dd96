// The records a run reads, by configured experiment, each file read once: experiments that
// read one file alike (the same columns, units and preparation: ReadKey, experiment.h) share
// one Trajectory, so 10 000 windows of one log hold the log once, not 10 000 times.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/data/trajectory.h"
#include "engine/model/experiment.h"

namespace vesselid {

class TrajectoryCache {
 public:
  // The data of `spec`, read and prepared (LoadExperimentData) on first use of its file by
  // any experiment; null on error.
  const Trajectory* Load(const ExperimentSpec& spec, std::string* error);
  // The data experiment `name` was given, null if none.
  const Trajectory* Find(const std::string& name) const;
  // Gives experiment `name` a record of its own (tests, tools with data in hand).
  void Put(const std::string& name, Trajectory data);
  // Notes of the run about experiment `name`'s record besides those of its reading (pieces
  // skipped, cut), each kept once.
  void AddNote(const std::string& name, Finding note);

  // In `experiments` order, each finding of the records' reading once (a file shared by
  // many experiments gives them once, in the first experiment's name) and each
  // experiment's notes.
  std::vector<Finding> Findings(const std::vector<std::string>& experiments) const;

  // A cache holding a copy of the records of `experiments` (a shared record copied once),
  // each changed by `edit(first experiment, copy)`.
  TrajectoryCache EditedCopy(
      const std::vector<std::string>& experiments,
      const std::function<void(const std::string&, Trajectory*)>& edit) const;

 private:
  struct Entry {
    std::shared_ptr<Trajectory> data;
    std::vector<Finding> notes;
  };
  std::map<std::string, Entry> experiments_;
  std::map<std::string, std::shared_ptr<Trajectory>> reads_;  // by ReadKey
};

}  // namespace vesselid
