// Terms of the quasi-quadratic lumped dynamics of MODELS.md §3 (seed 000, eq. 18):
//   f_i(nu) = sum_k c_ik phi_k(nu),  phi_k in {1, u, v, r, |u|u, |v|v, |r|r, uv, ur, vr,
//                                               uu, vv, rr}
// A basis is a list of term indices chosen per velocity component in the config.
#pragma once

#include <array>
#include <cmath>
#include <string>

namespace vesselid::input_gain {

enum Term { kTermOne, kTermU, kTermV, kTermR, kTermAbsUU, kTermAbsVV, kTermAbsRR, kTermUV, kTermUR, kTermVR, kTermUU, kTermVV, kTermRR, kTermNumTerms };

// Config and parameter names of the terms ("u.|u|u" is the |u|u coefficient of surge).
inline const std::array<std::string, kTermNumTerms>& TermNames() {
  static const std::array<std::string, kTermNumTerms> names = {
      "1", "u", "v", "r", "|u|u", "|v|v", "|r|r", "uv", "ur", "vr", "uu", "vv", "rr"};
  return names;
}

inline bool StringToTerm(const std::string& text, int* term) {
  for (int k = 0; k < kTermNumTerms; ++k) {
    if (TermNames()[k] == text) {
      *term = k;
      return true;
    }
  }
  return false;
}

template <class T>
T TermValue(int term, const T& u, const T& v, const T& r) {
  using std::abs;
  switch (term) {
    case kTermOne: return T(1.0);
    case kTermU: return u;
    case kTermV: return v;
    case kTermR: return r;
    case kTermAbsUU: return abs(u) * u;
    case kTermAbsVV: return abs(v) * v;
    case kTermAbsRR: return abs(r) * r;
    case kTermUV: return u * v;
    case kTermUR: return u * r;
    case kTermVR: return v * r;
    case kTermUU: return u * u;
    case kTermVV: return v * v;
    default: return r * r;
  }
}

}  // namespace vesselid::input_gain
