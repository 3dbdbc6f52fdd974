#include "sim/bearing/raceway_kernel.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/constants.h"
#include "core/error.h"
#include "sim/contact/spline_surface.h"

namespace spallkit::sim {

RacewayKernel::RacewayKernel(const fe::Mesh& mesh,
                             const std::string& curve,
                             double raceway_radius,
                             double half_width)
    : radius_(raceway_radius) {
  auto it = mesh.curves.find(curve);
  if (it == mesh.curves.end())
    throw InputError("hybrid model: housing mesh has no '" + curve + "'");
  std::vector<std::pair<double, int>> sorted;
  for (int id : it->second.nodes) sorted.emplace_back(std::atan2(mesh.y[id], mesh.x[id]), id);
  std::sort(sorted.begin(), sorted.end());
  const int n = static_cast<int>(sorted.size());
  if (n < 8) throw InputError("hybrid model: outer raceway has fewer than 8 nodes");
  dtheta_ = 2 * kPi / n;
  theta0_ = sorted[0].first;
  for (int k = 0; k < n; ++k) {
    const double expect = theta0_ + k * dtheta_;
    if (std::abs(sorted[k].first - expect) > 1e-6 * dtheta_ + 1e-9)
      throw InputError("hybrid model: outer raceway nodes are not uniformly spaced");
    const int id = sorted[k].second;
    nodes_.push_back(id);
    const double rr = std::hypot(mesh.x[id], mesh.y[id]);
    ex_.push_back(mesh.x[id] / rr);
    ey_.push_back(mesh.y[id] / rr);
  }
  const double spacing = radius_ * dtheta_;
  half_width_ = half_width > 0 ? half_width : std::max(1e-3, 2.0 * spacing);
  if (2 * static_cast<int>(std::ceil(half_width_ / spacing)) + 1 > kMaxNodes)
    throw InputError("hybrid model: spread_half_width_m covers more than 64 raceway nodes");
}

int RacewayKernel::Weights(double th, int* idx, double* w, double* dw) const {
  // w_k = a_k / S with a_k = B3(u_k), u_k = 2 R0 (theta_k - th) / L (the cubic B-spline, support
  // |u| < 2, i.e. half-width L), S = sum a_k; so dw_k/dth = (a_k' - w_k S') / S with
  // a_k' = B3'(u_k) (-2 R0 / L).
  const int n = static_cast<int>(nodes_.size());
  const double spacing = radius_ * dtheta_;
  const int m = static_cast<int>(std::ceil(half_width_ / spacing));
  const long k0 = std::lround((th - theta0_) / dtheta_);
  const double du_dth = -2.0 * radius_ / half_width_;
  int count = 0;
  double sum = 0.0, dsum = 0.0;
  for (long k = k0 - m; k <= k0 + m; ++k) {
    const double u = 2.0 * radius_ * (theta0_ + k * dtheta_ - th) / half_width_;
    double da;
    const double a = contact::CubicBSpline(u, &da);
    if (a <= 0.0) continue;
    idx[count] = static_cast<int>(((k % n) + n) % n);
    w[count] = a;
    if (dw) dw[count] = da * du_dth, dsum += dw[count];
    sum += a;
    ++count;
  }
  for (int i = 0; i < count; ++i) {
    w[i] /= sum;
    if (dw) dw[i] = (dw[i] - w[i] * dsum) / sum;
  }
  return count;
}

double RacewayKernel::Radius(const fe::NodalState& s, double th, double* slope) const {
  int idx[kMaxNodes];
  double w[kMaxNodes], dw[kMaxNodes];
  const int n = Weights(th, idx, w, slope ? dw : nullptr);
  double u = 0.0, du = 0.0;
  for (int i = 0; i < n; ++i) {
    const int id = nodes_[idx[i]];
    const double ui = (s.x[id] - s.x0[id]) * ex_[idx[i]] + (s.y[id] - s.y0[id]) * ey_[idx[i]];
    u += w[i] * ui;
    if (slope) du += dw[i] * ui;
  }
  if (slope) *slope = du;
  return radius_ + u;
}

void RacewayKernel::Velocity(const fe::NodalState& s, double th, double* vx, double* vy) const {
  int idx[kMaxNodes];
  double w[kMaxNodes];
  const int n = Weights(th, idx, w);
  *vx = *vy = 0.0;
  for (int i = 0; i < n; ++i) {
    const int id = nodes_[idx[i]];
    *vx += w[i] * s.vx[id], *vy += w[i] * s.vy[id];
  }
}

void RacewayKernel::Spread(fe::NodalState& s, double th, double fx, double fy) const {
  int idx[kMaxNodes];
  double w[kMaxNodes];
  const int n = Weights(th, idx, w);
  for (int i = 0; i < n; ++i) {
    const int id = nodes_[idx[i]];
    s.fx[id] += w[i] * fx, s.fy[id] += w[i] * fy;
  }
}

double RacewayKernel::ContactMass(const fe::NodalState& s) const {
  // A contact couples the roller with the raceway nodes through K = k w~ w~^T, w~ = (1, -w):
  // its one non-zero mode has omega^2 = k (1/m_roller + sum_i w_i^2 / m_i), so the ring acts as
  // ONE body of mass 1 / sum_i w_i^2 / m_i.
  int idx[kMaxNodes];
  double w[kMaxNodes], s_max = 0.0;
  const int nodes = static_cast<int>(nodes_.size());
  for (int step = 0; step <= 10; ++step) {
    const int n = Weights(theta0_ + 0.05 * step * dtheta_, idx, w);
    for (int k = 0; k < nodes; ++k) {  // node masses may differ near the seat
      double sum = 0.0;
      for (int i = 0; i < n; ++i) {
        const int id = nodes_[(idx[i] + k) % nodes];
        sum += w[i] * w[i] / s.mass[id];
      }
      s_max = std::max(s_max, sum);
    }
  }
  return 1.0 / s_max;
}

}  // namespace spallkit::sim
