// A command's outputs appear together or not at all. They are written into a staging folder
// inside --out (OUT/.vesselid-staging/, same file system, so every move is a rename) and then
// published: a journal in the staging folder lists the set; the previous set's completion file
// (results.json for `run`) is removed first, then every staged entry replaces its namesake,
// entries of the previous set this one lacks (its manifest, OUT/.vesselid-<set>.set) are removed,
// and the completion file is renamed in last. Whatever fails before the journal is written (a
// full disk, a file name, a signal) leaves the previous complete set as it was; a process
// killed while publishing leaves a journal, and the next vesselid command on the folder
// finishes the publication (FinishPublication, called under the folder's lock). So a folder
// with results.json always holds one whole set.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace vesselid {

class OutputStaging {
 public:
  // Starts an empty staging folder in `out_dir` (which the caller has locked: OutputFolder)
  // for the set `set` ("run", "study"); `known` names the entries a set of this kind may hold,
  // removed when absent from this one although the previous set's manifest is missing (an
  // output of a version without manifests). Null with a message when it cannot be made.
  static std::unique_ptr<OutputStaging> Begin(const std::string& out_dir, const std::string& set,
                                              std::vector<std::string> known, std::string* error);
  ~OutputStaging();  // removes the staging folder unless it was published
  OutputStaging(const OutputStaging&) = delete;
  OutputStaging& operator=(const OutputStaging&) = delete;

  // Where the outputs are written, under their final names relative to --out.
  const std::string& folder() const { return folder_; }

  // Publishes every entry of folder(), `last` (a file among them) last. False with a message
  // when an entry cannot replace its namesake (a folder where a file goes, or the reverse):
  // then nothing in --out has changed. A failure after the journal (a rename refused midway)
  // leaves the journal, and the next command finishes the publication.
  bool Publish(const std::string& last, std::string* error);

 private:
  OutputStaging(std::string out_dir, std::string set, std::vector<std::string> known,
                std::string folder)
      : out_dir_(std::move(out_dir)),
        set_(std::move(set)),
        known_(std::move(known)),
        folder_(std::move(folder)) {}
  std::string out_dir_, set_;
  std::vector<std::string> known_;
  std::string folder_;
  bool published_ = false;
};

// Finishes a publication a killed process left in `out_dir` (a staging folder with its
// journal) and removes a staging folder without one (a command stopped while writing: the
// previous set is whole). `finished` (optional) is set when a publication was finished.
bool FinishPublication(const std::string& out_dir, std::string* error, bool* finished = nullptr);

// The staging folder's name inside --out.
inline constexpr char kStagingFolder[] = ".vesselid-staging";

}  // namespace vesselid
