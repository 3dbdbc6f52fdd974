#include "sim/contact/film_lift.h"

#include <algorithm>
#include <cmath>

namespace spallkit::sim::contact {

namespace {

constexpr double kPalmgrenExponent = 10.0 / 9.0;

// delta_s = (A / K)^(9/19): the approach where film and elastic approach are equal.
double FilmScale(double film_coefficient, double palmgren_k) {
  return std::pow(film_coefficient / palmgren_k, 9.0 / 19.0);
}

// The root y > 0 of F(y) = y - y^(-10/9) - x, and F'(y) = 1 + 10/9 y^(-19/9) there. F is
// increasing and concave, so Newton's method from a point left of the root climbs to it
// monotonically; the start is such a point (F(start) <= 0).
double ElasticApproach(double x, double* slope) {
  double y;
  if (x >= 0.0) {
    y = std::max(x, 1.0);  // F(1) = -x, F(x) = -x^(-10/9)
  } else if (x >= -1.0) {
    y = 0.6;  // F(0.6) < -1.16 - x < 0
  } else {    // y^(-10/9) = y - x <= y_max - x with y_max = (-x)^(-9/10)
    y = std::pow(std::pow(-x, -0.9) - x, -0.9);
  }
  double fp = 1.0;
  for (int it = 0; it < 100; ++it) {
    const double ym = std::pow(y, -kPalmgrenExponent);
    fp = 1.0 + kPalmgrenExponent * ym / y;
    const double step = (y - ym - x) / fp;  // <= 0
    y -= step;
    if (!(std::abs(step) > 1e-14 * y)) break;
  }
  *slope = fp;
  return y;
}

}  // namespace

double MartinFilmCoefficient(double viscosity_pa_s,
                             double entrainment_speed,
                             double reduced_radius,
                             double length) {
  return 4.9 * viscosity_pa_s * std::abs(entrainment_speed) * reduced_radius * length;
}

FilmContactLoad FilmLineContact(double approach, double film_coefficient, double palmgren_k) {
  FilmContactLoad out;
  if (!(film_coefficient > 0.0)) {  // Palmgren's law alone
    if (!(approach > 0.0)) return out;
    out.load = out.conservative_load = palmgren_k * std::pow(approach, kPalmgrenExponent);
    out.stiffness = kPalmgrenExponent * out.load / approach;
    out.potential = out.load * approach * (9.0 / 19.0);
    out.potential_per_film = 1.0;
    return out;
  }
  const double scale = FilmScale(film_coefficient, palmgren_k);
  const double x = approach / scale;
  if (-x >= 2.0 * kFilmTaperStart) return out;
  double slope;  // d(delta) / d(delta_P)
  const double y = ElasticApproach(x, &slope);
  const double elastic = y * scale;
  const double load = palmgren_k * std::pow(elastic, kPalmgrenExponent);
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
  return 2.0 * kFilmTaperStart * FilmScale(film_coefficient, palmgren_k);
}

}  // namespace spallkit::sim::contact
