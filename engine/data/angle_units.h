// Whether an angle column read as radians looks like degrees. Degrees read as radians stay
// within [-180, 360] but span more than one turn, or step across their 0/360 wrap by far more
// than pi; radians that do so wrap within one turn. The check:
//   * a step |y_k - y_(k-1)| > pi where either value lies outside one turn (|y| > 2 pi), or
//   * a range max - min > 2 pi while the channel swings back and forth: its travel (the
//     sum of moves larger than kSwingBand, so that noise does not add up) exceeds 1.5 x the
//     range, and those moves change direction kSwingReversals times or more. Whole turns
//     logged unwrapped in radians travel about their range once; a spiral test (several turns
//     one way, then the other) reverses once or twice, a zigzag in degrees many times.
// A run warns (unit_findings.h); it cannot refuse: no series proves its unit.
#pragma once

#include <string>
#include <vector>

namespace vesselid {

inline constexpr double kSwingBand = 0.5;  // rad: moves below it are not counted as travel
inline constexpr int kSwingReversals = 3;

struct AngleUnitCheck {
  bool looks_like_degrees = false;
  double min = 0.0, max = 0.0;  // of the finite values
  double largest_step = 0.0;    // largest |y_k - y_(k-1)|
};

// NaN values (missing samples) are skipped.
AngleUnitCheck CheckAngleUnit(const std::vector<double>& values);

// "column 'psi' looks like degrees: range 0–359.8, steps up to 12.1; add it to degrees:".
std::string DescribeDegreesLook(const std::string& column, const AngleUnitCheck& check);

}  // namespace vesselid
