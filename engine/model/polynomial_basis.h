// Complete polynomial bases in two variables (seed 004 eq. (12)): every monomial a^i b^j with
// i + j <= degree, ordered by degree and, within a degree, by falling power of a:
//
//   degree 4:  1, a, b, a^2, ab, b^2, a^3, a^2 b, a b^2, b^3, a^4, a^3 b, a^2 b^2, a b^3, b^4
//
// Written once for double and Jets; no allocation, so it may run per integration step.
#pragma once

#include <string>
#include <vector>

namespace vesselid {

constexpr int NumMonomials(int degree) { return (degree + 1) * (degree + 2) / 2; }

// out[NumMonomials(degree)] = the monomials of (a, b) in the order above.
template <class T>
void Monomials(int degree, const T& a, const T& b, T* out) {
  out[0] = T(1.0);
  int first = 0;  // index of a^(d-1) in the previous degree
  for (int d = 1, k = 1; d <= degree; ++d) {
    // Degree d: a * (each monomial of degree d-1), then b * (the last one, b^(d-1)).
    for (int j = 0; j < d; ++j) out[k++] = a * out[first + j];
    out[k++] = b * out[first + d - 1];
    first += d;
  }
}

// Names as "1", "U", "r", "U2", "Ur", "r2", "U2r", ... (exponents written after the variable).
inline std::vector<std::string> MonomialNames(int degree, const std::string& a,
                                              const std::string& b) {
  auto power = [](const std::string& v, int e) {
    return e == 0 ? std::string() : e == 1 ? v : v + std::to_string(e);
  };
  std::vector<std::string> names = {"1"};
  for (int d = 1; d <= degree; ++d) {
    for (int j = 0; j <= d; ++j) names.push_back(power(a, d - j) + power(b, j));
  }
  return names;
}

// Exponent of b in monomial k (parity under b -> -b).
inline int MonomialPowerOfB(int degree, int k) {
  for (int d = 0, first = 0; d <= degree; first += d + 1, ++d) {
    if (k < first + d + 1) return k - first;
  }
  return -1;
}

}  // namespace vesselid
