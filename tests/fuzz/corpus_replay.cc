// A main() for the fuzz targets when libFuzzer is not linked (g++ builds): feeds every file
// in the folders (or the files) given on the command line to LLVMFuzzerTestOneInput once, so
// that each build checks that no seed or regression input crashes a reader.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

namespace fs = std::filesystem;

bool Replay(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    std::error_code ec;
    if (fs::is_directory(argv[i], ec)) {
      for (const fs::directory_entry& entry : fs::directory_iterator(argv[i])) {
        if (entry.is_regular_file()) files.push_back(entry.path());
      }
    } else {
      files.push_back(argv[i]);
    }
  }
  // Sorted, so that a failure names the same input on every run.
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s <corpus folder or file>...: no input found\n", argv[0]);
    return 1;
  }
  for (const fs::path& file : files) {
    std::fprintf(stderr, "replay %s\n", file.string().c_str());
    if (!Replay(file)) {
      std::fprintf(stderr, "%s: cannot read file\n", file.string().c_str());
      return 1;
    }
  }
  std::fprintf(stderr, "replayed %zu inputs\n", files.size());
  return 0;
}
