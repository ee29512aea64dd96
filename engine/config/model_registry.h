// The model families a run can name in its `model.family` key (problems/registry.h holds the
// shipped ones). A family builds its model from the config's `model` map and simulates the
// experiments of its `simulation` map (model_family.h, for the families themselves).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/model/model_handle.h"
#include "engine/run/reference_model.h"

namespace vesselid {

struct ModelFamily;

class ModelRegistry {
 public:
  void Register(ModelFamily family);
  // Null when no family has that name.
  const ModelFamily* Find(const std::string& name) const;
  std::vector<std::string> Names() const;

  // The model of family `family` with the options of its config map as plain text, e.g.
  // MakeModel("nomoto", {{"type", "second_order"}}) or {{"dofs", "[surge, sway, yaw]"}}
  // (each value is read as the config would read it). Null with the config's message
  // ("model.type: unknown type ...") in `error` when the family or an option is wrong.
  std::shared_ptr<const ModelHandle> MakeModel(const std::string& family,
                                               const std::map<std::string, std::string>& options,
                                               std::string* error) const;

  // Reads `final_validation.reference` (another run's output folder) for a run of `family`
  // with model `info`: set by the shipped registry (the reader lives above the config, with
  // `vesselid export`); without one a config naming a reference is refused.
  using ReferenceReader = std::function<bool(
      const std::string& folder, const ModelRegistry& registry, const std::string& family,
      const ModelInfo& info, ReferenceModel* reference, std::string* error)>;
  void SetReferenceReader(ReferenceReader reader) { reference_reader_ = std::move(reader); }
  const ReferenceReader& reference_reader() const { return reference_reader_; }

 private:
  ReferenceReader reference_reader_;
  // Shared: the registry copies and moves where the families' type is not known.
  std::vector<std::shared_ptr<const ModelFamily>> families_;
};

}  // namespace vesselid
