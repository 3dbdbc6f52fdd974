// Unit tests of the contact pieces on hand-built node arrays: friction law, penalty force,
// surfaces from meshes, grid search against brute force, stable step, determinism.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/error.h"
#include "sim/contact/contact_pair.h"
#include "sim/contact/friction.h"
#include "sim/contact/penalty.h"
#include "sim/contact/segment_grid.h"
#include "sim/contact/surface.h"
#include "sim/fe/mesh_primitives.h"

namespace spallkit::sim::contact {
namespace {

fe::NodalState MakeState(const std::vector<double>& x, const std::vector<double>& y, double mass) {
  fe::NodalState s;
  s.Resize(x.size());
  s.x = s.x0 = x;
  s.y = s.y0 = y;
  s.mass.assign(x.size(), mass);
  return s;
}

TEST(FrictionLaw, StaticAtRestDynamicAtHighSlipRate) {
  FrictionLaw law{.static_coefficient = 0.3, .dynamic_coefficient = 0.1, .decay = 5.0};
  EXPECT_DOUBLE_EQ(law.Coefficient(0.0), 0.3);
  EXPECT_NEAR(law.Coefficient(1e3), 0.1, 1e-12);
  EXPECT_NEAR(law.Coefficient(-1e3), 0.1, 1e-12);
  // Halfway at decay * |v| = ln 2.
  EXPECT_NEAR(law.Coefficient(std::log(2.0) / 5.0), 0.2, 1e-12);
  FrictionLaw no_decay{.static_coefficient = 0.3, .dynamic_coefficient = 0.1, .decay = 0.0};
  EXPECT_DOUBLE_EQ(no_decay.Coefficient(10.0), 0.3);
  std::string error;
  EXPECT_FALSE((FrictionLaw{.static_coefficient = -0.1}).IsValid(&error));
  EXPECT_NE(error.find("static"), std::string::npos);
}

TEST(FrictionLaw, ReturnMapSticksBelowCapAndDissipatesSlipWork) {
  const FrictionUpdate stick = ReturnMap(1.0, -0.5, 2.0, 5.0);  // trial 1 + 1 = 2 < 5
  EXPECT_FALSE(stick.sliding);
  EXPECT_DOUBLE_EQ(stick.force, 2.0);
  EXPECT_DOUBLE_EQ(stick.dissipation, 0.0);
  const FrictionUpdate slide = ReturnMap(4.0, -2.0, 2.0, 5.0);  // trial 8, cap 5: slip 1.5
  EXPECT_TRUE(slide.sliding);
  EXPECT_DOUBLE_EQ(slide.force, 5.0);
  EXPECT_DOUBLE_EQ(slide.dissipation, 5.0 * 1.5);
  const FrictionUpdate reverse = ReturnMap(0.0, 3.0, 2.0, 5.0);  // trial -6
  EXPECT_DOUBLE_EQ(reverse.force, -5.0);
}

TEST(PenaltyLaw, NamesRoundTrip) {
  for (PenaltyLaw law :
       {PenaltyLaw::kBulkModulus, PenaltyLaw::kMassTimeStep, PenaltyLaw::kConstant}) {
    PenaltyLaw back;
    ASSERT_TRUE(StringToPenaltyLaw(PenaltyLawToString(law), &back));
    EXPECT_EQ(back, law);
  }
  PenaltyLaw unused;
  EXPECT_FALSE(StringToPenaltyLaw("soft", &unused));
}

// A flat master (body below y = 0, chain walked right to left so the outward normal is +y) and a
// slave node 1 mm below its surface.
TEST(ContactPair, PenaltyForceForKnownPenetration) {
  // nodes: 0 = (1, 0), 1 = (0, 0) master; 2 = slave at (0.25, -1e-3)
  fe::NodalState state = MakeState({1.0, 0.0, 0.25}, {0.0, 0.0, -1e-3}, 1.0);
  ContactPairOptions options;
  options.penalty_law = PenaltyLaw::kConstant;
  options.constant_stiffness = 1e6;
  options.search_margin = 0.5;
  ContactPair pair("test",
                   MakeSurfaceFromChain("slave", {2}, false),
                   MakeSurfaceFromChain("master", {0, 1}, false),
                   options);
  pair.AddForces(state, 0.0, 1e-6);
  // Slave pushed out along +y with k * 1e-3 = 1000 N; master nodes get -1000 N split by
  // xi = 0.75 measured from node 0: node 0 takes 0.25, node 1 takes 0.75.
  EXPECT_NEAR(state.fy[2], 1000.0, 1e-9);
  EXPECT_NEAR(state.fx[2], 0.0, 1e-12);
  EXPECT_NEAR(state.fy[0], -250.0, 1e-9);
  EXPECT_NEAR(state.fy[1], -750.0, 1e-9);
  EXPECT_NEAR(pair.Resultant().normal_y, 1000.0, 1e-9);
  EXPECT_NEAR(pair.Resultant().normal_magnitude_sum, 1000.0, 1e-9);
  EXPECT_EQ(pair.Resultant().active_nodes, 1);
  EXPECT_NEAR(pair.Resultant().max_penetration, 1e-3, 1e-15);
  EXPECT_NEAR(pair.SlaveGaps()[0], -1e-3, 1e-15);
  EXPECT_NEAR(pair.StoredEnergy(), 0.5 * 1e6 * 1e-6, 1e-12);

  // Above the surface: no force, positive gap.
  fe::NodalState apart = MakeState({1.0, 0.0, 0.25}, {0.0, 0.0, 2e-3}, 1.0);
  pair.AddForces(apart, 0.0, 1e-6);
  EXPECT_EQ(apart.fy[2], 0.0);
  EXPECT_NEAR(pair.SlaveGaps()[0], 2e-3, 1e-15);
  EXPECT_EQ(pair.Resultant().active_nodes, 0);
}

TEST(ContactPair, SymmetricPassGivesResultantOnFirstSurface) {
  // Two flats overlapping by 1e-3: top body's bottom edge (walked left to right, normal -y) and
  // bottom body's top edge (walked right to left, normal +y).
  fe::NodalState state = MakeState({0.0, 1.0, 1.0, 0.0}, {-1e-3, -1e-3, 0.0, 0.0}, 1.0);
  ContactPairOptions options;
  options.penalty_law = PenaltyLaw::kConstant;
  options.constant_stiffness = 1e6;
  options.search_margin = 0.5;
  options.symmetric = true;
  ContactPair pair("sym",
                   MakeSurfaceFromChain("top", {0, 1}, false),
                   MakeSurfaceFromChain("bottom", {2, 3}, false),
                   options);
  pair.AddForces(state, 0.0, 1e-6);
  // Each pass: 2 slave nodes at a 1e-3 penetration (corners project onto segment ends).
  EXPECT_EQ(pair.Resultant().active_nodes, 4);
  EXPECT_NEAR(pair.Resultant().normal_y, 4000.0, 1e-6);  // pushes the top body up
  EXPECT_NEAR(state.fy[0] + state.fy[1], 2000.0 + 2000.0, 1e-6);
  EXPECT_NEAR(state.fy[2] + state.fy[3], -4000.0, 1e-6);
}

TEST(ContactSurface, BulkModulusStiffnessFromTheElementBehindTheSegment) {
  fe::RectangleSpec spec;
  spec.width = 2e-3;
  spec.height = 1e-3;
  spec.nx = 2;
  spec.ny = 1;
  const fe::Mesh mesh = fe::MakeRectangle("block", spec);
  const ContactSurface top = MakeSurface(mesh, "block.top", {175e9}, 0.01);
  ASSERT_EQ(top.num_segments(), 2);
  // Element 1e-3 x 1e-3, segment 1e-3: K L^2 / A t = K t.
  for (double k : top.bulk_stiffness) EXPECT_NEAR(k, 175e9 * 0.01, 1e-3);
  EXPECT_NEAR(BulkModulusPenalty(0.1, 175e9, 1e-3, 1e-6, 0.01), 0.1 * 175e9 * 0.01, 1e-3);
  EXPECT_NEAR(BulkModulus(210e9, 0.3), 175e9, 1e-3);
  // Walking against the body (reversed curve) is rejected with the curve named.
  fe::Mesh reversed = mesh;
  auto& nodes = reversed.curves["block.top"].nodes;
  std::reverse(nodes.begin(), nodes.end());
  try {
    MakeSurface(reversed, "block.top", {175e9}, 0.01);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("block.top"), std::string::npos);
  }
  EXPECT_THROW(MakeSurface(mesh, "block.nothing", {175e9}, 0.01), InputError);
}

// Random wavy closed chain: the grid must give the same closest segment as brute force for every
// point within margin / 2, and its candidates must contain every segment within the margin.
TEST(SegmentGrid, FindsTheSamePairsAsBruteForceOnRandomMeshes) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    const int n = 200 + 150 * trial;
    std::vector<double> x(n), y(n);
    std::vector<int> chain(n);
    for (int i = 0; i < n; ++i) {
      const double th = 2 * M_PI * i / n;
      const double r = 0.01 * (1.0 + 0.1 * std::sin(7 * th) + 0.02 * u(rng));
      x[i] = r * std::cos(th);
      y[i] = r * std::sin(th);
      chain[i] = i;
    }
    const ContactSurface surface = MakeSurfaceFromChain("wavy", chain, true);
    const double margin = surface.MeanSegmentLength(x.data(), y.data());
    SegmentGrid grid;
    grid.Build(surface, x.data(), y.data(), margin);
    std::vector<int> all(surface.num_segments());
    for (int s = 0; s < surface.num_segments(); ++s) all[s] = s;
    int compared = 0;
    for (int q = 0; q < 4000; ++q) {
      const double px = 0.0115 * u(rng), py = 0.0115 * u(rng);
      const Projection brute = ProjectOntoSurface(surface, x.data(), y.data(), px, py, all);
      if (brute.distance > 0.5 * margin) continue;
      const Projection fast =
          ProjectOntoSurface(surface, x.data(), y.data(), px, py, grid.Candidates(px, py));
      ASSERT_EQ(fast.segment, brute.segment) << "trial " << trial << " point " << q;
      EXPECT_EQ(fast.gap, brute.gap);
      ++compared;
    }
    EXPECT_GT(compared, 100);
    // The grid stays small: at most a few entries per segment.
    EXPECT_LT(grid.num_entries(), 12 * surface.num_segments());
  }
}

// One slave node with mass m held against a fixed master (massless nodes = fixed) by a constant
// force: linear oscillator with omega^2 = k / m. StableTimeStep at safety 1 is 2 / omega, and the
// central-difference run is bounded just below it and grows just above it.
double RunOscillator(double dt_factor, double* dt_stable) {
  ContactPairOptions options;
  options.penalty_law = PenaltyLaw::kConstant;
  options.constant_stiffness = 1e6;
  options.search_margin = 1.0;
  options.stable_step_safety = 1.0;
  ContactPair pair("osc",
                   MakeSurfaceFromChain("s", {2}, false),
                   MakeSurfaceFromChain("m", {0, 1}, false),
                   options);
  fe::NodalState st = MakeState({1.0, 0.0, 0.5}, {0.0, 0.0, -5e-4 + 1e-6}, 0.0);
  st.mass[2] = 1e-2;
  *dt_stable = pair.StableTimeStep(st);
  const double dt = dt_factor * *dt_stable;
  double peak = 0.0;
  for (int n = 0; n < 4000; ++n) {
    st.fx.assign(3, 0.0);
    st.fy.assign(3, 0.0);
    st.fy[2] = -500.0;  // pushes into the master: equilibrium penetration 500 / 1e6 = 5e-4
    pair.AddForces(st, n * dt, dt);
    st.vy[2] += dt * st.fy[2] / st.mass[2];
    st.y[2] += dt * st.vy[2];
    peak = std::max(peak, std::abs(st.y[2] + 5e-4));
  }
  return peak;
}

TEST(ContactPair, StableTimeStepIsTheOscillatorLimit) {
  double dt_stable = 0.0;
  const double below = RunOscillator(0.98, &dt_stable);
  EXPECT_NEAR(dt_stable, 2.0 / std::sqrt(1e6 / 1e-2), 1e-15);
  const double above = RunOscillator(1.02, &dt_stable);
  EXPECT_LT(below, 1e-4);        // stays near the initial 5e-5 offset
  EXPECT_GT(above, 10 * below);  // grows until it leaves contact
}

TEST(ContactPair, MassTimeStepLawCannotDestabilise) {
  ContactPairOptions options;
  options.penalty_law = PenaltyLaw::kMassTimeStep;
  options.penalty_scale = 0.1;
  options.search_margin = 1.0;
  ContactPair pair("soft",
                   MakeSurfaceFromChain("s", {2}, false),
                   MakeSurfaceFromChain("m", {0, 1}, false),
                   options);
  fe::NodalState st = MakeState({1.0, 0.0, 0.5}, {0.0, 0.0, -1e-4}, 2e-3);
  EXPECT_TRUE(std::isinf(pair.StableTimeStep(st)));  // adapts to the first step
  pair.AddForces(st, 0.0, 1e-7);
  // k = 0.1 * 2e-3 / 1e-14 = 2e10; F = k * 1e-4.
  EXPECT_NEAR(st.fy[2], 0.1 * 2e-3 / 1e-14 * 1e-4, 1e-3);
  EXPECT_NEAR(pair.StableTimeStep(st), 0.9 * 2.0 * 1e-7 / std::sqrt(0.2), 1e-18);
}

TEST(ContactPair, NormalDampingDissipatesWhileApproaching) {
  ContactPairOptions options;
  options.penalty_law = PenaltyLaw::kConstant;
  options.constant_stiffness = 1e6;
  options.search_margin = 1.0;
  options.normal_damping_ratio = 0.1;
  ContactPair pair("damp",
                   MakeSurfaceFromChain("s", {2}, false),
                   MakeSurfaceFromChain("m", {0, 1}, false),
                   options);
  fe::NodalState st = MakeState({1.0, 0.0, 0.5}, {0.0, 0.0, -1e-4}, 0.0);
  st.mass[2] = 1e-2;
  st.vy[2] = -1.0;
  pair.AddForces(st, 0.0, 1e-6);
  const double c = 2 * 0.1 * std::sqrt(1e6 * 1e-2);
  EXPECT_NEAR(st.fy[2], 1e6 * 1e-4 + c * 1.0, 1e-9);
  EXPECT_NEAR(pair.DampingDissipation(), c * 1.0 * 1e-6, 1e-15);
}

// A node slid along a fixed flat at constant speed under a constant normal force: the friction
// force settles at mu_d N, dissipation equals mu_d N times the distance slid (after the stick
// spring has loaded), and the resultant points against the motion.
TEST(ContactPair, SlidingNodeCarriesDynamicFriction) {
  ContactPairOptions options;
  options.penalty_law = PenaltyLaw::kConstant;
  options.constant_stiffness = 1e6;
  options.search_margin = 1.0;
  options.friction = {.static_coefficient = 0.4, .dynamic_coefficient = 0.2, .decay = 100.0};
  ContactPair pair("slide",
                   MakeSurfaceFromChain("s", {2}, false),
                   MakeSurfaceFromChain("m", {0, 1}, false),
                   options);
  fe::NodalState st = MakeState({1.0, 0.0, 0.2}, {0.0, 0.0, -1e-4}, 0.0);
  st.vx[2] = 1.0;  // 1 m/s: mu = 0.2 + 0.2 exp(-100) = 0.2
  const double dt = 1e-6;
  double ft = 0.0;
  for (int n = 0; n < 200; ++n) {
    st.fx.assign(3, 0.0);
    st.fy.assign(3, 0.0);
    pair.AddForces(st, n * dt, dt);
    ft = st.fx[2];
    st.x[2] += dt * st.vx[2];
  }
  const double normal = 1e6 * 1e-4;
  EXPECT_NEAR(ft, -0.2 * normal, 1e-9);
  EXPECT_NEAR(pair.Resultant().tangential_x, -0.2 * normal, 1e-9);
  // Stick spring k_t = k loads over x_load = 0.2*100/1e6 = 2e-5 m (20 steps), then all the slip
  // dissipates: work in = F (slid - x_load / 2) = stored + dissipated.
  const double slid = 200 * dt * 1.0, x_load = 0.2 * normal / 1e6;
  const double stored_tangential = pair.StoredEnergy() - 0.5 * 1e6 * 1e-4 * 1e-4;
  EXPECT_NEAR(stored_tangential, 0.5 * (0.2 * normal) * x_load, 1e-12);
  EXPECT_NEAR(pair.FrictionDissipation() + stored_tangential,
              0.2 * normal * (slid - 0.5 * x_load),
              1e-3 * 0.2 * normal * slid);
}

TEST(ContactPair, SaveAndLoadStateResumesIdentically) {
  ContactPairOptions options;
  options.penalty_law = PenaltyLaw::kConstant;
  options.constant_stiffness = 1e6;
  options.search_margin = 1.0;
  options.friction = {.static_coefficient = 0.4, .dynamic_coefficient = 0.2, .decay = 100.0};
  auto make = [&] {
    return ContactPair("ck",
                       MakeSurfaceFromChain("s", {2}, false),
                       MakeSurfaceFromChain("m", {0, 1}, false),
                       options);
  };
  auto step = [](ContactPair& pair, fe::NodalState& st, int n) {
    for (int i = 0; i < n; ++i) {
      st.fx.assign(3, 0.0);
      st.fy.assign(3, 0.0);
      pair.AddForces(st, 0.0, 1e-6);
      st.x[2] += 1e-6 * st.vx[2];
    }
  };
  ContactPair a = make();
  fe::NodalState sa = MakeState({1.0, 0.0, 0.2}, {0.0, 0.0, -1e-4}, 0.0);
  sa.vx[2] = 0.01;
  step(a, sa, 5);
  ContactPair b = make();
  fe::NodalState sb = sa;
  b.LoadState(a.SaveState());
  step(a, sa, 5);
  step(b, sb, 5);
  EXPECT_EQ(sa.fx[2], sb.fx[2]);
  EXPECT_EQ(a.FrictionDissipation(), b.FrictionDissipation());
  EXPECT_EQ(a.StoredEnergy(), b.StoredEnergy());
  EXPECT_THROW(b.LoadState("x"), InputError);
}

TEST(ContactPair, ParallelResultsAreBitIdentical) {
  // A wavy slave ring inside an overlapping master ring: many nodes in contact.
  const int n = 3000;
  std::vector<double> x(2 * n), y(2 * n);
  std::vector<int> slave(n), master(n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const double th = 2 * M_PI * i / n;
    const double rs = 0.0100 + 2e-6 * u(rng), rm = 0.01 - 1e-6;
    x[i] = rs * std::cos(th);
    y[i] = rs * std::sin(th);
    // Master: a bore (hole), walked clockwise so the body is outside.
    x[n + i] = rm * std::cos(-th + 0.3 / n);
    y[n + i] = rm * std::sin(-th + 0.3 / n);
    slave[i] = i;
    master[i] = n + i;
  }
  std::vector<double> vx(2 * n, 0.0);
  for (int i = 0; i < n; ++i) vx[i] = 0.1 * u(rng);
  ContactPairOptions options;
  options.penalty_law = PenaltyLaw::kConstant;
  options.constant_stiffness = 1e7;
  options.parallel_min_nodes = 1;
  options.friction = {.static_coefficient = 0.1, .dynamic_coefficient = 0.05, .decay = 1.0};
  std::vector<std::vector<double>> results;
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    ContactPair pair("par",
                     MakeSurfaceFromChain("s", slave, true),
                     MakeSurfaceFromChain("m", master, true),
                     options);
    fe::NodalState st = MakeState(x, y, 1e-3);
    st.vx = vx;
    for (int step = 0; step < 3; ++step) pair.AddForces(st, 0.0, 1e-7);
    std::vector<double> r = st.fx;
    r.insert(r.end(), st.fy.begin(), st.fy.end());
    r.push_back(pair.StoredEnergy());
    r.push_back(pair.FrictionDissipation());
    r.push_back(pair.Resultant().normal_magnitude_sum);
    EXPECT_GT(pair.Resultant().active_nodes, n / 4);
    results.push_back(r);
  }
  ASSERT_EQ(results[0].size(), results[1].size());
  for (size_t i = 0; i < results[0].size(); ++i) ASSERT_EQ(results[0][i], results[1][i]) << i;
}

TEST(ContactPair, FarApartSurfacesAreRejectedWithoutSearch) {
  ContactPairOptions options;
  options.penalty_law = PenaltyLaw::kConstant;
  options.constant_stiffness = 1e6;
  ContactPair pair("far",
                   MakeSurfaceFromChain("s", {2, 3}, false),
                   MakeSurfaceFromChain("m", {0, 1}, false),
                   options);
  fe::NodalState st = MakeState({1.0, 0.0, 5.0, 6.0}, {0.0, 0.0, 5.0, 5.0}, 1.0);
  pair.AddForces(st, 0.0, 1e-6);
  EXPECT_EQ(pair.num_rebuilds(), 0);
  EXPECT_TRUE(std::isinf(pair.SlaveGaps()[0]));
}

TEST(ContactPairOptions, RejectsBadValuesWithAMessage) {
  ContactPairOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.penalty_scale = 0.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("penalty_scale"), std::string::npos);
  options = ContactPairOptions{};
  options.penalty_law = PenaltyLaw::kBulkModulus;
  EXPECT_THROW(ContactPair("x",
                           MakeSurfaceFromChain("s", {0, 1}, false),
                           MakeSurfaceFromChain("m", {2, 3}, false),
                           options),
               InputError);
}

}  // namespace
}  // namespace spallkit::sim::contact
