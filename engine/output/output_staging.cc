#include "engine/output/output_staging.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "engine/base/atomic_file.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;

// In the staging folder once every output is in it: what the publication does, one line each
// ("set <name>", "last <entry>", "remove <entry>", "entry <entry>"). Its presence is what
// makes a staging folder complete.
constexpr char kJournal[] = ".publish";

struct Journal {
  std::string set, last;
  std::vector<std::string> remove, entries;
};

fs::path ManifestPath(const std::string& out_dir, const std::string& set) {
  return fs::path(out_dir) / (".vesselid-" + set + ".set");
}

// The lines of a text file; empty when it is missing.
std::vector<std::string> Lines(const fs::path& path) {
  std::vector<std::string> lines;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

std::string JournalText(const Journal& j) {
  std::string text = "set " + j.set + "\nlast " + j.last + "\n";
  for (const std::string& r : j.remove) text += "remove " + r + "\n";
  for (const std::string& e : j.entries) text += "entry " + e + "\n";
  return text;
}

bool ReadJournal(const fs::path& path, Journal* j, std::string* error) {
  for (const std::string& line : Lines(path)) {
    const size_t space = line.find(' ');
    const std::string key = line.substr(0, space);
    const std::string value = space == std::string::npos ? "" : line.substr(space + 1);
    // An entry is one name inside the folder: a journal naming anything else is not ours.
    if (value.empty() || value == "." || value == ".." || value.find('/') != std::string::npos) {
      *error = path.string() + ": unreadable line '" + line + "'";
      return false;
    }
    if (key == "set")
      j->set = value;
    else if (key == "last")
      j->last = value;
    else if (key == "remove")
      j->remove.push_back(value);
    else if (key == "entry")
      j->entries.push_back(value);
    else {
      *error = path.string() + ": unreadable line '" + line + "'";
      return false;
    }
  }
  if (j->set.empty() || j->last.empty()) {
    *error = path.string() + ": incomplete journal";
    return false;
  }
  return true;
}

bool Failed(const fs::path& path, const std::string& what, const std::error_code& ec,
            std::string* error) {
  *error = path.string() + ": " + what + ": " + ec.message();
  return false;
}

// Carries out `j` from wherever an earlier attempt stopped: every step can be repeated.
bool Roll(const fs::path& out, const fs::path& staging, const Journal& j, std::string* error) {
  std::error_code ec;
  // The previous set's completion file goes first: from here until the end, --out holds no
  // results.json, so nobody reads a mixture as a whole set.
  if (fs::exists(staging / j.last, ec)) {
    fs::remove(out / j.last, ec);
    if (ec) return Failed(out / j.last, "cannot remove the previous results", ec, error);
  }
  for (const std::string& name : j.remove) {
    fs::remove_all(out / name, ec);
    if (ec) return Failed(out / name, "cannot remove the previous output", ec, error);
  }
  for (const std::string& name : j.entries) {
    if (name == j.last || !fs::exists(staging / name, ec)) continue;  // moved already
    // A folder replaces a folder whole (rename needs an absent or empty target).
    if (fs::is_directory(out / name, ec)) {
      fs::remove_all(out / name, ec);
      if (ec) return Failed(out / name, "cannot remove the previous output", ec, error);
    }
    fs::rename(staging / name, out / name, ec);
    if (ec) return Failed(out / name, "cannot publish", ec, error);
  }
  std::string text;
  for (const std::string& name : j.entries) text += name + "\n";
  if (!WriteFileAtomically(ManifestPath(out.string(), j.set).string(), text, error)) return false;
  if (fs::exists(staging / j.last, ec)) {
    fs::rename(staging / j.last, out / j.last, ec);
    if (ec) return Failed(out / j.last, "cannot publish", ec, error);
  }
  fs::remove_all(staging, ec);
  if (ec) return Failed(staging, "cannot remove", ec, error);
  return true;
}

}  // namespace

std::unique_ptr<OutputStaging> OutputStaging::Begin(const std::string& out_dir,
                                                    const std::string& set,
                                                    std::vector<std::string> known,
                                                    std::string* error) {
  if (!FinishPublication(out_dir, error)) return nullptr;
  const fs::path folder = fs::path(out_dir) / kStagingFolder;
  std::error_code ec;
  fs::create_directory(folder, ec);
  if (ec) {
    Failed(folder, "cannot create the staging folder", ec, error);
    return nullptr;
  }
  return std::unique_ptr<OutputStaging>(
      new OutputStaging(out_dir, set, std::move(known), folder.string()));
}

OutputStaging::~OutputStaging() {
  if (published_) return;
  // Unpublished: the previous set stays; a journal (a publication refused midway) stays too,
  // for the next command to finish.
  std::error_code ec;
  if (fs::exists(fs::path(folder_) / kJournal, ec)) return;
  fs::remove_all(folder_, ec);
}

bool OutputStaging::Publish(const std::string& last, std::string* error) {
  const fs::path out(out_dir_), staging(folder_);
  Journal j{set_, last, {}, {}};
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(staging, ec)) {
    const std::string name = entry.path().filename().string();
    if (name == kJournal) continue;
    // Checked before anything changes: a rename cannot put a file where a folder is, nor the
    // reverse, and --out must not change halfway.
    const fs::path target = out / name;
    if (fs::exists(target, ec) && fs::is_directory(target, ec) != entry.is_directory()) {
      *error = target.string() + ": is a " +
               (entry.is_directory() ? "file where vesselid writes a folder"
                                     : "folder where vesselid writes a file") +
               "; move it away (the previous results are unchanged)";
      return false;
    }
    j.entries.push_back(name);
  }
  if (ec) return Failed(staging, "cannot list", ec, error);
  std::sort(j.entries.begin(), j.entries.end());
  if (!std::binary_search(j.entries.begin(), j.entries.end(), last)) {
    *error = (staging / last).string() + ": missing from the staged outputs";
    return false;
  }
  // What the previous set held and this one does not: its manifest, else every entry a set of
  // this kind may hold.
  std::vector<std::string> previous = Lines(ManifestPath(out_dir_, set_));
  if (previous.empty()) previous = known_;
  for (const std::string& name : previous) {
    if (name.find('/') != std::string::npos || name == "." || name == "..") continue;
    if (!std::binary_search(j.entries.begin(), j.entries.end(), name) &&
        fs::exists(out / name, ec)) {
      j.remove.push_back(name);
    }
  }
  if (!WriteFileAtomically((staging / kJournal).string(), JournalText(j), error)) return false;
  published_ = Roll(out, staging, j, error);
  return published_;
}

bool FinishPublication(const std::string& out_dir, std::string* error, bool* finished) {
  if (finished != nullptr) *finished = false;
  const fs::path out(out_dir), staging = fs::path(out_dir) / kStagingFolder;
  std::error_code ec;
  if (!fs::exists(staging, ec)) return true;
  if (!fs::exists(staging / kJournal, ec)) {
    // A command stopped while writing: nothing of it reached --out.
    fs::remove_all(staging, ec);
    if (ec) return Failed(staging, "cannot remove an unfinished staging folder", ec, error);
    return true;
  }
  Journal j;
  if (!ReadJournal(staging / kJournal, &j, error)) return false;
  if (!Roll(out, staging, j, error)) return false;
  if (finished != nullptr) *finished = true;
  return true;
}

}  // namespace vesselid
