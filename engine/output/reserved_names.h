// The names vesselid reserves inside an output folder (--out) for its own bookkeeping. Each is
// hidden (a leading dot) and none is an output a user reads.
#pragma once

namespace vesselid {

// Makes a non-empty folder an earlier output, which a later command may write into again.
inline constexpr char kMarkerFile[] = ".vesselid";
// flock'ed by the command at work in the folder; holds its pid.
inline constexpr char kLockFile[] = ".vesselid.lock";
// Where a command writes its outputs before they are published (output_staging.h).
inline constexpr char kStagingFolder[] = ".vesselid-staging";
// In the staging folder once every output is in it: what the publication does.
inline constexpr char kJournal[] = ".vesselid-publish";
// Names the folder swapped out or in while a publication exchanges the whole folder.
inline constexpr char kSwapToken[] = ".vesselid-swap";
// A run's checkpoint while the run is at work; published with its results as checkpoint/.
inline constexpr char kWorkingCheckpoint[] = ".vesselid-checkpoint";
// Each set's manifest is ".vesselid-<set>.set"; temporaries end in ".tmp".
inline constexpr char kReservedPrefix[] = ".vesselid";

}  // namespace vesselid
