// Checkpoints of a staged run. After each stage, the run's working checkpoint
// (OUT/.vesselid-checkpoint/) holds every finished stage's whole result (stage_result_archive.h,
// as CBOR: every double exact) and a manifest naming them with the fingerprint of the config
// and data they came from; it is published with the run's results as OUT/checkpoint/, so the
// folder never shows one run's results beside another run's checkpoint. `vesselid run
// --resume` loads the working checkpoint (a run stopped before it published) or else the
// published one, and goes on from the next stage with the results an uninterrupted run gives.
// Each file is written to a temporary name and renamed, the manifest last, so a run killed
// at any instant leaves the previous checkpoint intact.
#pragma once

#include <string>
#include <vector>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// A 64-bit hash (content_hash.h) of the config file and every experiment's name and data
// file, in hex: a resumed run must see the same bytes as the run it continues.
bool RunFingerprint(const RunConfig& config, std::string* fingerprint, std::string* error);

// The published checkpoint's folder inside --out.
inline constexpr char kCheckpointFolder[] = "checkpoint";

// "" when out_dir has no checkpoint folders or ones vesselid wrote (folders, not links, with
// their manifests); else why one is not replaced, naming it.
std::string CheckpointNotOwned(const std::string& out_dir);

// A checkpoint/ that no set's manifest names (an earlier vesselid published it beside its
// results without naming it) becomes the working checkpoint, so that the run can resume from
// it and publishes its own in its place.
bool AdoptUnpublishedCheckpoint(const std::string& out_dir, std::string* error);

// A fresh run: removes any earlier working checkpoint in out_dir (one CheckpointNotOwned accepts)
// and starts an empty one.
bool StartCheckpoint(const std::string& out_dir, const std::string& fingerprint,
                     std::string* error);

// Adds finished stage `index` (0-based; stages [0, index) are already saved).
bool SaveStageCheckpoint(const std::string& out_dir, const std::string& fingerprint, size_t index,
                         const StageResult& stage, std::string* error);

// The finished stages of the checkpoint in out_dir (the working one, else the published one,
// which the run then continues in a working copy); empty when there is none. False when there
// is one but it belongs to another config or other data, or cannot be read.
bool LoadCheckpoint(const std::string& out_dir, const std::string& fingerprint,
                    std::vector<StageResult>* finished, std::string* error);

// Puts a copy of the working checkpoint into the staging folder `staging` as checkpoint/, to
// be published with the results (nothing when there is none).
bool StageCheckpoint(const std::string& out_dir, const std::string& staging, std::string* error);

// Removes the working checkpoint once its copy is published.
void RemoveWorkingCheckpoint(const std::string& out_dir);

}  // namespace vesselid
