#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "sim/fe/mesh_primitives.h"
#include "sim/fe/quad_elements.h"

namespace spallkit::sim::fe {
namespace {

Mesh OneQuad(
    double x1, double y1, double x2, double y2, double x3, double y3, double x4, double y4) {
  Mesh m;
  m.x = {x1, x2, x3, x4};
  m.y = {y1, y2, y3, y4};
  m.quads = {{0, 1, 2, 3}};
  m.element_part = {0};
  m.part_names = {"q"};
  return m;
}

NodalState StateOf(const Mesh& m, const QuadElements& el) {
  NodalState s;
  s.Resize(m.num_nodes());
  s.x0 = s.x = m.x;
  s.y0 = s.y = m.y;
  el.AddLumpedMass(&s);
  return s;
}

TEST(QuadElements, LumpedMassIsRhoAtOverFour) {
  const Mesh m = OneQuad(0, 0, 2e-3, 0, 2.5e-3, 1e-3, 0, 1e-3);
  Section sec;
  sec.thickness = 0.02;
  QuadElements el(m, {sec});
  const NodalState s = StateOf(m, el);
  const double area = 0.5 * (2e-3 + 2.5e-3) * 1e-3;
  for (double mi : s.mass) EXPECT_NEAR(mi, 7850 * 0.02 * area / 4, 1e-15);
}

TEST(QuadElements, StableStepUsesLongestSideOrDiagonal) {
  // Flat trapezoid: area / longest diagonal would overestimate the step (a known pitfall).
  const Mesh m = OneQuad(0, 0, 1, 0, 0.9, 0.1, 0.1, 0.1);
  Section sec;
  QuadElements el(m, {sec});
  NodalState s = StateOf(m, el);
  const double area = 0.5 * (1.0 + 0.8) * 0.1;
  const double lmax = std::max(1.0, std::hypot(0.9, 0.1));  // bottom side vs diagonals
  EXPECT_NEAR(el.ComputeCornerForces(s, 0.0, 1), area / lmax / sec.WaveSpeed(), 1e-15);
  // Square: L_e = h / sqrt(2) (200 um -> 21 ns with TSSFAC 0.9, plane strain).
  const Mesh sq = OneQuad(0, 0, 200e-6, 0, 200e-6, 200e-6, 0, 200e-6);
  QuadElements el2(sq, {sec});
  NodalState s2 = StateOf(sq, el2);
  EXPECT_NEAR(0.9 * el2.ComputeCornerForces(s2, 0.0, 1), 21.2e-9, 0.1e-9);
  EXPECT_NEAR(sec.WaveSpeed(), 6001.0, 1.0);
}

TEST(QuadElements, RigidSpinGivesNoStressAndPositiveOmegaRotatesStress) {
  // Unit square with initial uniaxial stress; one step of rigid CCW spin w*h = 0.2 rad:
  // Hughes-Winget rotates the stress by alpha = 2 atan(0.1) exactly, adds no strain.
  const Mesh m = OneQuad(-0.5, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5, 0.5);
  Section sec;
  QuadElements el(m, {sec});
  NodalState s = StateOf(m, el);
  // First load the element: stretch in x for one step (dt = 1e-6 s, v = +-0.5 m/s).
  const double h = 1e-6;
  for (int i = 0; i < 4; ++i) s.vx[i] = 1.0 * s.x[i], s.vy[i] = 0.0;
  for (int i = 0; i < 4; ++i) s.x[i] += h * s.vx[i];  // positions at n, v at n - 1/2
  el.ComputeCornerForces(s, h, 1);
  const double sxx0 = el.sxx(0), syy0 = el.syy(0);
  EXPECT_GT(sxx0, 0.0);
  EXPECT_NEAR(el.sxy(0), 0.0, 1e-9 * sxx0);
  // Now a rigid rotation step by angle theta: chord velocity (x^{n+1} - x^n)/h.
  const double theta = 0.2;
  NodalState r = s;
  for (int i = 0; i < 4; ++i) {
    const double xn = s.x[i], yn = s.y[i];
    const double xr = std::cos(theta) * xn - std::sin(theta) * yn,
                 yr = std::sin(theta) * xn + std::cos(theta) * yn;
    r.vx[i] = (xr - xn) / h, r.vy[i] = (yr - yn) / h;
    r.x[i] = xr, r.y[i] = yr;
  }
  el.ComputeCornerForces(r, h, 1);
  // Rotated uniaxial stress: sxy = (sxx0 - syy0) sin(theta) cos(theta) (CCW: positive).
  const double c = std::cos(theta), sn = std::sin(theta);
  EXPECT_NEAR(el.sxx(0), sxx0 * c * c + syy0 * sn * sn, 1e-9 * sxx0);
  EXPECT_NEAR(el.syy(0), sxx0 * sn * sn + syy0 * c * c, 1e-9 * sxx0);
  EXPECT_NEAR(el.sxy(0), (sxx0 - syy0) * sn * c, 1e-9 * sxx0);
}

TEST(QuadElements, HourglassResistsBendingModeButNotLinearFields) {
  const Mesh m = OneQuad(0, 0, 1e-3, 0, 1.2e-3, 0.9e-3, -0.1e-3, 1.1e-3);  // distorted
  Section sec;
  QuadElements el(m, {sec});
  NodalState s = StateOf(m, el);
  // Linear velocity field: no hourglass energy.
  for (int i = 0; i < 4; ++i)
    s.vx[i] = 3.0 * s.x[i] - 2.0 * s.y[i] + 1.0, s.vy[i] = 0.5 * s.x[i] + 4.0 * s.y[i];
  el.ComputeCornerForces(s, 1e-8, 1);
  EXPECT_NEAR(el.HourglassEnergy(), 0.0, 1e-25);
  // Hourglass pattern: resisted.
  QuadElements el2(m, {sec});
  NodalState s2 = StateOf(m, el2);
  const double hg[4] = {1, -1, 1, -1};
  for (int i = 0; i < 4; ++i) s2.vx[i] = 0.01 * hg[i];
  el2.ComputeCornerForces(s2, 1e-8, 1);
  el2.ComputeCornerForces(s2, 1e-8, 1);
  EXPECT_GT(el2.HourglassEnergy(), 0.0);
  el2.GatherForces(&s2, 1);
  // Forces oppose the hourglass velocity and sum to zero.
  double power = 0, sx = 0;
  for (int i = 0; i < 4; ++i) power += s2.fx[i] * s2.vx[i], sx += s2.fx[i];
  EXPECT_LT(power, 0.0);
  EXPECT_NEAR(sx, 0.0, 1e-12 * std::abs(s2.fx[0]));
}

TEST(QuadElements, InvertedElementThrows) {
  const Mesh m = OneQuad(0, 0, 1, 0, 1, 1, 0, 1);
  Section sec;
  QuadElements el(m, {sec});
  NodalState s = StateOf(m, el);
  std::swap(s.x[1], s.x[3]);
  std::swap(s.y[1], s.y[3]);
  EXPECT_THROW(el.ComputeCornerForces(s, 0.0, 1), NumericalError);
}

TEST(QuadElements, SectionValidation) {
  Section sec;
  sec.material.poisson_ratio = 0.5;
  std::string err;
  EXPECT_FALSE(sec.IsValid(&err));
  EXPECT_NE(err.find("poisson_ratio"), std::string::npos);
  const Mesh m = OneQuad(0, 0, 1, 0, 1, 1, 0, 1);
  EXPECT_THROW(QuadElements(m, {sec}), InputError);
  EXPECT_THROW(QuadElements(m, {}), InputError);
}

}  // namespace
}  // namespace spallkit::sim::fe
