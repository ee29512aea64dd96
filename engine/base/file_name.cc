#include "engine/base/file_name.h"

#include <cstdio>

namespace vesselid {
namespace {

bool KeptInFileName(unsigned char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '@' || c == '#' || c == '+' || c == '=' || c == ',' || c == '-';
}

}  // namespace

std::string NameProblem(std::string_view name) {
  if (name.empty()) return "is empty";
  for (unsigned char c : name) {
    if (c < 0x20 || c == 0x7f) {
      char code[8];
      std::snprintf(code, sizeof(code), "0x%02x", c);
      return std::string("holds a control character (") + code + ")";
    }
  }
  const size_t bytes = FileNameOf(name).size();
  if (bytes > kMaxFileNameBytes) {
    return "has " + std::to_string(name.size()) + " bytes (" + std::to_string(bytes) +
           " in a file name), more than the " + std::to_string(kMaxFileNameBytes) +
           " a name may have: it names output files";
  }
  return "";
}

std::string FileNameOf(std::string_view name) {
  std::string file;
  for (unsigned char c : name) {
    if (KeptInFileName(c)) {
      file += static_cast<char>(c);
    } else {
      char code[4];
      std::snprintf(code, sizeof(code), "%%%02X", c);
      file += code;
    }
  }
  return file;
}

std::string OutputFileNameProblem(const std::string& name, const std::string& key) {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos) {
    return key + ": '" + name + "' is not a plain file name: a simulated record is written into " +
           "--out under its own name (no folder part, not absolute)";
  }
  if (name.rfind(".vesselid", 0) == 0) {
    return key + ": '" + name + "' is a name vesselid keeps for its own files in --out";
  }
  return "";
}

}  // namespace vesselid
