#include "engine/base/case_seed.h"

namespace vesselid {

unsigned CaseSeed(unsigned study_seed, int part, int index) {
  unsigned long long z = (static_cast<unsigned long long>(study_seed) << 32) ^
                         (static_cast<unsigned long long>(part) << 24) ^
                         static_cast<unsigned long long>(index);
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<unsigned>(z & 0xFFFFFFFFu);
}

}  // namespace vesselid
