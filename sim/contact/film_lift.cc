#include "sim/contact/film_lift.h"

#include <algorithm>
#include <cmath>

#include "sim/contact/near_power.h"

namespace spallkit::sim::contact {

namespace {

constexpr double kPalmgrenExponent = 10.0 / 9.0;
constexpr double kNearSpan = 5e-3;  // FilmContactMemory's expansions: |x / x0 - 1| <= this

// A point left of the root of F below (F(start) <= 0).
double LeftStart(double x) {
  if (x >= 0.0) return std::max(x, 1.0);  // F(1) = -x, F(x) = -x^(-10/9)
  if (x >= -1.0) return 0.6;              // F(0.6) < -1.16 - x < 0
  // y^(-10/9) = y - x <= y_max - x with y_max = (-x)^(-9/10)
  return std::pow(std::pow(-x, -0.9) - x, -0.9);
}

// The root y > 0 of F(y) = y - y^(-10/9) - x, and F'(y) = 1 + 10/9 y^(-19/9) there. F is
// increasing and concave. Without a memory: Newton's method from a point left of the root, which
// climbs to it monotonically. With one: Halley's method (cubic convergence) from the last root,
// close on either side, so that one step usually suffices; a step that would leave y > 0 starts
// again from the left.
double ElasticApproach(double x, double* slope, FilmContactMemory* m) {
  double* y0 = m ? &m->root0 : nullptr;
  double* p0 = m ? &m->root0_power : nullptr;
  const bool warm = m && m->root > 0.0;
  double y = warm ? m->root : LeftStart(x);
  for (int it = 0; it < 100; ++it) {
    const double ym = NearPower<-10, 9>(y, kNearSpan, y0, p0);
    const double inv_y = 1.0 / y;
    const double f = y - ym - x;
    const double fp = 1.0 + kPalmgrenExponent * ym * inv_y;
    double step;
    bool done;
    if (warm && it < 3) {
      // F'' = -(10/9)(19/9) y^(-28/9); after a Halley step of s the error is of order s^3.
      const double fpp = -(190.0 / 81.0) * ym * inv_y * inv_y;
      step = 2.0 * f * fp / (2.0 * fp * fp - f * fpp);
      done = !(std::abs(step) > 1e-5 * y);
    } else {
      step = f / fp;  // Newton: the error after a step of s is of order s^2
      done = !(std::abs(step) > 1e-7 * y);
    }
    if (!(y - step > 0.0)) {
      y = LeftStart(x);
      continue;
    }
    y -= step;
    if (done) break;
  }
  if (m) m->root = y;
  // At the root y^(-10/9) = y - x, so F'(y) = 1 + 10/9 (y - x) / y needs no power.
  *slope = 1.0 + kPalmgrenExponent * (y - x) / y;
  return y;
}

}  // namespace

double MartinFilmCoefficient(double viscosity_pa_s,
                             double entrainment_speed,
                             double reduced_radius,
                             double length) {
  return 4.9 * viscosity_pa_s * std::abs(entrainment_speed) * reduced_radius * length;
}

FilmContactLoad FilmLineContact(double approach,
                                double film_coefficient,
                                double palmgren_k,
                                FilmContactMemory* memory) {
  FilmContactLoad out;
  double* e0 = memory ? &memory->elastic0 : nullptr;
  double* e0_power = memory ? &memory->elastic0_power : nullptr;
  if (!(film_coefficient > 0.0)) {  // Palmgren's law alone
    if (memory) memory->root = 0.0;
    if (!(approach > 0.0)) return out;
    out.load = out.conservative_load =
        palmgren_k * NearPower<10, 9>(approach, kNearSpan, e0, e0_power);
    out.stiffness = kPalmgrenExponent * out.load / approach;
    out.potential = out.load * approach * (9.0 / 19.0);
    out.potential_per_film = 1.0;
    return out;
  }
  // delta_s = (A / K)^(9/19): the approach where film and elastic approach are equal.
  const double scale = NearPower<9, 19>(film_coefficient / palmgren_k,
                                        kNearSpan,
                                        memory ? &memory->ratio0 : nullptr,
                                        memory ? &memory->scale0 : nullptr);
  const double x = approach / scale;
  if (-x >= 2.0 * kFilmTaperStart) {
    if (memory) memory->root = 0.0;
    return out;
  }
  double slope;  // d(delta) / d(delta_P)
  const double y = ElasticApproach(x, &slope, memory);
  const double elastic = y * scale;
  const double load = palmgren_k * NearPower<10, 9>(elastic, kNearSpan, e0, e0_power);
  const double stiffness = kPalmgrenExponent * load / elastic / slope;
  out.conservative_load = load / slope;
  out.potential = load * elastic * (9.0 / 19.0);
  // delta_P(delta, A): d(delta_P)/dA = 1 / (Q slope), so dV/dA = Q d(delta_P)/dA = 1 / slope.
  out.potential_per_film = 1.0 / slope;
  double taper = 1.0, taper_slope = 0.0;  // and its derivative in delta
  if (-x > kFilmTaperStart) {
    const double t = (-x - kFilmTaperStart) / kFilmTaperStart;
    taper = 1.0 - t * t * (3.0 - 2.0 * t);
    taper_slope = 6.0 * t * (1.0 - t) / (kFilmTaperStart * scale);
  }
  out.load = load * taper;
  out.stiffness = stiffness * taper + load * taper_slope;
  return out;
}

double FilmReach(double film_coefficient, double palmgren_k) {
  if (!(film_coefficient > 0.0)) return 0.0;
  return 2.0 * kFilmTaperStart * std::pow(film_coefficient / palmgren_k, 9.0 / 19.0);
}

}  // namespace spallkit::sim::contact
