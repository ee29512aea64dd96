#include "engine/output/checkpoint.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "engine/base/atomic_file.h"
#include "engine/base/content_hash.h"
#include "engine/base/input_file.h"
#include "engine/base/work_limits.h"
#include "engine/output/output_staging.h"
#include "engine/output/reserved_names.h"
#include "engine/output/stage_result_archive.h"
#include "nlohmann/json.hpp"

namespace vesselid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr char kManifest[] = "manifest.json";

// The checkpoint a run at work writes, and the one published with a run's results.
fs::path WorkingFolder(const std::string& out_dir) { return fs::path(out_dir) / kWorkingCheckpoint; }
fs::path PublishedFolder(const std::string& out_dir) { return fs::path(out_dir) / kCheckpointFolder; }

bool HasManifest(const fs::path& folder) {
  std::error_code ec;
  return fs::symlink_status(folder, ec).type() == fs::file_type::directory &&
         fs::symlink_status(folder / kManifest, ec).type() == fs::file_type::regular;
}

bool ReadBytes(const std::string& path, std::string* bytes, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = path + ": cannot open";
    return false;
  }
  bytes->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (in.bad()) {
    *error = path + ": read failed";
    return false;
  }
  return true;
}

// A piece of the fingerprint followed by its length, so that pieces cannot run together.
void AddPiece(const std::string& bytes, ContentHash* hash) {
  hash->Add(bytes);
  const std::uint64_t size = bytes.size();
  hash->Add(&size, sizeof(size));
}

// Hashes a regular file of at most max_bytes as it reads it, a block at a time, then its
// length.
bool HashFile(const std::string& path, const std::string& kind, std::uint64_t max_bytes,
              const std::string& limit_key, ContentHash* hash, std::string* error) {
  if (!CheckInputFile(path, kind, max_bytes, limit_key, error)) return false;
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    *error = path + ": cannot open";
    return false;
  }
  std::vector<char> block(1 << 18);
  std::uint64_t size = 0;
  size_t read;
  while ((read = std::fread(block.data(), 1, block.size(), file)) > 0) {
    hash->Add(block.data(), read);
    size += read;
  }
  hash->Add(&size, sizeof(size));
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) *error = path + ": read failed";
  return !failed;
}

std::string StageFile(size_t index) {
  char name[32];
  std::snprintf(name, sizeof(name), "stage_%03zu.cbor", index + 1);
  return name;
}

bool WriteManifest(const fs::path& folder, const std::string& fingerprint,
                   const std::vector<std::string>& stages, std::string* error) {
  const json manifest = {{"fingerprint", fingerprint}, {"stages", stages}};
  return WriteFileAtomically((folder / kManifest).string(), manifest.dump(2) + "\n", error);
}

bool ReadManifest(const fs::path& folder, json* manifest, std::string* error) {
  std::string bytes;
  if (!ReadBytes((folder / kManifest).string(), &bytes, error)) return false;
  *manifest = json::parse(bytes, nullptr, false);
  if (manifest->is_discarded() || !(*manifest)["fingerprint"].is_string() ||
      !(*manifest)["stages"].is_array()) {
    *error = (folder / kManifest).string() + ": not a vesselid checkpoint manifest";
    return false;
  }
  return true;
}

// A checkpoint file's name without the ".tmp" of its temporary.
std::string WithoutTemporarySuffix(std::string name) {
  if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0) name.resize(name.size() - 4);
  return name;
}

// Whether every entry of the folder is a plain file of a checkpoint's names (the manifest, a
// stage file, their temporaries): a working checkpoint a kill left half made or half removed
// (no manifest yet, or no more).
bool OnlyCheckpointFiles(const fs::path& folder) {
  std::error_code ec;
  for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = WithoutTemporarySuffix(it->path().filename().string());
    const bool stage = name.size() > 11 && name.rfind("stage_", 0) == 0 &&
                       name.compare(name.size() - 5, 5, ".cbor") == 0 &&
                       name.find_first_not_of("0123456789", 6) == name.size() - 5;
    if (it->is_symlink() || !it->is_regular_file() || !(stage || name == kManifest)) return false;
  }
  return !ec;
}

// "" when `folder` is absent or a checkpoint vesselid wrote (`working`: also one half made or
// half removed); else why not.
std::string FolderNotOwned(const fs::path& folder, bool working) {
  std::error_code ec;
  const fs::file_type type = fs::symlink_status(folder, ec).type();
  if (type == fs::file_type::not_found) return "";
  if (working && type == fs::file_type::directory &&
      fs::symlink_status(folder / kManifest, ec).type() == fs::file_type::not_found &&
      OnlyCheckpointFiles(folder)) {
    return "";
  }
  json manifest;
  std::string unread;
  if (type == fs::file_type::directory &&
      fs::symlink_status(folder / kManifest, ec).type() == fs::file_type::regular &&
      ReadManifest(folder, &manifest, &unread)) {
    // Its files: the manifest, the stages it lists and the next one (written, not yet listed,
    // when a run was killed between the two), and their temporaries.
    std::set<std::string> own = {kManifest};
    const size_t listed = manifest["stages"].size();
    for (size_t k = 0; k <= listed; ++k) own.insert(StageFile(k));
    std::string foreign;
    for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator();
         it.increment(ec)) {
      const std::string name = WithoutTemporarySuffix(it->path().filename().string());
      if (it->is_symlink() || !it->is_regular_file() || own.count(name) == 0) {
        foreign = it->path().filename().string();
        break;
      }
    }
    if (foreign.empty()) return "";
    return (folder / foreign).string() + ": vesselid keeps a run's checkpoint in " +
           folder.string() + ", but did not write this: move it away or choose another --out " +
           "(nothing was changed)";
  }
  return folder.string() + ": vesselid keeps a run's checkpoint here, but did not write what is "
         "there (no checkpoint manifest, or a link): move it away or choose another --out "
         "(nothing was changed)";
}

// `to` made afresh with the files of the checkpoint `from`, as hard links where the file system
// has them.
bool CopyCheckpoint(const fs::path& from, const fs::path& to, std::string* error) {
  std::error_code ec;
  fs::remove_all(to, ec);
  fs::create_directory(to, ec);
  for (auto it = fs::directory_iterator(from, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    if (!it->is_regular_file() || it->is_symlink()) continue;
    const fs::path target = to / it->path().filename();
    std::error_code link_ec;
    fs::create_hard_link(it->path(), target, link_ec);
    if (link_ec) fs::copy_file(it->path(), target, link_ec);
    if (link_ec) {
      *error = target.string() + ": cannot copy the checkpoint: " + link_ec.message();
      return false;
    }
  }
  if (ec) {
    *error = to.string() + ": cannot copy the checkpoint: " + ec.message();
    return false;
  }
  return true;
}

}  // namespace

bool RunFingerprint(const RunConfig& config, std::string* fingerprint, std::string* error) {
  ContentHash hash;
  if (!HashFile(config.path, "config file", kMaxConfigBytes, "", &hash, error)) return false;
  std::set<std::string> hashed;  // each file once (windows of one log name it 10 000 times)
  for (const ExperimentSpec& spec : config.experiments) {
    AddPiece(spec.name, &hash);
    // The file by its canonical path: `--data out` and `--data ./out/` name the same files.
    std::error_code canonical_ec;
    const fs::path canonical = fs::weakly_canonical(spec.file, canonical_ec);
    AddPiece(canonical_ec ? spec.file : canonical.string(), &hash);
    // A missing file counts as absent: the run itself reports it when it needs the data.
    std::error_code ec;
    if (!fs::exists(spec.file, ec)) {
      AddPiece("absent", &hash);
      continue;
    }
    if (!hashed.insert(spec.file).second) continue;
    if (!HashFile(spec.file, "data file", spec.csv.max_bytes, "limits.file_mb", &hash, error)) return false;
  }
  char hex[20];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(hash.Digest()));
  *fingerprint = hex;
  return true;
}

std::string CheckpointNotOwned(const std::string& out_dir) {
  const std::string published = FolderNotOwned(PublishedFolder(out_dir), false);
  return published.empty() ? FolderNotOwned(WorkingFolder(out_dir), true) : published;
}

bool StartCheckpoint(const std::string& out_dir, const std::string& fingerprint,
                     std::string* error) {
  const fs::path folder = WorkingFolder(out_dir);
  std::error_code ec;
  *error = CheckpointNotOwned(out_dir);
  if (!error->empty()) return false;
  fs::remove_all(folder, ec);
  fs::create_directories(folder, ec);
  if (ec) {
    *error = folder.string() + ": cannot create folder: " + ec.message();
    return false;
  }
  return WriteManifest(folder, fingerprint, {}, error);
}

bool SaveStageCheckpoint(const std::string& out_dir, const std::string& fingerprint, size_t index,
                         const StageResult& stage, std::string* error) {
  const fs::path folder = WorkingFolder(out_dir);
  json manifest;
  if (!ReadManifest(folder, &manifest, error)) return false;
  std::vector<std::string> stages = manifest["stages"].get<std::vector<std::string>>();
  if (manifest["fingerprint"] != fingerprint || stages.size() != index) {
    *error = folder.string() + ": checkpoint does not continue this run";
    return false;
  }
  const std::vector<std::uint8_t> cbor = json::to_cbor(StageResultToArchive(stage));
  if (!WriteFileAtomically((folder / StageFile(index)).string(),
                           std::string(cbor.begin(), cbor.end()), error)) {
    return false;
  }
  stages.push_back(stage.name);
  return WriteManifest(folder, fingerprint, stages, error);
}

bool LoadCheckpoint(const std::string& out_dir, const std::string& fingerprint,
                    std::vector<StageResult>* finished, std::string* error) {
  finished->clear();
  // The checkpoint of a run stopped before it published, else the one published with the last
  // run's results; the run goes on in a working copy of the latter (hard links: every
  // checkpoint file is replaced by a rename, never written in place).
  // A working checkpoint of another config or other data (a run of another config stopped
  // there) gives way to a published one of this run's.
  fs::path folder = WorkingFolder(out_dir);
  json working;
  std::string unread;
  if (!HasManifest(folder) || (HasManifest(PublishedFolder(out_dir)) &&
                               ReadManifest(folder, &working, &unread) &&
                               working["fingerprint"] != fingerprint)) {
    folder = PublishedFolder(out_dir);
    if (!HasManifest(folder)) return true;
    json published;
    if (!ReadManifest(folder, &published, error)) return false;
    // Copied only to go on from it: a checkpoint of another config is refused below as it is.
    if (published["fingerprint"] == fingerprint &&
        !CopyCheckpoint(folder, WorkingFolder(out_dir), error)) {
      return false;
    }
  }
  json manifest;
  if (!ReadManifest(folder, &manifest, error)) return false;
  if (manifest["fingerprint"] != fingerprint) {
    *error = folder.string() +
             ": the checkpoint was made from another config or other data; run without "
             "--resume to start again";
    return false;
  }
  const std::vector<std::string> stages = manifest["stages"].get<std::vector<std::string>>();
  for (size_t i = 0; i < stages.size(); ++i) {
    const std::string path = (folder / StageFile(i)).string();
    std::string bytes;
    if (!ReadBytes(path, &bytes, error)) return false;
    const json archive = json::from_cbor(bytes, true, false);
    StageResult stage;
    if (archive.is_discarded()) {
      *error = path + ": not a CBOR stage archive";
      return false;
    }
    if (!StageResultFromArchive(archive, &stage, error)) {
      *error = path + ": " + *error;
      return false;
    }
    if (stage.name != stages[i]) {
      *error = path + ": holds stage '" + stage.name + "', the manifest names '" + stages[i] + "'";
      return false;
    }
    finished->push_back(std::move(stage));
  }
  return true;
}


bool AdoptUnpublishedCheckpoint(const std::string& out_dir, std::string* error) {
  const fs::path published = PublishedFolder(out_dir), working = WorkingFolder(out_dir);
  std::error_code ec;
  if (!HasManifest(published) || OwnedEntries(out_dir).count(kCheckpointFolder) != 0 ||
      fs::symlink_status(working, ec).type() != fs::file_type::not_found) {
    return true;
  }
  fs::rename(published, working, ec);
  if (ec) {
    *error = published.string() + ": cannot take over the checkpoint: " + ec.message();
    return false;
  }
  return true;
}

bool StageCheckpoint(const std::string& out_dir, const std::string& staging, std::string* error) {
  const fs::path working = WorkingFolder(out_dir);
  if (!HasManifest(working)) return true;
  return CopyCheckpoint(working, fs::path(staging) / kCheckpointFolder, error);
}

void RemoveWorkingCheckpoint(const std::string& out_dir) {
  std::error_code ec;
  if (HasManifest(WorkingFolder(out_dir))) fs::remove_all(WorkingFolder(out_dir), ec);
}

}  // namespace vesselid
