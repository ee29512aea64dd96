#include "engine/output/output_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/resource.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "engine/base/file_name.h"
#include "engine/base/input_file.h"
#include "engine/base/text_match.h"
#include "engine/output/checkpoint.h"
#include "engine/output/output_staging.h"
#include "engine/output/reserved_names.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;

constexpr char kTemporarySuffix[] = ".tmp";

// The pid written into a lock file, or "" when it cannot be read.
std::string LockHolder(int fd) {
  char text[32] = {0};
  const ssize_t n = ::pread(fd, text, sizeof(text) - 1, 0);
  std::string pid(text, n > 0 ? static_cast<size_t>(n) : 0);
  pid.erase(std::remove(pid.begin(), pid.end(), '\n'), pid.end());
  return pid;
}

std::string AnotherProcess(const std::string& pid) {
  return "another vesselid process" + (pid.empty() || pid == "?" ? "" : " (pid " + pid + ")") +
         " is writing into this folder; wait for it or choose another --out";
}

// False, saying why, when `path` names no folder of its own: empty, or the root folder.
bool OutNamed(const std::string& path, std::string* error) {
  std::error_code ec;
  if (path.empty()) {
    *error = "--out is empty: name a folder for the results";
    return false;
  }
  if (fs::weakly_canonical(path, ec) == fs::path("/")) {
    *error = path + ": --out is the root folder: name a folder of its own for the results";
    return false;
  }
  return true;
}

// An entry of the existing folder `path` when it is neither empty nor an earlier output of
// vesselid (its marker; a file of the name vesselid writes, a report.txt, is not one); ""
// otherwise.
std::string ForeignEntry(const std::string& path) {
  std::error_code ec;
  for (const char* mark : {kMarkerFile, kLockFile}) {  // a lock: a vesselid process is at work
    if (fs::symlink_status(fs::path(path) / mark, ec).type() == fs::file_type::regular) return "";
  }
  fs::directory_iterator it(path, ec);
  if (ec || it == fs::directory_iterator()) return "";
  return it->path().filename().string();
}

// "" when every output `planned` names is absent from `out` or vesselid's to replace; else
// why not (the first in the way).
std::string PlannedNotOwned(const std::string& out, const PlannedOutputs& planned) {
  // A publication a killed command left is finished under the folder's lock first
  // (OutputFolder::Open), its manifest with it; the publication checks again.
  if (PublicationUnfinished(out)) return "";
  const std::set<std::string> owned = OwnedEntries(out);
  std::vector<std::string> names;
  for (const std::string& f : planned.files) {
    if (f != kLockFile) names.push_back(f);
  }
  for (const std::string& f : planned.folders) {
    if (f != kCheckpointFolder) names.push_back(f);
  }
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out, ec)) {
    const std::string name = entry.path().filename().string();
    for (const std::string& prefix : planned.csv_prefixes) {
      if (StartsWith(name, prefix) && EndsWith(name, ".csv")) names.push_back(name);
    }
  }
  for (const std::string& name : names) {
    const std::string why = NotOwned(out, name, owned);
    if (!why.empty()) return why;
  }
  if (std::find(planned.folders.begin(), planned.folders.end(), kCheckpointFolder) !=
      planned.folders.end()) {
    return CheckpointNotOwned(out);
  }
  return "";
}

}  // namespace

std::unique_ptr<OutputFolder> OutputFolder::Open(const std::string& path, std::string* error) {
  std::error_code ec;
  if (!OutNamed(path, error)) return nullptr;
  const bool existed = fs::exists(path, ec);
  if (existed && !fs::is_directory(path, ec)) {
    *error = path + ": --out names a file, not a folder";
    return nullptr;
  }
  fs::create_directories(path, ec);
  if (ec) {
    *error = path + ": cannot create the output folder: " + ec.message();
    return nullptr;
  }
  // A refused run leaves no folder it made (an empty folder only: fs::remove).
  auto refuse = [&](const std::string& what) {
    *error = path + ": " + what;
    std::error_code ignored;
    if (!existed) fs::remove(path, ignored);
    return nullptr;
  };
  struct statvfs space;
  if (::statvfs(path.c_str(), &space) == 0) {
    const unsigned long long free_bytes =
        static_cast<unsigned long long>(space.f_bavail) * space.f_frsize;
    if (free_bytes < kFirstWriteBytes) {
      return refuse("only " + ByteCount(free_bytes) + " free on its file system, less than " +
                    ByteCount(kFirstWriteBytes) + " for the results");
    }
  }
  struct rlimit file_size;
  if (::getrlimit(RLIMIT_FSIZE, &file_size) == 0 && file_size.rlim_cur != RLIM_INFINITY &&
      file_size.rlim_cur < kFirstWriteBytes) {
    return refuse("the file size limit (ulimit -f) of " + ByteCount(file_size.rlim_cur) +
                  " is less than " + ByteCount(kFirstWriteBytes) + " for the results");
  }
  const std::string lock_path = (fs::path(path) / kLockFile).string();
  int fd = -1;
  for (int attempt = 0;; ++attempt) {
    // O_NOFOLLOW: a link planted at the lock's name would have its target truncated.
    fd = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0)
      return refuse("cannot write into the output folder: " + std::string(std::strerror(errno)));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const std::string pid = LockHolder(fd);
      ::close(fd);
      return refuse(AnotherProcess(pid));
    }
    // The file locked must still be the one at the lock's name: a process that ended between
    // our open and our lock removed it, and the next process would lock a new one beside us.
    struct stat held, named;
    if (::fstat(fd, &held) == 0 && ::lstat(lock_path.c_str(), &named) == 0 &&
        held.st_dev == named.st_dev && held.st_ino == named.st_ino) {
      break;
    }
    ::close(fd);
    if (attempt == 16) return refuse("cannot take the folder's lock: its lock file keeps changing");
  }
  auto folder = std::unique_ptr<OutputFolder>(new OutputFolder(path, fd, !existed));
  const std::string marker_path = (fs::path(path) / kMarkerFile).string();
  const int marker = ::open(marker_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (marker >= 0) {  // else it is there already (or a link, which is neither followed nor replaced)
    const char text[] = "written by vesselid: a later vesselid command may write into this folder\n";
    [[maybe_unused]] const ssize_t written = ::write(marker, text, sizeof(text) - 1);  // empty marks too
    ::close(marker);
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd, 0) != 0 ||
      ::pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    const std::string reason = std::strerror(errno);
    folder.reset();  // unlocks and removes the lock file
    return refuse("cannot write into the output folder: " + reason);
  }
  // A command killed while publishing its outputs left them half moved: finished now, so the
  // folder holds one whole set before anything else reads or writes it (output_staging.h).
  if (!FinishPublication(path, error)) return nullptr;
  return folder;
}

OutputFolder::~OutputFolder() {
  // Removed while still locked: a process that opens the old file after this gets the lock of
  // a file no longer in the folder, and the next one creates a fresh lock file.
  std::error_code ec;
  fs::remove(fs::path(path_) / kLockFile, ec);
  ::close(lock_fd_);
  if (!created_) return;
  for (const auto& entry : fs::directory_iterator(path_, ec)) {
    if (entry.path().filename() != kMarkerFile) return;  // something was written
  }
  if (ec) return;
  fs::remove(fs::path(path_) / kMarkerFile, ec);
  fs::remove(path_, ec);  // empty now, or left as it is
}

PlannedOutputs RunOutputs(const RunConfig& config) {
  PlannedOutputs planned;
  planned.files = {"results.json", "report.txt", "report.html", "study.json", "study.txt",
                   kLockFile};
  planned.folders = {"traces", kCheckpointFolder, "surfaces"};
  for (const StageConfig& stage : config.stages) {
    if (stage.kind == StageConfig::Kind::kStepRegression) {
      planned.csv_prefixes.push_back(FileNameOf(stage.options.name) + ".");
    }
  }
  return planned;
}

bool DefaultOutFolder(const std::string& run_dir, const std::string& name, std::string* out_dir,
                      std::string* error) {
  const fs::path folder = fs::path(run_dir) / name;
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(folder, ec))) {
    *error = folder.string() + ": a link, where the default --out of this command is made "
                               "inside the run's folder; name --out to write elsewhere";
    return false;
  }
  *out_dir = folder.string();
  return true;
}

std::vector<std::string> RunInputs(const RunConfig& config, bool config_is_file) {
  std::vector<std::string> inputs;
  if (config_is_file && !config.path.empty()) inputs.push_back(config.path);
  for (const ExperimentSpec& spec : config.experiments) {
    if (!spec.file.empty()) inputs.push_back(spec.file);
  }
  const std::string& reference = config.final_validation.reference.folder;
  if (config.has_final_validation && !reference.empty()) {
    inputs.push_back((fs::path(reference) / "results.json").string());
  }
  return inputs;
}

namespace {

// The pid of another process holding the lock of `out_dir` ("?" when it cannot be read), or
// "" when none holds it. A probe: a shared lock tried and let go at once.
std::string LockedBy(const std::string& out_dir) {
  const std::string lock_path = (fs::path(out_dir) / kLockFile).string();
  const int fd = ::open(lock_path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) return "";
  std::string holder;
  if (::flock(fd, LOCK_SH | LOCK_NB) != 0) {
    holder = LockHolder(fd);
    if (holder.empty()) holder = "?";
  } else {
    ::flock(fd, LOCK_UN);
  }
  ::close(fd);
  return holder;
}

bool InputsSurvive(const std::string& out_dir, const PlannedOutputs& planned,
                   const std::vector<std::string>& inputs, std::string* error);

}  // namespace

bool CheckInputsSurvive(const std::string& out_dir, const PlannedOutputs& planned,
                        const std::vector<std::string>& inputs, std::string* error) {
  if (InputsSurvive(out_dir, planned, inputs, error)) return true;
  // What another vesselid process is writing there right now is not in the way: say that.
  const std::string pid = LockedBy(out_dir);
  if (!pid.empty()) {
    *error = out_dir + ": " + AnotherProcess(pid);
    return false;
  }
  // Nor what one published between the check's reads (a manifest read before, its entries
  // after): checked once more, the folder whole again.
  return InputsSurvive(out_dir, planned, inputs, error);
}

namespace {

bool InputsSurvive(const std::string& out_dir, const PlannedOutputs& planned,
                   const std::vector<std::string>& inputs, std::string* error) {
  if (!OutNamed(out_dir, error)) return false;
  std::error_code ec;
  const fs::path out = fs::weakly_canonical(out_dir, ec);
  if (ec) return true;  // nothing there to overwrite
  for (const std::string& input : inputs) {
    const fs::path file = fs::weakly_canonical(input, ec);
    if (ec) continue;
    const fs::path relative = file.lexically_relative(out);
    if (relative.empty() || *relative.begin() == "..") continue;
    const std::string first = relative.begin()->string();
    // An input in a subfolder of --out (not one vesselid writes): --out is a parent of the
    // data, and its outputs would mix with the data's tree.
    if (std::next(relative.begin()) != relative.end() &&
        std::find(planned.folders.begin(), planned.folders.end(), first) == planned.folders.end()) {
      *error = out_dir + ": --out holds the inputs' folder " + file.parent_path().string() + " (" +
               input + "): choose a folder beside or inside it";
      return false;
    }
    bool written = false;
    if (std::next(relative.begin()) != relative.end()) {
      written =
          std::find(planned.folders.begin(), planned.folders.end(), first) != planned.folders.end();
    } else {
      std::string name = first;
      if (EndsWith(name, kTemporarySuffix)) name.resize(name.size() - (sizeof(kTemporarySuffix) - 1));
      written = std::find(planned.files.begin(), planned.files.end(), name) != planned.files.end();
      for (const std::string& prefix : planned.csv_prefixes) {
        written |= StartsWith(name, prefix) && EndsWith(name, ".csv");
      }
    }
    if (written) {
      *error = input + ": this input is where the output " + (out / relative).string() +
               " would be written; choose another --out";
      return false;
    }
  }
  // A folder of other files is not written into, unless the command's inputs lie in it (the
  // user writes beside them on purpose).
  if (fs::is_directory(out, ec)) {
    const std::string other = ForeignEntry(out.string());
    bool holds_input = false;
    for (const std::string& input : inputs) {
      holds_input |= fs::weakly_canonical(input, ec).parent_path() == out;
    }
    if (!other.empty() && !holds_input) {
      *error = out_dir + ": --out holds other files ('" + other +
               "') and no earlier vesselid output: choose an empty or new folder";
      return false;
    }
    // Nothing in the way of an output but what vesselid wrote (output_staging.h).
    const std::string why = PlannedNotOwned(out.string(), planned);
    if (!why.empty()) {
      *error = why;
      return false;
    }
  }
  return true;
}

}  // namespace

}  // namespace vesselid
