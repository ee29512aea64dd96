// Thrust law of the input-gain propellers as configured terms (MODELS.md §3):
//
//   T_s(x) = sum_k a_k phi_k(s),  s = x - d_f,  x > d_f     (ahead)
//   T_s(x) = sum_k c_k phi_k(s),  s = x - d_r,  x < d_r     (astern),  else 0
//
// over the listed terms phi: linear `n` (s) and quadratic `n|n|` (s|s|). The scale lives in
// the gains b_u, b_v, b_r, so one ahead coefficient is 1: the linear term's when it is listed,
// else the quadratic's; the other ahead coefficient is k_f. Astern: k_r1 (linear) and k_r2
// (quadratic, written -k_r2 s^2 = k_r2 s|s|). The dead zone [d_r, d_f] is optional.
//   thrust: [n, "n|n|"], dead_zone: true   (default, seed 000)  k_f k_r1 k_r2 d_f d_r
//   thrust: ["n|n|"], dead_zone: false     (a purely quadratic thruster)  k_r2
// The names are resolved once into parameter offsets, so the right-hand side tests flags.
#pragma once

#include <string>
#include <vector>

namespace vesselid::input_gain {

struct ThrustLaw {
  bool linear = true;     // term n
  bool quadratic = true;  // term n|n|
  bool dead_zone = true;  // parameters d_f, d_r

  // Config names of the listed terms, in canonical order ("n", "n|n|").
  std::vector<std::string> TermNames() const {
    std::vector<std::string> names;
    if (linear) names.push_back("n");
    if (quadratic) names.push_back("n|n|");
    return names;
  }
  bool Default() const { return linear && quadratic && dead_zone; }
};

// Offsets of the propeller parameters after the gains (-1: not a parameter of the law), in
// the order k_f, k_r1, k_r2, d_f, d_r, tau_T.
struct ThrustOffsets {
  int k_f = -1, k_r1 = -1, k_r2 = -1, d_f = -1, d_r = -1, tau_T = -1;
  int count = 0;

  ThrustOffsets(const ThrustLaw& law, bool dynamic) {
    if (law.linear && law.quadratic) k_f = count++;
    if (law.linear) k_r1 = count++;
    if (law.quadratic) k_r2 = count++;
    if (law.dead_zone) {
      d_f = count++;
      d_r = count++;
    }
    if (dynamic) tau_T = count++;
  }
};

// Reads a term's config name; false when it is none.
inline bool StringToThrustTerm(const std::string& text, ThrustLaw* law) {
  if (text == "n") {
    law->linear = true;
    return true;
  }
  if (text == "n|n|") {
    law->quadratic = true;
    return true;
  }
  return false;
}

}  // namespace vesselid::input_gain
