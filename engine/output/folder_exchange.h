// Two folders of one file system traded in one step: renameat2(RENAME_EXCHANGE). A reader of
// either path sees the one folder or the other, never a mixture and never nothing. The
// publication uses it to put a whole new set where the earlier one was (output_staging.h).
#pragma once

#include <string>

namespace vesselid {

// Exchanges the folders at `a` and `b` (both must exist, on one file system). False with the
// system's reason (the file system cannot exchange, or the folders are on two) when nothing
// was changed.
bool ExchangeFolders(const std::string& a, const std::string& b, std::string* error);

// Whether some process the user can see (this one included) has its working folder at or
// under `folder` (a canonical path): a shell open there would be left in a removed folder by
// an exchange, so the publication then moves entries one by one instead.
bool SomeoneWorksInside(const std::string& folder);

}  // namespace vesselid
