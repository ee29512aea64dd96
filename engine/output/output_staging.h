// A command's outputs appear together or not at all. They are written into a staging folder
// inside --out (OUT/.vesselid-staging/, same file system, so every move is a rename) and then
// published: a journal in the staging folder lists the set. Where --out holds nothing but
// vesselid's outputs the whole folder is exchanged for the staged one in one step
// (swap_publication.h); otherwise, entry by entry: the previous set's completion file
// (results.json for `run`) is removed first, then every entry of the previous set (those this
// set replaces and those it lacks), then the staged entries are moved in, the set's manifest
// (OUT/.vesselid-<set>.set) is rewritten, and the completion file is renamed in last: the
// folder never holds entries of two sets, and holds results.json only over a whole one. Whatever
// fails before the journal is written (a full disk, a file name, a signal) leaves the previous
// complete set as it was; a process killed while publishing leaves a journal, and the next
// vesselid command on the folder finishes the publication (FinishPublication, called under the
// folder's lock). So a folder with results.json always holds one whole set.
//
// vesselid touches only what it wrote. What it wrote is what a manifest in --out names
// (OwnedEntries): a manifest reached through a link, or naming anything but a plain entry of
// the folder, is not trusted. An entry in the way of an output that no manifest names (a
// user's traces/ beside the config, a report.txt of their own) is refused before anything
// changes, and so is a journal asking to replace or remove one; links inside --out are never
// followed (a staging folder or journal that is a link is not vesselid's).
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "engine/output/reserved_names.h"

namespace vesselid {

class OutputStaging {
 public:
  // Starts an empty staging folder in `out_dir` (which the caller has locked: OutputFolder)
  // for the set `set` ("run", "study"). Null with a message when it cannot be made.
  static std::unique_ptr<OutputStaging> Begin(const std::string& out_dir, const std::string& set,
                                              std::string* error);
  ~OutputStaging();  // removes the staging folder unless it was published
  OutputStaging(const OutputStaging&) = delete;
  OutputStaging& operator=(const OutputStaging&) = delete;

  // Where the outputs are written, under their final names relative to --out.
  const std::string& folder() const { return folder_; }

  // Publishes every entry of folder(), `last` (a file among them) last. False with a message
  // when an entry cannot replace its namesake (a folder where a file goes, or the reverse; a
  // namesake no manifest names): then nothing in --out has changed. A failure after the journal (a rename refused midway)
  // leaves the journal, and the next command finishes the publication.
  bool Publish(const std::string& last, std::string* error);

 private:
  OutputStaging(std::string out_dir, std::string set, std::string folder)
      : out_dir_(std::move(out_dir)), set_(std::move(set)), folder_(std::move(folder)) {}
  std::string out_dir_, set_;
  std::string folder_;
  bool published_ = false;
};

// Finishes a publication a killed process left in `out_dir` (a staging folder with its
// journal) and removes a staging folder without one (a command stopped while writing: the
// previous set is whole). `finished` (optional) is set when a publication was finished.
bool FinishPublication(const std::string& out_dir, std::string* error, bool* finished = nullptr);

// The entries of `out_dir` that vesselid wrote: the union of the names its sets' manifests
// (OUT/.vesselid-*.set, regular files, not links) list, each a plain entry of the folder.
std::set<std::string> OwnedEntries(const std::string& out_dir);

// "" when `name` in `out_dir` is absent or vesselid's to replace (OwnedEntries names it and it
// is not a link); else why not, naming the path, for a refusal that changes nothing.
std::string NotOwned(const std::string& out_dir, const std::string& name,
                     const std::set<std::string>& owned);

// Whether `out_dir` holds a publication a killed process left (a staging folder, not a link,
// with its journal): the next command on the folder finishes it (OutputFolder::Open).
bool PublicationUnfinished(const std::string& out_dir);

}  // namespace vesselid
