// Checkpoints of a staged run. After each stage, OUT/checkpoint/ holds every finished stage's
// whole result (stage_result_archive.h, as CBOR: every double exact) and a manifest naming
// them with the fingerprint of the config and data they came from. `vesselid run --resume`
// loads them and goes on from the next stage, with the results an uninterrupted run gives.
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

// "" when out_dir has no checkpoint folder or one vesselid wrote (a folder, not a link, with
// its manifest); else why it is not replaced, naming it.
std::string CheckpointNotOwned(const std::string& out_dir);

// A fresh run: removes any earlier checkpoint in out_dir (one CheckpointNotOwned accepts)
// and starts an empty one.
bool StartCheckpoint(const std::string& out_dir, const std::string& fingerprint,
                     std::string* error);

// Adds finished stage `index` (0-based; stages [0, index) are already saved).
bool SaveStageCheckpoint(const std::string& out_dir, const std::string& fingerprint, size_t index,
                         const StageResult& stage, std::string* error);

// The finished stages of the checkpoint in out_dir; empty when there is none. False when there
// is one but it belongs to another config or other data, or cannot be read.
bool LoadCheckpoint(const std::string& out_dir, const std::string& fingerprint,
                    std::vector<StageResult>* finished, std::string* error);

}  // namespace vesselid
