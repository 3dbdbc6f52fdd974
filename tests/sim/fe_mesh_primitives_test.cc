#include <gtest/gtest.h>

#include <cmath>

#include "core/constants.h"
#include "core/error.h"
#include "sim/fe/mesh_primitives.h"

namespace spallkit::sim::fe {
namespace {

double TotalArea(const Mesh& m) {
  double a = 0;
  for (int e = 0; e < m.num_elements(); ++e) a += QuadArea(m, e);
  return a;
}

// Signed area enclosed by a closed curve (shoelace): > 0 counter-clockwise.
double CurveArea(const Mesh& m, const BoundaryCurve& c) {
  double a = 0;
  const size_t n = c.nodes.size();
  for (size_t k = 0; k < n; ++k) {
    const int i = c.nodes[k], j = c.nodes[(k + 1) % n];
    a += m.x[i] * m.y[j] - m.x[j] * m.y[i];
  }
  return 0.5 * a;
}

TEST(MeshPrimitives, RectangleAreaCurvesAndGrading) {
  RectangleSpec s;
  s.x0 = 1.0;
  s.y0 = -2.0;
  s.width = 3.0;
  s.height = 2.0;
  s.nx = 6;
  s.ny = 5;
  s.grade_edge = GradeEdge::kTop;
  s.grade_ratio = 4.0;
  const Mesh m = MakeRectangle("blk", s);
  ValidateMesh(m);
  EXPECT_EQ(m.num_nodes(), 7 * 6);
  EXPECT_EQ(m.num_elements(), 30);
  EXPECT_NEAR(TotalArea(m), 6.0, 1e-12);
  EXPECT_NEAR(CurveArea(m, m.curves.at("blk.outer")), 6.0, 1e-12);
  EXPECT_EQ(m.node_sets.at("blk.top").size(), 7u);
  // Top row is 4x finer than the bottom row.
  const double h_bottom = m.y[7] - m.y[0];
  const double h_top = m.y[5 * 7] - m.y[4 * 7];
  EXPECT_NEAR(h_bottom / h_top, 4.0, 1e-12);
  // Bottom edge curve walks +x: outward normal (b - a) rotated by -90 deg points to -y.
  const auto& b = m.curves.at("blk.bottom").nodes;
  EXPECT_GT(m.x[b[1]], m.x[b[0]]);
  for (int id : m.node_sets.at("blk.top")) EXPECT_DOUBLE_EQ(m.y[id], 0.0);
}

TEST(MeshPrimitives, AnnulusAreaAndOrientation) {
  AnnulusSpec s;
  s.inner_radius = 0.03;
  s.outer_radius = 0.04;
  s.n_theta = 60;
  s.n_radial = 3;
  s.radial_ratio = 0.5;
  const Mesh m = MakeAnnulus("ring", s);
  ValidateMesh(m);
  const double poly = 0.5 * s.n_theta * std::sin(2 * kPi / s.n_theta);
  EXPECT_NEAR(TotalArea(m), poly * (0.04 * 0.04 - 0.03 * 0.03), 1e-15);
  EXPECT_NEAR(CurveArea(m, m.curves.at("ring.outer")), poly * 0.04 * 0.04, 1e-15);
  EXPECT_NEAR(CurveArea(m, m.curves.at("ring.inner")), -poly * 0.03 * 0.03, 1e-15);  // clockwise
  for (int id : m.node_sets.at("ring.inner"))
    EXPECT_NEAR(std::hypot(m.x[id], m.y[id]), 0.03, 1e-15);
  // Outermost layer half as thick as the innermost.
  const double t_in = std::hypot(m.x[60], m.y[60]) - 0.03;
  const double t_out = 0.04 - std::hypot(m.x[120], m.y[120]);
  EXPECT_NEAR(t_out / t_in, 0.5, 1e-12);
}

TEST(MeshPrimitives, DiscRimIsUniformAndAreaMatchesPolygon) {
  DiscSpec s;
  s.cx = 0.1;
  s.cy = 0.2;
  s.radius = 0.005;
  s.n_core = 6;
  s.n_radial = 5;
  s.theta0 = 0.3;
  s.radial_ratio = 0.5;
  const Mesh m = MakeDisc("roller", s);
  ValidateMesh(m);
  const auto& rim = m.curves.at("roller.outer");
  ASSERT_EQ(rim.nodes.size(), 24u);
  const double poly = 0.5 * 24 * std::sin(2 * kPi / 24) * s.radius * s.radius;
  EXPECT_NEAR(TotalArea(m), poly, 1e-16);
  EXPECT_NEAR(CurveArea(m, rim), poly, 1e-16);
  for (size_t k = 0; k < rim.nodes.size(); ++k) {
    const int id = rim.nodes[k];
    EXPECT_NEAR(std::hypot(m.x[id] - s.cx, m.y[id] - s.cy), s.radius, 1e-15);
    double th = std::atan2(m.y[id] - s.cy, m.x[id] - s.cx) - (s.theta0 + 2 * kPi * k / 24);
    th = std::remainder(th, 2 * kPi);
    EXPECT_NEAR(th, 0.0, 1e-12) << k;
  }
  const int c = m.node_sets.at("roller.center")[0];
  EXPECT_LT(std::hypot(m.x[c] - s.cx, m.y[c] - s.cy), 1e-12);  // n_core even: exact centre node
}

TEST(MeshPrimitives, MergeRenumbersAndRejectsDuplicates) {
  const Mesh a = MakeRectangle("a", RectangleSpec{});
  AnnulusSpec as;
  const Mesh b = MakeAnnulus("b", as);
  const Mesh m = MergeMeshes({a, b});
  ValidateMesh(m);
  EXPECT_EQ(m.num_nodes(), a.num_nodes() + b.num_nodes());
  EXPECT_EQ(m.num_parts(), 2);
  EXPECT_EQ(m.element_part.back(), 1);
  EXPECT_EQ(m.curves.at("b.outer").nodes[0], a.num_nodes() + b.curves.at("b.outer").nodes[0]);
  EXPECT_THROW(MergeMeshes({a, a}), InputError);
}

TEST(MeshPrimitives, ReorderKeepsGeometryAndSets) {
  AnnulusSpec as;
  as.n_theta = 40;
  as.n_radial = 4;
  DiscSpec ds;
  ds.cx = 3.0;
  Mesh m = MergeMeshes({MakeAnnulus("ring", as), MakeDisc("disc", ds)});
  const Mesh before = m;
  const std::vector<int> new_id = ReorderForLocality(&m);
  ValidateMesh(m);
  EXPECT_NEAR(TotalArea(m), TotalArea(before), 1e-12);
  for (int i = 0; i < before.num_nodes(); ++i) {
    EXPECT_EQ(m.x[new_id[i]], before.x[i]);
    EXPECT_EQ(m.y[new_id[i]], before.y[i]);
  }
  const auto& c0 = before.curves.at("disc.outer").nodes;
  const auto& c1 = m.curves.at("disc.outer").nodes;
  for (size_t k = 0; k < c0.size(); ++k) EXPECT_EQ(c1[k], new_id[c0[k]]);
  // Bandwidth shrinks compared with the generator order.
  auto bandwidth = [](const Mesh& mm) {
    int bw = 0;
    for (const auto& q : mm.quads)
      for (int a : q)
        for (int b : q) bw = std::max(bw, std::abs(a - b));
    return bw;
  };
  EXPECT_LE(bandwidth(m), bandwidth(before));
}

TEST(MeshPrimitives, InvalidInputThrows) {
  RectangleSpec s;
  s.nx = 0;
  EXPECT_THROW(MakeRectangle("x", s), InputError);
  Mesh m = MakeRectangle("x", RectangleSpec{});
  std::swap(m.quads[0][1], m.quads[0][3]);  // clockwise
  EXPECT_THROW(ValidateMesh(m), InputError);
}

}  // namespace
}  // namespace spallkit::sim::fe
