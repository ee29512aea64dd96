#include "engine/output/swap_publication.h"

#include <sys/stat.h>
#include <sys/xattr.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "engine/base/atomic_file.h"
#include "engine/base/text_match.h"
#include "engine/output/checkpoint.h"
#include "engine/output/folder_exchange.h"
#include "engine/output/output_staging.h"
#include "engine/output/publish_step.h"
#include "engine/output/reserved_names.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;

constexpr char kNewSide[] = "new";  // the token of the staged folder, exchanged in
constexpr char kOldSide[] = "old";  // the token of the earlier folder, exchanged out

fs::file_type TypeOf(const fs::path& path) {
  std::error_code ec;
  return fs::symlink_status(path, ec).type();
}

bool IsManifest(const std::string& name) {
  return StartsWith(name, std::string(kReservedPrefix) + "-") && EndsWith(name, ".set");
}

// What the folder's bookkeeping carries into the new folder: the marker, the lock and the
// manifests (plain files; a link planted at one of these names is not vesselid's).
bool Carried(const std::string& name) {
  return name == kMarkerFile || name == kLockFile || IsManifest(name);
}


// The canonical --out and its sibling that the staged folder passes through.
bool SwapPaths(const std::string& out_dir, fs::path* out, fs::path* sibling) {
  std::error_code ec;
  *out = fs::canonical(out_dir, ec);
  if (ec || !out->has_parent_path() || *out == out->root_path()) return false;
  *sibling = out->parent_path() / ("." + out->filename().string() + ".vesselid-swap");
  return true;
}

std::string TokenText(const char* side, const fs::path& out) {
  return std::string(side) + "\n" + out.string() + "\n";
}

// The side a token at `path` names for `out` ("" when it is not vesselid's token for it). The
// folder is the rest of the file but its last newline: a folder's name may hold newlines.
std::string TokenSide(const fs::path& path, const fs::path& out) {
  if (TypeOf(path) != fs::file_type::regular) return "";
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t line = text.find('\n');
  if (line == std::string::npos || text.back() != '\n') return "";
  const std::string side = text.substr(0, line);
  const std::string folder = text.substr(line + 1, text.size() - line - 2);
  if (folder != out.string() || (side != kNewSide && side != kOldSide)) return "";
  return side;
}

// vesselid's working entries of `out`, left in the earlier folder and removed with it: the
// staging folder itself (it becomes the new folder), a token of this folder's and a run's
// working checkpoint (published as checkpoint/). Only entries vesselid can tell it wrote: a
// temporary or a file of the user's at a reserved name keeps the folder from being exchanged.
bool Working(const fs::path& out, const std::string& name) {
  if (name == kStagingFolder) return true;
  if (name == kSwapToken) return !TokenSide(out / name, out).empty();
  if (name == kWorkingCheckpoint) return CheckpointNotOwned(out.string()).empty();
  return false;
}

bool Failed(const fs::path& path, const std::error_code& ec, std::string* error) {
  *error = path.string() + ": cannot remove the earlier output: " + ec.message();
  return false;
}

// Removes the earlier folder at `sibling`: what its manifests name and vesselid's bookkeeping,
// its token last (a process killed midway leaves a folder the next command still knows as
// vesselid's), then the folder if nothing else is in it. Anything else (a user's file put there
// since) stays, with the folder.
bool RemoveSwappedOut(const fs::path& sibling, std::string* error) {
  const std::set<std::string> owned = OwnedEntries(sibling.string());
  // Outputs and working entries first, the manifests (which name the outputs), marker and lock
  // after them: a kill midway leaves every output still named.
  std::vector<fs::path> outputs, bookkeeping;
  bool foreign = false;
  std::error_code ec;
  for (auto it = fs::directory_iterator(sibling, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name == kSwapToken) continue;
    if (Carried(name)) {
      bookkeeping.push_back(it->path());
    } else if (Working(sibling, name) || NotOwned(sibling.string(), name, owned).empty()) {
      outputs.push_back(it->path());
    } else {
      foreign = true;  // not vesselid's: kept
    }
  }
  if (ec) return Failed(sibling, ec, error);
  for (const fs::path& path : outputs) {
    fs::remove_all(path, ec);
    if (ec) return Failed(path, ec, error);
    PublishStepTaken();
  }
  if (foreign) return true;  // a user's entry: the folder stays, with what names vesselid's
  for (const fs::path& path : bookkeeping) {
    fs::remove(path, ec);
    if (ec) return Failed(path, ec, error);
    PublishStepTaken();
  }
  PublishStepTaken();
  fs::remove(sibling / kSwapToken, ec);
  PublishStepTaken();
  fs::remove(sibling, ec);
  if (ec) return Failed(sibling, ec, error);
  return true;
}

// The journal and the token that travel with the new folder: gone once it is --out, the token
// last (it is what tells the next command that the journal is vesselid's).
void RemoveSwapLeftovers(const fs::path& out) {
  std::error_code ec;
  for (const char* name : {kJournal, kSwapToken}) {
    if (TypeOf(out / name) != fs::file_type::regular) continue;
    fs::remove(out / name, ec);
    PublishStepTaken();
  }
}

// The names of the extended attributes of `path` (its ACLs among them); false when they cannot
// be listed.
bool AttributeNames(const fs::path& path, std::vector<std::string>* names) {
  names->clear();
  const ssize_t size = ::listxattr(path.c_str(), nullptr, 0);
  if (size < 0) return errno == ENOTSUP;  // a file system without them: none
  std::string list(static_cast<size_t>(size), '\0');
  const ssize_t got = ::listxattr(path.c_str(), list.data(), list.size());
  if (got < 0) return false;
  for (size_t at = 0; at < static_cast<size_t>(got);) {
    const size_t end = list.find('\0', at);
    names->push_back(list.substr(at, end - at));
    at = end + 1;
  }
  return true;
}

// The staged folder's extended attributes made those of --out (its access and default ACLs, a
// user's notes): the staged folder, made inside --out, may have inherited others.
bool TakeExtendedAttributes(const fs::path& out, const fs::path& staging) {
  std::vector<std::string> wanted, present;
  if (!AttributeNames(out, &wanted) || !AttributeNames(staging, &present)) return false;
  for (const std::string& name : present) {
    if (std::find(wanted.begin(), wanted.end(), name) == wanted.end() &&
        ::removexattr(staging.c_str(), name.c_str()) != 0) {
      return false;
    }
  }
  for (const std::string& name : wanted) {
    const ssize_t size = ::getxattr(out.c_str(), name.c_str(), nullptr, 0);
    if (size < 0) return false;
    std::string value(static_cast<size_t>(size), '\0');
    if (::getxattr(out.c_str(), name.c_str(), value.data(), value.size()) != size ||
        ::setxattr(staging.c_str(), name.c_str(), value.data(), value.size(), 0) != 0) {
      return false;
    }
  }
  return true;
}

// The staged folder takes the permission bits, owner, group and extended attributes (ACLs) of
// --out (a folder made private stays private); false when they cannot be given (then no
// exchange).
bool TakeAttributes(const fs::path& out, const fs::path& staging) {
  struct stat from, to;
  if (::stat(out.c_str(), &from) != 0 || ::stat(staging.c_str(), &to) != 0) return false;
  if ((from.st_uid != to.st_uid || from.st_gid != to.st_gid) &&
      ::chown(staging.c_str(), from.st_uid, from.st_gid) != 0) {
    return false;
  }
  return ::chmod(staging.c_str(), from.st_mode & 07777) == 0 && TakeExtendedAttributes(out, staging);
}

// Whether `out` holds nothing the exchange would leave behind (see the header).
bool OnlyVesselidsEntries(const fs::path& out, const std::set<std::string>& entries,
                          const std::set<std::string>& removed) {
  std::error_code ec;
  for (auto it = fs::directory_iterator(out, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (Carried(name) || Working(out, name) || entries.count(name) != 0 ||
        removed.count(name) != 0) {
      continue;
    }
    return false;
  }
  return !ec;
}

}  // namespace

bool PublishBySwap(const std::string& out_dir, const std::set<std::string>& entries,
                   const std::set<std::string>& removed, const std::string& manifest_name,
                   const std::function<std::string()>& manifest_text, bool* swapped,
                   std::string* error) {
  *swapped = false;
  fs::path out, sibling;
  if (!SwapPaths(out_dir, &out, &sibling)) return true;
  const fs::path staging = out / kStagingFolder;
  if (TypeOf(sibling) != fs::file_type::not_found || !OnlyVesselidsEntries(out, entries, removed) ||
      SomeoneWorksInside(out.string())) {
    return true;
  }
  for (const std::string& name : entries) {
    if (TypeOf(staging / name) == fs::file_type::not_found) return true;  // moved in already
  }
  std::error_code ec;
  // The new folder's bookkeeping (what a killed earlier attempt put there is made afresh).
  std::string unused;
  if (!WriteFileAtomically((staging / manifest_name).string(), manifest_text(), &unused)) return true;
  for (auto it = fs::directory_iterator(out, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!Carried(name) || name == manifest_name || !it->is_regular_file()) continue;
    std::error_code link_ec;
    fs::remove(staging / name, link_ec);
    fs::create_hard_link(it->path(), staging / name, link_ec);
    if (link_ec) return true;
  }
  if (ec || !TakeAttributes(out, staging) ||
      !WriteFileAtomically((staging / kSwapToken).string(), TokenText(kNewSide, out), &unused) ||
      !WriteFileAtomically((out / kSwapToken).string(), TokenText(kOldSide, out), &unused)) {
    fs::remove(out / kSwapToken, ec);
    return true;
  }
  PublishStepTaken();
  fs::rename(staging, sibling, ec);
  if (ec) {  // another file system beside --out (a mount point), or a parent without write access
    fs::remove(out / kSwapToken, ec);
    return true;
  }
  PublishStepTaken();
  std::string exchange_error;
  if (!ExchangeFolders(sibling.string(), out.string(), &exchange_error)) {
    // The file system cannot exchange: the staged folder goes back where it was.
    fs::rename(sibling, staging, ec);
    if (ec) {
      *error = sibling.string() + ": cannot return the staged outputs to " + staging.string() +
               ": " + ec.message() + " (the next vesselid command on the folder does)";
      return false;
    }
    fs::remove(out / kSwapToken, ec);
    return true;
  }
  *swapped = true;
  PublishStepTaken();
  RemoveSwapLeftovers(out);
  return RemoveSwappedOut(sibling, error);
}

bool SwapUnfinished(const std::string& out_dir) {
  fs::path out, sibling;
  if (!SwapPaths(out_dir, &out, &sibling)) return false;
  if (!TokenSide(out / kSwapToken, out).empty()) return true;
  if (TypeOf(sibling) != fs::file_type::directory) return false;
  const std::string side = TokenSide(sibling / kSwapToken, out);
  return side == kOldSide ||
         (side == kNewSide && TypeOf(sibling / kJournal) == fs::file_type::regular);
}

bool FinishSwap(const std::string& out_dir, std::string* error) {
  fs::path out, sibling;
  if (!SwapPaths(out_dir, &out, &sibling)) return true;
  const std::string side = TypeOf(sibling) == fs::file_type::directory
                               ? TokenSide(sibling / kSwapToken, out)
                               : std::string();
  std::error_code ec;
  if (side.empty() && TypeOf(sibling) == fs::file_type::directory && fs::is_empty(sibling, ec)) {
    fs::remove(sibling, ec);  // killed after the earlier folder's token went: empty, so ours
  }
  if (side == kNewSide && TypeOf(sibling / kJournal) == fs::file_type::regular) {
    // Killed before the exchange: --out holds the whole earlier set; the staged set goes back
    // to the staging folder, whose journal publishes it.
    const fs::path staging = out / kStagingFolder;
    if (TypeOf(staging) != fs::file_type::not_found) {
      *error = staging.string() + " and " + sibling.string() +
               ": two staged sets; remove the one that is not wanted";
      return false;
    }
    fs::rename(sibling, staging, ec);
    if (ec) {
      *error = sibling.string() + ": cannot return the staged outputs: " + ec.message();
      return false;
    }
    fs::remove(staging / kSwapToken, ec);
  } else if (side == kOldSide) {
    // Killed after the exchange: --out holds the whole new set; the earlier one goes.
    if (!RemoveSwappedOut(sibling, error)) return false;
  }
  if (TokenSide(out / kSwapToken, out) == kNewSide) {
    RemoveSwapLeftovers(out);
  } else if (!TokenSide(out / kSwapToken, out).empty()) {
    fs::remove(out / kSwapToken, ec);
  }
  return true;
}

}  // namespace vesselid
