// What a data-partition study (partition_study.h) splits and how: the `study.partitions`
// section as plain data.
#pragma once

#include <string>
#include <vector>

namespace vesselid {

struct StudyOptions {
  // Name of a stage of the run; empty: the run's last stage when it is an output-error
  // stage, else its first least_squares stage.
  std::string stage;
  // Least squares: the pool of records, config experiment names each expanded to its
  // segments; empty: the stage's experiments followed by its validation experiments.
  // Output error: experiments added to the stage's own (each segment its own experiment).
  std::vector<std::string> experiments;
  // Repetitions of table (a); repetition r splits with seed + r.
  int partitions = 20;
  // Share of the pool's units held out for validation, in (0, 1).
  double validation_share = 0.3;
  // Training shares of table (b); validation_share + each share <= 1.
  std::vector<double> training_shares = {0.7, 0.6, 0.5};
  // Units of a split: "segments" (whole records) and/or "points" (samples).
  std::vector<std::string> methods = {"segments", "points"};
  unsigned seed = 1;

  bool IsValid(std::string* error) const;
};

}  // namespace vesselid
