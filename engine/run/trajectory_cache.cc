#include "engine/run/trajectory_cache.h"

#include <set>

namespace vesselid {

const Trajectory* TrajectoryCache::Load(const ExperimentSpec& spec, std::string* error) {
  Entry& entry = experiments_[spec.name];
  if (entry.data != nullptr) return entry.data.get();
  const std::string key = ReadKey(spec);
  auto read = reads_.find(key);
  if (read == reads_.end()) {
    auto data = std::make_shared<Trajectory>();
    if (!LoadExperimentData(spec, data.get(), error)) {
      experiments_.erase(spec.name);
      return nullptr;
    }
    read = reads_.emplace(key, std::move(data)).first;
  }
  entry.data = read->second;
  return entry.data.get();
}

const Trajectory* TrajectoryCache::Find(const std::string& name) const {
  const auto found = experiments_.find(name);
  return found == experiments_.end() ? nullptr : found->second.data.get();
}

void TrajectoryCache::Put(const std::string& name, Trajectory data) {
  experiments_[name].data = std::make_shared<Trajectory>(std::move(data));
}

void TrajectoryCache::AddNote(const std::string& name, Finding note) {
  AddFindingOnce(std::move(note), &experiments_[name].notes);
}

std::vector<Finding> TrajectoryCache::Findings(const std::vector<std::string>& experiments) const {
  std::vector<Finding> findings;
  std::set<const Trajectory*> given;
  for (const std::string& name : experiments) {
    const auto found = experiments_.find(name);
    if (found == experiments_.end()) continue;
    const Trajectory* data = found->second.data.get();
    if (data != nullptr && given.insert(data).second) {
      findings.insert(findings.end(), data->findings.begin(), data->findings.end());
    }
    findings.insert(findings.end(), found->second.notes.begin(), found->second.notes.end());
  }
  return findings;
}

TrajectoryCache TrajectoryCache::EditedCopy(
    const std::vector<std::string>& experiments,
    const std::function<void(const std::string&, Trajectory*)>& edit) const {
  TrajectoryCache copy;
  std::map<const Trajectory*, std::shared_ptr<Trajectory>> copies;
  for (const std::string& name : experiments) {
    const auto found = experiments_.find(name);
    if (found == experiments_.end() || found->second.data == nullptr) continue;
    std::shared_ptr<Trajectory>& edited = copies[found->second.data.get()];
    if (edited == nullptr) {
      edited = std::make_shared<Trajectory>(*found->second.data);
      edit(name, edited.get());
    }
    copy.experiments_[name].data = edited;
  }
  return copy;
}

}  // namespace vesselid
