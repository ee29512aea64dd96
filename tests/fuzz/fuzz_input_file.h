// The file a fuzz input is written to: the readers under test take a path, not bytes. One
// folder per process (in /dev/shm when it exists, so inputs stay in memory), made once and
// removed at a normal exit; concurrent fuzzers (-jobs, -fork) each get their own.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace vesselid::fuzz {

// A broken invariant of an accepted input is a finding: abort so that libFuzzer keeps it.
#define FUZZ_CHECK(condition)                                                       \
  do {                                                                              \
    if (!(condition)) {                                                             \
      std::fprintf(stderr, "%s:%d: fuzz check failed: %s\n", __FILE__, __LINE__, \
                   #condition);                                                     \
      std::abort();                                                                 \
    }                                                                               \
  } while (0)

class FuzzInputFile {
 public:
  explicit FuzzInputFile(const std::string& name) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path root = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm")
                                                           : fs::temp_directory_path();
    folder_ = root / ("vesselid_fuzz_" + std::to_string(::getpid()));
    fs::create_directories(folder_);
    path_ = (folder_ / name).string();
  }
  ~FuzzInputFile() {
    std::error_code ec;
    std::filesystem::remove_all(folder_, ec);
  }
  FuzzInputFile(const FuzzInputFile&) = delete;
  FuzzInputFile& operator=(const FuzzInputFile&) = delete;

  // Replaces the file's contents with the input; returns its path.
  const std::string& Write(const uint8_t* data, size_t size) {
    std::FILE* file = std::fopen(path_.c_str(), "wb");
    FUZZ_CHECK(file != nullptr);
    FUZZ_CHECK(size == 0 || std::fwrite(data, 1, size, file) == size);
    FUZZ_CHECK(std::fclose(file) == 0);
    return path_;
  }

  const std::string& path() const { return path_; }

 private:
  std::filesystem::path folder_;
  std::string path_;
};

}  // namespace vesselid::fuzz
