// Names that become parts of output file names (experiments, stages): what a name may hold,
// and the reversible escape that makes a file name of it, so that two names never share a
// file (traces/fit.a/b.csv and traces/fit.a_b.csv were one file before).
#pragma once

#include <string>
#include <string_view>

namespace vesselid {

// The longest name as a file name (escaped, FileNameOf), in bytes: a trace's file name holds a
// stage's and an experiment's, "<stage>.validation.<experiment>.csv", within a file
// system's 255.
constexpr size_t kMaxFileNameBytes = 115;

// Empty when `name` may name an experiment or stage, else why not ("is empty", "has 5000
// bytes, more than the 115 ...", "holds a control character (0x0a)").
std::string NameProblem(std::string_view name);

// `name` with every byte outside [A-Za-z0-9_@#+=,-] written as %XX (two upper-case hex
// digits): "a/b" -> "a%2Fb", "a.b" -> "a%2Eb", "zz10s_a" unchanged. Reversible, so distinct
// names give distinct file names; '.' is escaped because it joins names in a file name.
std::string FileNameOf(std::string_view name);

// Empty when `name` is a plain file name a command may write into its own folder (no folder
// part, not absolute, not . or .., not one of vesselid's own .vesselid* files); else why not.
// `key` names where it came from ("simulation.steps_file").
std::string OutputFileNameProblem(const std::string& name, const std::string& key);

}  // namespace vesselid
