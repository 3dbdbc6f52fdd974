#include "sim/fe/quad_elements.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "core/multiversion.h"
#include "sim/fe/mesh_primitives.h"

namespace spallkit::sim::fe {
namespace {

// By value (std::max returns a reference, which GCC vectorises as a select of addresses plus a
// gather from the stack).
inline double Max(double a, double b) { return a > b ? a : b; }
inline double Min(double a, double b) { return a < b ? a : b; }

}  // namespace

QuadElements::QuadElements(const Mesh& mesh, std::vector<Section> sections)
    : sections_(std::move(sections)) {
  ValidateMesh(mesh);
  if (static_cast<int>(sections_.size()) != mesh.num_parts()) {
    std::ostringstream os;
    os << "elements: got " << sections_.size() << " sections for " << mesh.num_parts()
       << " mesh parts";
    throw InputError(os.str());
  }
  for (int p = 0; p < num_parts(); ++p) {
    std::string err;
    if (!sections_[p].IsValid(&err)) throw InputError(err + " (part '" + mesh.part_names[p] + "')");
  }
  num_nodes_ = mesh.num_nodes();
  const int ne = mesh.num_elements();
  part_ = mesh.element_part;
  n1_.resize(ne), n2_.resize(ne), n3_.resize(ne), n4_.resize(ne);
  for (int e = 0; e < ne; ++e) {
    n1_[e] = mesh.quads[e][0], n2_[e] = mesh.quads[e][1], n3_[e] = mesh.quads[e][2],
    n4_[e] = mesh.quads[e][3];
  }
  for (auto* v : {&sxx_, &syy_, &sxy_, &szz_, &qx_, &qy_}) v->assign(ne, 0.0);
  // One extra slot that stays 0: the padding target of the 4-slot gather table.
  fcx_.assign(4 * static_cast<size_t>(ne) + 1, 0.0);
  fcy_.assign(4 * static_cast<size_t>(ne) + 1, 0.0);

  // Blocks: runs of at most kBlockSize consecutive elements of one part.
  for (int e = 0; e < ne;) {
    int end = e + 1;
    while (end < ne && end - e < kBlockSize && part_[end] == part_[e]) ++end;
    blocks_.push_back({e, end, part_[e]});
    e = end;
  }
  block_int_.assign(blocks_.size(), 0.0);
  block_hg_.assign(blocks_.size(), 0.0);
  block_damp_.assign(blocks_.size(), 0.0);
  block_inv_dt_.assign(blocks_.size(), 0.0);
  block_min_area_.assign(blocks_.size(), 0.0);

  // CSR node -> corner slots; slots of a node in ascending order (fixed summation order).
  node_ptr_.assign(num_nodes_ + 1, 0);
  for (int e = 0; e < ne; ++e)
    for (int c = 0; c < 4; ++c) ++node_ptr_[mesh.quads[e][c] + 1];
  for (int i = 0; i < num_nodes_; ++i) node_ptr_[i + 1] += node_ptr_[i];
  node_slots_.resize(4 * static_cast<size_t>(ne));
  std::vector<int> fill(node_ptr_.begin(), node_ptr_.end() - 1);
  for (int c = 0; c < 4; ++c)
    for (int e = 0; e < ne; ++e) node_slots_[fill[mesh.quads[e][c]]++] = c * ne + e;
  for (int i = 0; i < num_nodes_; ++i)
    std::sort(node_slots_.begin() + node_ptr_[i], node_slots_.begin() + node_ptr_[i + 1]);
  // Fixed-width gather table: the first 4 slots of every node (padded with the zero slot), and
  // the rare further slots (nodes shared by more than 4 elements) in a short overflow list.
  const int zero_slot = 4 * ne;
  gather4_.assign(4 * static_cast<size_t>(num_nodes_), zero_slot);
  for (int i = 0; i < num_nodes_; ++i) {
    for (int k = node_ptr_[i]; k < node_ptr_[i + 1]; ++k) {
      if (k - node_ptr_[i] < 4) {
        gather4_[4 * static_cast<size_t>(i) + (k - node_ptr_[i])] = node_slots_[k];
      } else {
        overflow_node_.push_back(i);
        overflow_slot_.push_back(node_slots_[k]);
      }
    }
  }
}

const std::vector<int>& QuadElements::connectivity(int corner) const {
  switch (corner) {
    case 0:
      return n1_;
    case 1:
      return n2_;
    case 2:
      return n3_;
    default:
      return n4_;
  }
}

void QuadElements::AddLumpedMass(NodalState* s) const {
  for (int e = 0; e < num_elements(); ++e) {
    const Section& sec = sections_[part_[e]];
    const double x31 = s->x0[n3_[e]] - s->x0[n1_[e]], x42 = s->x0[n4_[e]] - s->x0[n2_[e]];
    const double y31 = s->y0[n3_[e]] - s->y0[n1_[e]], y42 = s->y0[n4_[e]] - s->y0[n2_[e]];
    const double m = 0.25 * sec.material.density * sec.thickness * 0.5 * (x31 * y42 - x42 * y31);
    s->mass[n1_[e]] += m, s->mass[n2_[e]] += m, s->mass[n3_[e]] += m, s->mass[n4_[e]] += m;
  }
}

// The element kernel. Written so that GCC vectorises it (check with -fopt-info-vec): no calls
// (the stable step is reduced as max (c/L_e)^2, the square root is taken once per pass, which
// also keeps std::sqrt's errno out of the loop), one division per element (the three
// denominators 2A(x^(n-1/2)), 2A(x^n) and 1 + q^2 share one reciprocal), no branches.
template <bool kStiffDamp, bool kEnergy>
double QuadElements::BlockKernel(
    const Block& b, const NodalState& s, double h, double* e_int, double* e_hg, double* e_damp) {
  const Section& sec = sections_[b.part];
  const double lam = sec.PlaneLambda(), two_mu = 2.0 * sec.material.Mu();
  const double lam_z = sec.mode == PlaneMode::kPlaneStrain ? sec.material.Lambda() : 0.0;
  const double t = sec.thickness, half_t = 0.5 * t;
  const double c2_wave = 2.0 * sec.WaveSpeed(), c2_wave_sq = c2_wave * c2_wave;
  const double kappa_scale = sec.hourglass_coefficient * (2.0 / 3.0) * sec.BendingModulus() * t;
  const double hh = 0.5 * h, qh = 0.25 * h;
  const double beta = beta_;
  const std::size_t ne = n1_.size();
  const double* __restrict x = s.x.data();
  const double* __restrict y = s.y.data();
  const double* __restrict vx = s.vx.data();
  const double* __restrict vy = s.vy.data();
  const int* __restrict n1 = n1_.data();
  const int* __restrict n2 = n2_.data();
  const int* __restrict n3 = n3_.data();
  const int* __restrict n4 = n4_.data();
  double* __restrict sxx = sxx_.data();
  double* __restrict syy = syy_.data();
  double* __restrict sxy = sxy_.data();
  double* __restrict szz = szz_.data();
  double* __restrict qxa = qx_.data();
  double* __restrict qya = qy_.data();
  double* __restrict fx1 = fcx_.data();
  double* __restrict fx2 = fx1 + ne;
  double* __restrict fx3 = fx2 + ne;
  double* __restrict fx4 = fx3 + ne;
  double* __restrict fy1 = fcy_.data();
  double* __restrict fy2 = fy1 + ne;
  double* __restrict fy3 = fy2 + ne;
  double* __restrict fy4 = fy3 + ne;

  double dint = 0.0, dhg = 0.0, ddamp = 0.0, inv_dt2_max = 0.0,
         min_area = std::numeric_limits<double>::infinity();
#pragma omp simd reduction(+ : dint, dhg, ddamp) reduction(max : inv_dt2_max) \
    reduction(min : min_area)
  for (int e = b.begin; e < b.end; ++e) {
    const int i1 = n1[e], i2 = n2[e], i3 = n3[e], i4 = n4[e];
    const double x1 = x[i1], x2 = x[i2], x3 = x[i3], x4 = x[i4];
    const double y1 = y[i1], y2 = y[i2], y3 = y[i3], y4 = y[i4];
    const double u1 = vx[i1], u2 = vx[i2], u3 = vx[i3], u4 = vx[i4];
    const double w1 = vy[i1], w2 = vy[i2], w3 = vy[i3], w4 = vy[i4];
    const double x31 = x3 - x1, x42 = x4 - x2, y31 = y3 - y1, y42 = y4 - y2;
    const double u31 = u3 - u1, u42 = u4 - u2, w31 = w3 - w1, w42 = w4 - w2;

    // --- Rate of deformation on the mid-step geometry (exactly skew for rigid rotation).
    const double xm31 = x31 - hh * u31, xm42 = x42 - hh * u42;
    const double ym31 = y31 - hh * w31, ym42 = y42 - hh * w42;
    const double two_am = xm31 * ym42 - xm42 * ym31;
    // 2A * velocity gradient.
    const double nxx = ym42 * u31 - ym31 * u42;
    const double nxy = xm31 * u42 - xm42 * u31;  // d vx / d y
    const double nyx = ym42 * w31 - ym31 * w42;  // d vy / d x
    const double nyy = xm31 * w42 - xm42 * w31;
    // Hughes-Winget rotation: tan(alpha / 2) = q = omega h / 2 = wq / 2A_m, so
    // cos(alpha) = (4A_m^2 - wq^2) / den, sin(alpha) = 2 wq 2A_m / den, den = 4A_m^2 + wq^2.
    const double wq = qh * (nyx - nxy);
    const double am2 = two_am * two_am, wq2 = wq * wq;
    const double den = am2 + wq2;
    // Current geometry.
    const double two_a = x31 * y42 - x42 * y31;
    // One reciprocal for 1 / (2A_m), 1 / (2A) and 1 / den.
    const double a_am = two_a * two_am;
    const double r = 1.0 / (a_am * den);
    const double inv_m = two_a * den * r;
    const double inv_a2 = two_am * den * r;
    const double inv_den = a_am * r;
    const double ca = (am2 - wq2) * inv_den, sa = 2.0 * wq * two_am * inv_den;
    const double c2 = ca * ca - sa * sa, s2 = 2.0 * sa * ca;
    const double s_inc = h * inv_m;
    const double dxx = s_inc * nxx, dyy = s_inc * nyy, dxy = 0.5 * s_inc * (nxy + nyx);

    // --- Stress: rotate, then add the elastic increment.
    const double s_xx0 = sxx[e], s_yy0 = syy[e], s_xy0 = sxy[e];
    const double p = 0.5 * (s_xx0 + s_yy0), d = 0.5 * (s_xx0 - s_yy0);
    const double dr = d * c2 - s_xy0 * s2;
    const double rxx = p + dr, ryy = p - dr, rxy = d * s2 + s_xy0 * c2;
    const double tr = dxx + dyy;
    const double n_xx = rxx + lam * tr + two_mu * dxx;
    const double n_yy = ryy + lam * tr + two_mu * dyy;
    const double n_xy = rxy + two_mu * dxy;
    sxx[e] = n_xx, syy[e] = n_yy, sxy[e] = n_xy;
    szz[e] += lam_z * tr;
    const double area_m = 0.5 * two_am;
    if constexpr (kEnergy)
      dint +=
          t * area_m * (0.5 * (rxx + n_xx) * dxx + 0.5 * (ryy + n_yy) * dyy + (rxy + n_xy) * dxy);

    // --- Stable step on the current geometry: (c / L_e)^2 = c^2 lmax / A^2.
    min_area = Min(min_area, two_a > 0.0 ? two_a : -1.0);  // NaN counts as inverted
    const double x21 = x2 - x1, y21 = y2 - y1, x32 = x3 - x2, y32 = y3 - y2;
    const double x43 = x4 - x3, y43 = y4 - y3, x14 = x1 - x4, y14 = y1 - y4;
    const double d13 = x31 * x31 + y31 * y31, d24 = x42 * x42 + y42 * y42;
    const double lmax = Max(Max(Max(d13, d24), Max(x21 * x21 + y21 * y21, x32 * x32 + y32 * y32)),
                            Max(x43 * x43 + y43 * y43, x14 * x14 + y14 * y14));
    inv_dt2_max = Max(inv_dt2_max, c2_wave_sq * lmax * (inv_a2 * inv_a2));

    double fxx = n_xx, fyy = n_yy, fxy = n_xy;  // stress that makes the force
    if constexpr (kStiffDamp) {
      // Viscous stress beta * C : D with D from the same velocity gradient.
      const double vxx = inv_m * nxx, vyy = inv_m * nyy, vxy = 0.5 * inv_m * (nxy + nyx);
      const double vtr = vxx + vyy;
      const double sv_xx = beta * (lam * vtr + two_mu * vxx);
      const double sv_yy = beta * (lam * vtr + two_mu * vyy);
      const double sv_xy = beta * two_mu * vxy;
      fxx += sv_xx, fyy += sv_yy, fxy += sv_xy;
      // Summed with or without kEnergy: dropping it lets the compiler fuse the viscous
      // stress's products differently (FMA), and the forces would no longer be bit-identical.
      ddamp += t * area_m * h * (sv_xx * vxx + sv_yy * vyy + 2.0 * sv_xy * vxy);
    }

    // --- Hourglass (gamma projection, co-rotational stiffness).
    const double hx = x1 - x2 + x3 - x4, hy = y1 - y2 + y3 - y4;
    const double g1 = (hy * x42 - hx * y42) * inv_a2;
    const double g2 = (hx * y31 - hy * x31) * inv_a2;
    const double qdx = 0.25 * ((u1 - u2 + u3 - u4) + g1 * u31 + g2 * u42);
    const double qdy = 0.25 * ((w1 - w2 + w3 - w4) + g1 * w31 + g2 * w42);
    const double kappa_h = kappa_scale * h * (d13 + d24) * inv_a2;
    const double qx0 = qxa[e], qy0 = qya[e];
    const double qxr = ca * qx0 - sa * qy0, qyr = sa * qx0 + ca * qy0;
    const double qxn = qxr + kappa_h * qdx, qyn = qyr + kappa_h * qdy;
    qxa[e] = qxn, qya[e] = qyn;
    if constexpr (kEnergy) dhg += 0.5 * h * ((qxr + qxn) * qdx + (qyr + qyn) * qdy);
    const double gm1 = 0.25 * (1.0 - g1), gm2 = 0.25 * (-1.0 - g2);
    const double gm3 = 0.25 * (1.0 + g1), gm4 = 0.25 * (-1.0 + g2);

    // --- Corner (resisting) forces: t A sigma . b_I + gamma_I Q.
    const double ax1 = half_t * (fxy * x42 - fxx * y42), ay1 = half_t * (fyy * x42 - fxy * y42);
    const double ax2 = half_t * (fxx * y31 - fxy * x31), ay2 = half_t * (fxy * y31 - fyy * x31);
    fx1[e] = ax1 + gm1 * qxn, fy1[e] = ay1 + gm1 * qyn;
    fx2[e] = ax2 + gm2 * qxn, fy2[e] = ay2 + gm2 * qyn;
    fx3[e] = -ax1 + gm3 * qxn, fy3[e] = -ay1 + gm3 * qyn;
    fx4[e] = -ax2 + gm4 * qxn, fy4[e] = -ay2 + gm4 * qyn;
  }
  *e_int += dint;
  *e_hg += dhg;
  *e_damp += ddamp;
  return min_area > 0.0 ? inv_dt2_max : std::numeric_limits<double>::infinity();
}

double QuadElements::StableStep(const NodalState& s) const {
  double inv_dt2 = 0.0;
  for (double v : block_inv_dt_) inv_dt2 = std::max(inv_dt2, v);
  if (!std::isfinite(inv_dt2)) {
    // Find the first inverted element for the message.
    for (int e = 0; e < num_elements(); ++e) {
      const double x31 = s.x[n3_[e]] - s.x[n1_[e]], x42 = s.x[n4_[e]] - s.x[n2_[e]];
      const double y31 = s.y[n3_[e]] - s.y[n1_[e]], y42 = s.y[n4_[e]] - s.y[n2_[e]];
      if (!(x31 * y42 - x42 * y31 > 0.0)) {
        std::ostringstream os;
        os << "element " << e << " (part " << part_[e] << ") inverted or degenerate (area <= 0)";
        throw NumericalError(os.str());
      }
    }
    throw NumericalError("elements: non-finite stable time step (NaN in positions or velocities)");
  }
  if (!(inv_dt2 > 0.0)) return std::numeric_limits<double>::infinity();
  const double inv_dt = std::sqrt(inv_dt2);
  if (beta_ > 0.0) {
    // Stiffness damping: dt = dt_e (sqrt(1 + xi^2) - xi), xi = beta / dt_e. Monotone in 1/dt_e,
    // so applying it to the largest 1/dt_e gives the smallest damped step.
    const double xi = beta_ * inv_dt;
    return (std::sqrt(1.0 + xi * xi) - xi) / inv_dt;
  }
  return 1.0 / inv_dt;
}

// The element kernel is inlined here once per instruction set (core/multiversion.h).
SPALLKIT_MULTIVERSION
void QuadElements::ComputeBlock(int k, const NodalState& s, double dt_prev) {
  double* e_int = &block_int_[k];
  double* e_hg = &block_hg_[k];
  double* e_damp = &block_damp_[k];
  const Block& b = blocks_[k];
  if (energy_terms_)
    block_inv_dt_[k] = beta_ > 0.0 ? BlockKernel<true, true>(b, s, dt_prev, e_int, e_hg, e_damp)
                                   : BlockKernel<false, true>(b, s, dt_prev, e_int, e_hg, e_damp);
  else
    block_inv_dt_[k] = beta_ > 0.0 ? BlockKernel<true, false>(b, s, dt_prev, e_int, e_hg, e_damp)
                                   : BlockKernel<false, false>(b, s, dt_prev, e_int, e_hg, e_damp);
}

// On one thread the loops run without an OpenMP region: libgomp allocates a team for every
// region when it has no thread pool (no allocation in the time loop).
double QuadElements::ComputeCornerForces(const NodalState& s, double dt_prev, int threads) {
  const int nb = static_cast<int>(blocks_.size());
  const int nt = threads > 0 ? threads : omp_get_max_threads();
  if (nt > 1) {
#pragma omp parallel for schedule(static) num_threads(nt)
    for (int k = 0; k < nb; ++k) ComputeBlock(k, s, dt_prev);
  } else {
    for (int k = 0; k < nb; ++k) ComputeBlock(k, s, dt_prev);
  }
  return StableStep(s);
}

double QuadElements::ComputeForces(NodalState* s, double dt_prev, int threads) {
  const int nb = static_cast<int>(blocks_.size());
  const int nc = (num_nodes_ + kGatherChunk - 1) / kGatherChunk;
  const int nt = threads > 0 ? threads : omp_get_max_threads();
  if (nt > 1) {
#pragma omp parallel num_threads(nt)
    {
#pragma omp for schedule(static)
      for (int k = 0; k < nb; ++k) ComputeBlock(k, *s, dt_prev);
        // (implicit barrier: every corner force is written before any node gathers)
#pragma omp for schedule(static) nowait
      for (int c = 0; c < nc; ++c)
        GatherForces(s, c * kGatherChunk, std::min(num_nodes_, (c + 1) * kGatherChunk));
    }
  } else {
    for (int k = 0; k < nb; ++k) ComputeBlock(k, *s, dt_prev);
    GatherForces(s, 0, num_nodes_);
  }
  return StableStep(*s);
}

void QuadElements::GatherForces(NodalState* s, int begin, int end) const {
  const int* __restrict g = gather4_.data();
  const double* __restrict fcx = fcx_.data();
  const double* __restrict fcy = fcy_.data();
  double* __restrict fx = s->fx.data();
  double* __restrict fy = s->fy.data();
  // Same sum, in the same (ascending slot) order, as a loop over the node's slots: branch-free.
  for (int i = begin; i < end; ++i) {
    const int* gi = g + 4 * static_cast<size_t>(i);
    fx[i] = -(((fcx[gi[0]] + fcx[gi[1]]) + fcx[gi[2]]) + fcx[gi[3]]);
    fy[i] = -(((fcy[gi[0]] + fcy[gi[1]]) + fcy[gi[2]]) + fcy[gi[3]]);
  }
  if (overflow_node_.empty()) return;
  const auto first = std::lower_bound(overflow_node_.begin(), overflow_node_.end(), begin);
  for (auto k = static_cast<size_t>(first - overflow_node_.begin());
       k < overflow_node_.size() && overflow_node_[k] < end;
       ++k) {
    const int i = overflow_node_[k];
    fx[i] -= fcx[overflow_slot_[k]];
    fy[i] -= fcy[overflow_slot_[k]];
  }
}

void QuadElements::GatherForces(NodalState* s, int threads) const {
  const int nc = (num_nodes_ + kGatherChunk - 1) / kGatherChunk;
  const int nt = threads > 0 ? threads : omp_get_max_threads();
  if (nt <= 1) return GatherForces(s, 0, num_nodes_);
#pragma omp parallel for schedule(static) num_threads(nt)
  for (int c = 0; c < nc; ++c)
    GatherForces(s, c * kGatherChunk, std::min(num_nodes_, (c + 1) * kGatherChunk));
}

namespace {
double SumBlocks(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}
}  // namespace

namespace {
constexpr double kNotKept = std::numeric_limits<double>::quiet_NaN();
}  // namespace

double QuadElements::InternalEnergy() const {
  return energy_terms_ ? SumBlocks(block_int_) : kNotKept;
}
double QuadElements::HourglassEnergy() const {
  return energy_terms_ ? SumBlocks(block_hg_) : kNotKept;
}
double QuadElements::DampingEnergy() const {
  return energy_terms_ ? SumBlocks(block_damp_) : kNotKept;
}
double QuadElements::InternalEnergy(int part) const {
  if (!energy_terms_) return kNotKept;
  double s = 0.0;
  for (size_t k = 0; k < blocks_.size(); ++k)
    if (blocks_[k].part == part) s += block_int_[k];
  return s;
}
double QuadElements::HourglassEnergy(int part) const {
  if (!energy_terms_) return kNotKept;
  double s = 0.0;
  for (size_t k = 0; k < blocks_.size(); ++k)
    if (blocks_[k].part == part) s += block_hg_[k];
  return s;
}

double QuadElements::VonMises(int e) const {
  const double a = sxx_[e], b = syy_[e], c = szz_[e], t = sxy_[e];
  return std::sqrt(0.5 * ((a - b) * (a - b) + (b - c) * (b - c) + (c - a) * (c - a)) + 3.0 * t * t);
}

double QuadElements::Area(const NodalState& s, int e) const {
  const double x31 = s.x[n3_[e]] - s.x[n1_[e]], x42 = s.x[n4_[e]] - s.x[n2_[e]];
  const double y31 = s.y[n3_[e]] - s.y[n1_[e]], y42 = s.y[n4_[e]] - s.y[n2_[e]];
  return 0.5 * (x31 * y42 - x42 * y31);
}

void QuadElements::Centroid(const NodalState& s, int e, double* x, double* y) const {
  *x = 0.25 * (s.x[n1_[e]] + s.x[n2_[e]] + s.x[n3_[e]] + s.x[n4_[e]]);
  *y = 0.25 * (s.y[n1_[e]] + s.y[n2_[e]] + s.y[n3_[e]] + s.y[n4_[e]]);
}

void QuadElements::Save(CheckpointWriter* out) const {
  for (const auto* v :
       {&sxx_, &syy_, &sxy_, &szz_, &qx_, &qy_, &block_int_, &block_hg_, &block_damp_})
    out->PutVector(*v);
}

void QuadElements::Load(CheckpointReader* in) {
  const char* names[] = {"sxx",
                         "syy",
                         "sxy",
                         "szz",
                         "qx",
                         "qy",
                         "internal energy",
                         "hourglass energy",
                         "damping energy"};
  int k = 0;
  for (auto* v : {&sxx_, &syy_, &sxy_, &szz_, &qx_, &qy_, &block_int_, &block_hg_, &block_damp_})
    in->GetVectorInto(v, names[k++]);
}

}  // namespace spallkit::sim::fe
