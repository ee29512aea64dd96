// Publishing a staged set by exchanging the whole output folder (folder_exchange.h): a reader
// of --out at any instant sees the complete earlier set or the complete new one.
//
// The staged folder OUT/.vesselid-staging receives what the folder's bookkeeping needs (the
// set's new manifest; hard links to the marker, the lock and the other sets' manifests, so the
// lock held on OUT/.vesselid.lock is the same file on both sides), is renamed beside --out as
// PARENT/.<name>.vesselid-swap and exchanged with --out in one renameat2; the earlier folder,
// now at the sibling's name, is removed. A token file (kSwapToken) in each says which side it
// is, so that the next command finishes what a killed one left (FinishSwap).
//
// Taken only when nothing else is at stake: --out holds nothing but vesselid's bookkeeping and
// the entries this publication replaces or removes (a user's file beside the outputs, or
// another command's output folder inside, would be left behind in the old folder), every new
// entry is still staged, the sibling's name is free, the file system can exchange, and no
// process has its working folder inside --out. Otherwise the caller publishes entry by entry
// (output_staging.h), which never mixes two sets either but holds no results.json meanwhile.
#pragma once

#include <functional>
#include <set>
#include <string>

namespace vesselid {

// Publishes the set staged in OUT/.vesselid-staging (journal written; `entries` its entries,
// `removed` the earlier set's entries it removes) by the exchange. `manifest_name` is the
// set's manifest; `manifest_text` gives its text (listed only when the exchange is taken).
// *swapped is false, with nothing changed, when the exchange is not taken; false with a
// message when a step after the exchange failed (the next command finishes it).
bool PublishBySwap(const std::string& out_dir, const std::set<std::string>& entries,
                   const std::set<std::string>& removed, const std::string& manifest_name,
                   const std::function<std::string()>& manifest_text, bool* swapped,
                   std::string* error);

// Finishes what a process killed inside PublishBySwap left: before the exchange, the staged
// folder goes back to OUT/.vesselid-staging (its journal then publishes it); after it, the
// earlier folder is removed. Tokens left in --out are removed.
bool FinishSwap(const std::string& out_dir, std::string* error);

// Whether FinishSwap has something to do.
bool SwapUnfinished(const std::string& out_dir);

}  // namespace vesselid
