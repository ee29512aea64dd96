#include "engine/output/output_staging.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "engine/base/atomic_file.h"
#include "engine/base/text_match.h"
#include "engine/output/publish_step.h"
#include "engine/output/swap_publication.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;

// The journal (kJournal) holds one line each: "set <name>", "last <entry>", "remove <entry>",
// "entry <entry>". Its presence is what makes a staging folder complete.

struct Journal {
  std::string set, last;
  std::vector<std::string> remove, entries;
};

fs::path ManifestPath(const std::string& out_dir, const std::string& set) {
  return fs::path(out_dir) / (".vesselid-" + set + ".set");
}

bool IsLink(const fs::path& path) {
  std::error_code ec;
  return fs::symlink_status(path, ec).type() == fs::file_type::symlink;
}

bool Present(const fs::path& path) {
  std::error_code ec;
  return fs::symlink_status(path, ec).type() != fs::file_type::not_found && !ec;
}

// A path inside a folder as a manifest may name it: relative, every part a plain name.
bool PlainPath(const std::string& path) {
  if (path.empty() || path.front() == '/' || path.back() == '/') return false;
  size_t start = 0;
  while (start <= path.size()) {
    const size_t end = std::min(path.find('/', start), path.size());
    const std::string part = path.substr(start, end - start);
    if (part.empty() || part == "." || part == "..") return false;
    start = end + 1;
  }
  return path.find('\0') == std::string::npos;
}

// The lines of a regular text file; empty when it is missing or a link (not trusted).
std::vector<std::string> Lines(const fs::path& path) {
  std::vector<std::string> lines;
  std::error_code ec;
  if (fs::symlink_status(path, ec).type() != fs::file_type::regular) return lines;
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

// `name` and, for a folder, every path under it (not following links), relative to `base`:
// the lines a manifest gives an entry.
void ListEntry(const fs::path& base, const std::string& name, std::vector<std::string>* lines) {
  lines->push_back(name);
  std::error_code ec;
  if (fs::symlink_status(base / name, ec).type() != fs::file_type::directory) return;
  for (auto it = fs::recursive_directory_iterator(base / name, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    lines->push_back(it->path().lexically_relative(base).string());
  }
}

// Checks every destructive step of `j` against what vesselid wrote (NotOwned) before any is
// taken: a journal (a forged one too) cannot replace or remove what a manifest does not name.
bool JournalOwned(const fs::path& out, const fs::path& staging, const Journal& j,
                  std::string* error) {
  const std::set<std::string> owned = OwnedEntries(out.string());
  std::vector<std::string> replaced = j.remove;
  for (const std::string& name : j.entries) {
    if (Present(staging / name)) replaced.push_back(name);
  }
  for (const std::string& name : replaced) {
    const std::string why = NotOwned(out.string(), name, owned);
    if (why.empty()) continue;
    *error = why + "; the unfinished publication in " + staging.string() +
             " is not carried out (remove that folder to go on)";
    return false;
  }
  return true;
}

// The set's manifest: every entry and everything under it, where it is now (entry by entry:
// still staged or moved already; `staged_only`: all still staged, for the exchange).
std::string ManifestText(const fs::path& out, const fs::path& staging, const Journal& j,
                         bool staged_only) {
  std::vector<std::string> lines;
  for (const std::string& name : j.entries) {
    ListEntry(staged_only || !Present(out / name) ? staging : out, name, &lines);
  }
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// Publishes entry by entry, from wherever an earlier attempt stopped: every step can be
// repeated.
bool Roll(const fs::path& out, const fs::path& staging, const Journal& j, std::string* error) {
  std::error_code ec;
  // The previous set's completion file goes first: from here until the end, --out holds no
  // results.json, so nobody reads a mixture as a whole set.
  if (fs::exists(staging / j.last, ec)) {
    fs::remove(out / j.last, ec);
    if (ec) return Failed(out / j.last, "cannot remove the previous results", ec, error);
    PublishStepTaken();
  }
  for (const std::string& name : j.remove) {
    fs::remove_all(out / name, ec);
    if (ec) return Failed(out / name, "cannot remove the previous output", ec, error);
    PublishStepTaken();
  }
  // Every entry of the previous set this one replaces goes before any of this set arrives, so
  // that the folder never holds entries of both.
  // Still staged (not moved by an earlier attempt), and not a link, which vesselid never stages.
  auto staged = [&](const std::string& name) {
    return name != j.last && Present(staging / name) && !IsLink(staging / name);
  };
  for (const std::string& name : j.entries) {
    if (!staged(name)) continue;
    fs::remove_all(out / name, ec);
    if (ec) return Failed(out / name, "cannot remove the previous output", ec, error);
    PublishStepTaken();
  }
  for (const std::string& name : j.entries) {
    if (!staged(name)) continue;
    fs::rename(staging / name, out / name, ec);
    if (ec) return Failed(out / name, "cannot publish", ec, error);
    PublishStepTaken();
  }
  if (!WriteFileAtomically(ManifestPath(out.string(), j.set).string(), ManifestText(out, staging, j, false),
                           error)) {
    return false;
  }
  PublishStepTaken();
  if (fs::exists(staging / j.last, ec) && !IsLink(staging / j.last)) {
    fs::rename(staging / j.last, out / j.last, ec);
    if (ec) return Failed(out / j.last, "cannot publish", ec, error);
    PublishStepTaken();
  }
  fs::remove_all(staging, ec);
  if (ec) return Failed(staging, "cannot remove", ec, error);
  return true;
}

// Carries out `j`: by exchanging the whole folder where nothing else is at stake
// (swap_publication.h), else entry by entry.
bool Complete(const fs::path& out, const fs::path& staging, const Journal& j, std::string* error) {
  if (!JournalOwned(out, staging, j, error)) return false;
  bool swapped = false;
  if (!PublishBySwap(out.string(), {j.entries.begin(), j.entries.end()},
                     {j.remove.begin(), j.remove.end()},
                     ManifestPath(out.string(), j.set).filename().string(),
                     [&] { return ManifestText(out, staging, j, true); }, &swapped, error)) {
    return false;
  }
  return swapped || Roll(out, staging, j, error);
}

}  // namespace

std::set<std::string> OwnedEntries(const std::string& out_dir) {
  std::set<std::string> owned;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out_dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (!StartsWith(name, ".vesselid-") || !EndsWith(name, ".set")) continue;
    for (const std::string& line : Lines(entry.path())) {
      if (PlainPath(line)) owned.insert(line);
    }
  }
  return owned;
}

std::string NotOwned(const std::string& out_dir, const std::string& name,
                     const std::set<std::string>& owned) {
  const fs::path out(out_dir), path = out / name;
  if (!Present(path)) return "";
  auto refuse = [&](const fs::path& what) {
    if (IsLink(what)) {
      return what.string() + ": a link where vesselid writes its output '" + name +
             "'; vesselid neither follows nor replaces links in --out: move it away or choose "
             "another --out (nothing was changed)";
    }
    return what.string() + ": vesselid would replace this with its output '" + name +
           "', but did not write it (no manifest in the folder names it): move it away or "
           "choose another --out (nothing was changed)";
  };
  if (IsLink(path) || owned.count(name) == 0) return refuse(path);
  std::vector<std::string> inside;
  ListEntry(out, name, &inside);
  for (const std::string& p : inside) {
    if (IsLink(out / p) || owned.count(p) == 0) return refuse(out / p);
  }
  return "";
}

std::unique_ptr<OutputStaging> OutputStaging::Begin(const std::string& out_dir,
                                                    const std::string& set,
                                                    std::string* error) {
  if (!FinishPublication(out_dir, error)) return nullptr;
  const fs::path folder = fs::path(out_dir) / kStagingFolder;
  std::error_code ec;
  if (Present(folder) && fs::symlink_status(folder, ec).type() != fs::file_type::directory) {
    *error = folder.string() + ": not vesselid's staging folder (a file or a link at its name); "
             "move it away";
    return nullptr;
  }
  fs::create_directory(folder, ec);
  if (ec) {
    Failed(folder, "cannot create the staging folder", ec, error);
    return nullptr;
  }
  return std::unique_ptr<OutputStaging>(new OutputStaging(out_dir, set, folder.string()));
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
  const std::set<std::string> owned = OwnedEntries(out_dir_);
  for (const auto& entry : fs::directory_iterator(staging, ec)) {
    const std::string name = entry.path().filename().string();
    if (name == kJournal || entry.is_symlink()) continue;
    const std::string why = NotOwned(out_dir_, name, owned);
    if (!why.empty()) {
      *error = why;
      return false;
    }
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
  // What the previous set held and this one does not (its manifest's top-level entries, as
  // long as everything in them is vesselid's).
  for (const std::string& name : Lines(ManifestPath(out_dir_, set_))) {
    if (!PlainPath(name) || name.find('/') != std::string::npos) continue;
    if (!std::binary_search(j.entries.begin(), j.entries.end(), name) && Present(out / name) &&
        NotOwned(out_dir_, name, owned).empty()) {
      j.remove.push_back(name);
    }
  }
  if (!WriteFileAtomically((staging / kJournal).string(), JournalText(j), error)) return false;
  published_ = Complete(out, staging, j, error);
  return published_;
}

bool PublicationUnfinished(const std::string& out_dir) {
  const fs::path staging = fs::path(out_dir) / kStagingFolder;
  std::error_code ec;
  if (SwapUnfinished(out_dir)) return true;
  return fs::symlink_status(staging, ec).type() == fs::file_type::directory &&
         fs::symlink_status(staging / kJournal, ec).type() == fs::file_type::regular;
}

bool FinishPublication(const std::string& out_dir, std::string* error, bool* finished) {
  if (finished != nullptr) *finished = false;
  const fs::path out(out_dir), staging = fs::path(out_dir) / kStagingFolder;
  std::error_code ec;
  if (!FinishSwap(out_dir, error)) return false;
  if (!Present(staging)) return true;
  if (IsLink(staging)) {
    // Not vesselid's: what it points to is neither read nor touched; the link goes.
    fs::remove(staging, ec);
    if (ec) return Failed(staging, "cannot remove a link at the staging folder's name", ec, error);
    return true;
  }
  if (fs::symlink_status(staging, ec).type() != fs::file_type::directory) return true;
  if (fs::symlink_status(staging / kJournal, ec).type() != fs::file_type::regular) {
    // A command stopped while writing: nothing of it reached --out.
    fs::remove_all(staging, ec);
    if (ec) return Failed(staging, "cannot remove an unfinished staging folder", ec, error);
    return true;
  }
  Journal j;
  if (!ReadJournal(staging / kJournal, &j, error)) return false;
  if (!Complete(out, staging, j, error)) return false;
  if (finished != nullptr) *finished = true;
  return true;
}

}  // namespace vesselid
