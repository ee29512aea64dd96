// Seeds of independent random cases (study cases, bootstrap replicates): a pure function of
// the seed, a part number and the case index, so that no case depends on how cases are
// distributed over threads or processes.
#pragma once

namespace vesselid {

// SplitMix64 finaliser over (seed, part, index): nearby indices give unrelated seeds.
unsigned CaseSeed(unsigned study_seed, int part, int index);

}  // namespace vesselid
