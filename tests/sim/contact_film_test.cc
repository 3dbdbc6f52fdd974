// The lubricated line contact's normal law (sim/contact/film_lift.h) against its two limits:
// Palmgren's elastic law under load and Martin's rigid-isoviscous film at light load, and its
// consistency (stiffness = dQ/d delta, conservative load = dV/d delta, no jump anywhere).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "sim/contact/film_lift.h"
#include "sim/quasistatic/harris_jones.h"

namespace spallkit::sim::contact {
namespace {

// The N205EM's inner-race contact at 1200 rpm with an ISO VG 68 oil: roller 6.5 mm, raceway
// radius 16 mm, entrainment (125.7 - 52.2 rad/s) 16 mm = 1.18 m/s, viscosity 0.05 Pa s, the
// scene's length 9 mm.
constexpr double kViscosity = 0.05, kEntrainment = 1.18, kLength = 9e-3;
constexpr double kReducedRadius = 3.25e-3 * 16e-3 / (3.25e-3 + 16e-3);

double K() { return PalmgrenContactStiffness(kLength); }
double A() { return MartinFilmCoefficient(kViscosity, kEntrainment, kReducedRadius, kLength); }
// delta_s = (A / K)^(9/19), where the film and the elastic approach are equal.
double Scale() { return std::pow(A() / K(), 9.0 / 19.0); }

TEST(FilmLiftTest, ScaleOfTheN205emInnerContactIsAFractionOfAMicrometre) {
  EXPECT_GT(Scale(), 0.05e-6);
  EXPECT_LT(Scale(), 0.5e-6);
  // At zero approach the two terms are equal: delta_P = delta_s, Q = K delta_s^(10/9).
  const FilmContactLoad f = FilmLineContact(0.0, A(), K());
  EXPECT_NEAR(f.load / (K() * std::pow(Scale(), 10.0 / 9.0)), 1.0, 1e-12);
}

TEST(FilmLiftTest, UnderLoadItIsPalmgrensLaw) {
  for (double load : {500.0, 3000.0}) {              // the load zone's rollers
    const double delta = std::pow(load / K(), 0.9);  // Palmgren's approach for that load
    const FilmContactLoad f = FilmLineContact(delta, A(), K());
    // The film adds A / Q to the approach, i.e. about (10/9) K delta^(1/9) A / Q of load, and
    // its compliance makes about (10/9) (delta_s / delta_P)^(19/9) of it the film's.
    EXPECT_GT(f.load, load);
    EXPECT_LT(f.load / load - 1.0, load > 1000 ? 1e-3 : 2e-2) << load;
    EXPECT_GT(f.conservative_load / f.load, load > 1000 ? 0.998 : 0.98) << load;
  }
}

// Martin (1916): a rigid cylinder on a plane carries w' = 4.9 eta u R / h per unit length at
// film thickness h. The law's film thickness at load Q (the gap plus the elastic approach
// (Q / K)^(9/10)) is that; at light load it is most of the gap.
TEST(FilmLiftTest, AtLightLoadTheFilmIsMartins) {
  for (double load : {2.0, 5.0, 10.0, 20.0}) {
    const double martin = 4.9 * kViscosity * kEntrainment * kReducedRadius / (load / kLength);
    ASSERT_LT(martin, kFilmTaperStart * Scale());  // before the taper
    double lo = -martin, hi = 0.0;                 // Q(lo) < load < Q(hi)
    ASSERT_LT(FilmLineContact(lo, A(), K()).load, load);
    ASSERT_GT(FilmLineContact(hi, A(), K()).load, load);
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (FilmLineContact(mid, A(), K()).load < load ? lo : hi) = mid;
    }
    const double gap = -0.5 * (lo + hi);
    EXPECT_NEAR((gap + std::pow(load / K(), 0.9)) / martin, 1.0, 1e-9) << load;
    EXPECT_GT(gap / martin, load <= 10.0 ? 0.85 : 0.7) << load;
  }
  // There the film, not the elastic law, carries the load.
  const FilmContactLoad f = FilmLineContact(-1e-6, A(), K());
  EXPECT_LT(f.conservative_load / f.load, 0.05);
}

TEST(FilmLiftTest, LoadIsSmoothAndItsStiffnessAndPotentialAreConsistent) {
  const double s = Scale();
  double previous = 0.0;
  for (double x = -2.0 * kFilmTaperStart + 0.005; x <= 60.0; x += 0.01) {
    const double d = x * s, h = 1e-6 * s;
    const FilmContactLoad f = FilmLineContact(d, A(), K());
    const FilmContactLoad lo = FilmLineContact(d - h, A(), K());
    const FilmContactLoad hi = FilmLineContact(d + h, A(), K());
    ASSERT_GE(f.load, previous) << x;  // increasing, and by what its stiffness says: no step
    ASSERT_LE(f.load - previous, 1.05 * f.stiffness * 0.01 * s + 1e-12) << x;
    const double tol = 1e-5 * f.stiffness + 1e-6;
    ASSERT_NEAR((hi.load - lo.load) / (2 * h), f.stiffness, tol) << x;
    ASSERT_NEAR((hi.potential - lo.potential) / (2 * h),
                f.conservative_load,
                1e-5 * f.conservative_load + 1e-9)
        << x;
    previous = f.load;
  }
  EXPECT_EQ(FilmLineContact(-FilmReach(A(), K()), A(), K()).load, 0.0);
  EXPECT_GT(FilmLineContact(-0.99 * FilmReach(A(), K()), A(), K()).load, 0.0);
}

// A contact point's memory (the last root and the powers' expansion points) changes nothing but
// rounding along a history like a contact's: slow drifts of the approach and the entrainment
// (a loaded roller), jumps (a spall edge, the load zone's edges) and rattles across the gap.
TEST(FilmLiftTest, MemoryOfTheLastStepChangesNothingButRounding) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> step(0.0, 1.0);
  FilmContactMemory memory;
  double x = 5.0, a = A(), worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double size = i % 10000 == 0 ? 20.0 : (i % 50 == 0 ? 2.0 : 0.01);
    x = std::clamp(x + size * step(rng), -2.0 * kFilmTaperStart - 5.0, 500.0);
    a = std::clamp(a * std::exp(1e-3 * step(rng)), 0.2 * A(), 5.0 * A());
    const double d = x * std::pow(a / K(), 9.0 / 19.0);
    const FilmContactLoad exact = FilmLineContact(d, a, K());
    const FilmContactLoad near = FilmLineContact(d, a, K(), &memory);
    auto rel = [](double u, double v) { return std::abs(u - v) / std::max(std::abs(v), 1e-300); };
    if (exact.load == 0.0) {
      ASSERT_EQ(near.load, 0.0) << i;
      continue;
    }
    worst = std::max({worst,
                      rel(near.load, exact.load),
                      rel(near.stiffness, exact.stiffness),
                      rel(near.conservative_load, exact.conservative_load),
                      rel(near.potential, exact.potential)});
  }
  std::printf("largest relative difference %.2g\n", worst);
  EXPECT_LT(worst, 1e-9);
}

TEST(FilmLiftTest, WithoutAFilmItIsPalmgrensLawAlone) {
  EXPECT_EQ(FilmLineContact(-1e-9, 0.0, K()).load, 0.0);
  EXPECT_EQ(FilmLineContact(0.0, 0.0, K()).load, 0.0);
  const FilmContactLoad f = FilmLineContact(1e-5, 0.0, K());
  EXPECT_DOUBLE_EQ(f.load, K() * std::pow(1e-5, 10.0 / 9.0));
  EXPECT_DOUBLE_EQ(f.potential, 9.0 / 19.0 * f.load * 1e-5);
  EXPECT_EQ(FilmReach(0.0, K()), 0.0);
  EXPECT_EQ(MartinFilmCoefficient(kViscosity, 0.0, kReducedRadius, kLength), 0.0);
}

}  // namespace
}  // namespace spallkit::sim::contact
