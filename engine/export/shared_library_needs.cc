#include "engine/export/shared_library_needs.h"

#include <elf.h>

#include <cstring>
#include <fstream>
#include <iterator>

namespace vesselid {

bool SharedLibraryNeeds(const std::string& path, std::vector<std::string>* needs,
                        std::string* error) {
  needs->clear();
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto fail = [&](const std::string& why) {
    *error = path + ": " + why;
    return false;
  };
  Elf64_Ehdr header;
  if (bytes.size() < sizeof(header)) return fail("not an ELF file");
  std::memcpy(&header, bytes.data(), sizeof(header));
  if (std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0 || header.e_ident[EI_CLASS] != ELFCLASS64) {
    return fail("not a 64-bit ELF file");
  }
  // Every section header, inside the file.
  auto section = [&](size_t k, Elf64_Shdr* s) {
    const size_t at = header.e_shoff + k * sizeof(Elf64_Shdr);
    if (at + sizeof(Elf64_Shdr) > bytes.size()) return false;
    std::memcpy(s, bytes.data() + at, sizeof(Elf64_Shdr));
    return s->sh_offset + s->sh_size <= bytes.size();
  };
  for (size_t k = 0; k < header.e_shnum; ++k) {
    Elf64_Shdr dynamic, strings;
    if (!section(k, &dynamic) || dynamic.sh_type != SHT_DYNAMIC) continue;
    if (!section(dynamic.sh_link, &strings)) return fail("a dynamic section without its strings");
    for (size_t at = 0; at + sizeof(Elf64_Dyn) <= dynamic.sh_size; at += sizeof(Elf64_Dyn)) {
      Elf64_Dyn entry;
      std::memcpy(&entry, bytes.data() + dynamic.sh_offset + at, sizeof(entry));
      if (entry.d_tag == DT_NULL) break;
      if (entry.d_tag != DT_NEEDED || entry.d_un.d_val >= strings.sh_size) continue;
      const char* name = bytes.data() + strings.sh_offset + entry.d_un.d_val;
      needs->emplace_back(name, strnlen(name, strings.sh_size - entry.d_un.d_val));
    }
    return true;
  }
  return fail("no dynamic section");
}

}  // namespace vesselid
