// x^(N/D) for an argument that moves little from one call to the next: a quartic Taylor
// expansion about the last exactly computed point x0 while |x / x0 - 1| <= span, std::pow (and a
// new expansion point) otherwise. The expansion point is the caller's state, kept per contact
// point (checkpointed with the model, so a resumed run takes the same branches). Truncation: the
// next term, p (p-1)(p-2)(p-3)(p-4)/120 r^5, relative.
#pragma once

#include <cmath>

namespace spallkit::sim::contact {

// *x0, *p0: the expansion point and x0^(N/D) (start with *x0 = 0); no state: std::pow.
template <int N, int D>
double NearPower(double x, double span, double* x0, double* p0) {
  constexpr double p = static_cast<double>(N) / D, c2 = p * (p - 1.0) / 2.0,
                   c3 = c2 * (p - 2.0) / 3.0, c4 = c3 * (p - 3.0) / 4.0;
  if (!x0) return std::pow(x, p);
  const double r = x / *x0 - 1.0;  // *x0 = 0: infinite
  if (!(std::abs(r) <= span)) {
    *x0 = x;
    *p0 = std::pow(x, p);
    return *p0;
  }
  return *p0 * (1.0 + r * (p + r * (c2 + r * (c3 + r * c4))));
}

}  // namespace spallkit::sim::contact
