#include "sim/bearing/constraints.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/checkpoint_io.h"
#include "core/error.h"

namespace spallkit::sim {
RigidPart::RigidPart(std::string name, std::vector<int> nodes)
    : name_(std::move(name)), nodes_(std::move(nodes)) {
  if (nodes_.size() < 2) throw InputError("rigid part '" + name_ + "': needs at least 2 nodes");
}

RigidPart::Motion RigidPart::ComputeMotion(const fe::NodalState& s) const {
  Motion m;
  double sx = 0, sy = 0, px = 0, py = 0, lz = 0, j0 = 0;
  for (int id : nodes_) {
    const double mi = s.mass[id];
    m.mass += mi, sx += mi * s.x[id], sy += mi * s.y[id];
    px += mi * s.vx[id], py += mi * s.vy[id];
    lz += mi * (s.x[id] * s.vy[id] - s.y[id] * s.vx[id]);
    j0 += mi * (s.x[id] * s.x[id] + s.y[id] * s.y[id]);
  }
  m.cx = sx / m.mass, m.cy = sy / m.mass, m.vx = px / m.mass, m.vy = py / m.mass;
  m.inertia = j0 - m.mass * (m.cx * m.cx + m.cy * m.cy);
  const double l = lz - m.mass * (m.cx * m.vy - m.cy * m.vx);
  m.omega = m.inertia > 0 ? l / m.inertia : 0.0;
  return m;
}

void RigidPart::AddForces(fe::NodalState& s, double /*t*/, double dt) {
  if (ref_x_.empty()) {
    // Reference shape: positions relative to the mass centre at the first step.
    const Motion m0 = ComputeMotion(s);
    for (int id : nodes_) ref_x_.push_back(s.x[id] - m0.cx), ref_y_.push_back(s.y[id] - m0.cy);
  }
  // Project positions and velocities back onto a rigid motion (best-fit rotation of the
  // reference shape about the mass centre; momentum and angular momentum unchanged): the
  // central-difference update keeps the set rigid only to O(dt^2) per step, and that drift
  // would accumulate over thousands of revolutions.
  Motion m = ComputeMotion(s);
  SPALLKIT_CHECK(m.inertia > 0.0, "rigid part '" << name_ << "' has no rotational inertia");
  {
    double dot = 0, cross = 0;
    for (size_t k = 0; k < nodes_.size(); ++k) {
      const int id = nodes_[k];
      const double rx = s.x[id] - m.cx, ry = s.y[id] - m.cy, mi = s.mass[id];
      dot += mi * (ref_x_[k] * rx + ref_y_[k] * ry);
      cross += mi * (ref_x_[k] * ry - ref_y_[k] * rx);
    }
    const double norm = std::hypot(dot, cross);
    const double c = dot / norm, sn = cross / norm;
    for (size_t k = 0; k < nodes_.size(); ++k) {
      const int id = nodes_[k];
      const double rx = c * ref_x_[k] - sn * ref_y_[k], ry = sn * ref_x_[k] + c * ref_y_[k];
      s.x[id] = m.cx + rx, s.y[id] = m.cy + ry;
      s.vx[id] = m.vx - m.omega * ry, s.vy[id] = m.vy + m.omega * rx;
    }
  }
  double fx = 0, fy = 0, tz = 0;
  for (int id : nodes_) {
    const double rx = s.x[id] - m.cx, ry = s.y[id] - m.cy;
    fx += s.fx[id], fy += s.fy[id], tz += rx * s.fy[id] - ry * s.fx[id];
  }
  const double ax = fx / m.mass, ay = fy / m.mass, alpha = tz / m.inertia;
  const double w2 = m.omega * m.omega;
  double power = 0.0;
  for (int id : nodes_) {
    const double mi = s.mass[id];
    const double rx = s.x[id] - m.cx, ry = s.y[id] - m.cy;
    const double nfx = mi * (ax - alpha * ry - w2 * rx);
    const double nfy = mi * (ay + alpha * rx - w2 * ry);
    power += (nfx - s.fx[id]) * s.vx[id] + (nfy - s.fy[id]) * s.vy[id];
    s.fx[id] = nfx, s.fy[id] = nfy;
  }
  work_ += power * dt;
}

std::string RigidPart::SaveState() const {
  CheckpointWriter out;
  out.Put(work_);
  for (size_t k = 0; k < ref_x_.size(); ++k) out.Put(ref_x_[k]), out.Put(ref_y_[k]);
  return out.Take();
}

void RigidPart::LoadState(const std::string& bytes) {
  const size_t n = bytes.size() / sizeof(double);
  if (bytes.size() % sizeof(double) != 0 || (n != 1 && n != 1 + 2 * nodes_.size()))
    throw InputError("checkpoint: bad state size for '" + name_ + "'");
  CheckpointReader in(bytes, "checkpoint: state of '" + name_ + "'");
  work_ = in.Get<double>();
  ref_x_.clear(), ref_y_.clear();
  while (!in.AtEnd()) {
    ref_x_.push_back(in.Get<double>());
    ref_y_.push_back(in.Get<double>());
  }
}

bool CageGuideOptions::IsValid(std::string* error) const {
  if (radial_play_m >= 0.0 && stiffness_n_per_m > 0.0) return true;
  if (error) *error = "cage guide: radial_play_m must be >= 0 and stiffness_n_per_m > 0";
  return false;
}

double CageGuideOptions::RadialForce(double radial, double* energy) const {
  const double over = std::abs(radial) - radial_play_m;
  if (over <= 0.0) return 0.0;
  *energy += 0.5 * stiffness_n_per_m * over * over;
  return (radial > 0.0 ? -1.0 : 1.0) * stiffness_n_per_m * over;
}

CagePocketGuide::CagePocketGuide(std::string name,
                                 std::vector<std::vector<int>> rollers,
                                 std::vector<std::vector<int>> pockets,
                                 std::vector<int> cage,
                                 double pitch_radius_m,
                                 const CageGuideOptions& options)
    : name_(std::move(name)),
      rollers_(std::move(rollers)),
      pockets_(std::move(pockets)),
      cage_(std::move(cage)),
      pitch_radius_(pitch_radius_m),
      options_(options),
      force_(rollers_.size(), 0.0) {
  std::string error;
  if (!options_.IsValid(&error)) throw InputError(name_ + ": " + error);
  if (rollers_.empty() || rollers_.size() != pockets_.size() || cage_.empty())
    throw InputError(name_ + ": needs one pocket per roller and a cage node set");
  for (size_t j = 0; j < rollers_.size(); ++j)
    if (rollers_[j].empty() || pockets_[j].empty())
      throw InputError(name_ + ": empty roller or pocket node set " + std::to_string(j));
}

namespace {
struct MassCentre {
  double m = 0, x = 0, y = 0;
};
MassCentre CentreOf(const fe::NodalState& s, const std::vector<int>& nodes) {
  MassCentre c;
  for (int id : nodes) c.m += s.mass[id], c.x += s.mass[id] * s.x[id], c.y += s.mass[id] * s.y[id];
  c.x /= c.m, c.y /= c.m;
  return c;
}
}  // namespace

void CagePocketGuide::AddForces(fe::NodalState& s, double /*t*/, double /*dt*/) {
  potential_ = 0.0;
  const MassCentre cage = CentreOf(s, cage_);
  double cage_inertia = -1.0;  // about the cage's mass centre, computed when first needed
  for (size_t j = 0; j < rollers_.size(); ++j) {
    force_[j] = 0.0;
    const MassCentre roller = CentreOf(s, rollers_[j]);
    const MassCentre pocket = CentreOf(s, pockets_[j]);
    const double lx = pocket.x - cage.x, ly = pocket.y - cage.y, l = std::hypot(lx, ly);
    const double ex = lx / l, ey = ly / l;
    const double dx = roller.x - cage.x, dy = roller.y - cage.y;
    // Force on the roller, back towards the play band along e (at its mass centre).
    const double f = options_.RadialForce(dx * ex + dy * ey - pitch_radius_, &potential_);
    if (f == 0.0) continue;
    force_[j] = std::abs(f);
    const double fx = f * ex, fy = f * ey;
    for (int id : rollers_[j]) {
      const double w = s.mass[id] / roller.m;
      s.fx[id] += w * fx, s.fy[id] += w * fy;
    }
    // The opposite force at the roller's centre, on the cage: resultant by mass plus the torque
    // (c_j - c_cage) x (-F) by mass times e_z x r (the RigidPart turns both into exact rigid
    // accelerations). With e turning with the cage this is V's derivative by the cage angle.
    if (cage_inertia < 0.0) {
      cage_inertia = 0.0;
      for (int id : cage_) {
        const double rx = s.x[id] - cage.x, ry = s.y[id] - cage.y;
        cage_inertia += s.mass[id] * (rx * rx + ry * ry);
      }
    }
    const double torque = -(dx * fy - dy * fx);
    for (int id : cage_) {
      const double rx = s.x[id] - cage.x, ry = s.y[id] - cage.y, mi = s.mass[id];
      s.fx[id] += -mi / cage.m * fx - torque * mi * ry / cage_inertia;
      s.fy[id] += -mi / cage.m * fy + torque * mi * rx / cage_inertia;
    }
  }
}

double CagePocketGuide::StableTimeStep(const fe::NodalState& s) const {
  // The spring between a roller's and the cage's mass centres: omega^2 = k (1/m_r + 1/m_c).
  // Lumped masses are fixed for a run: computed once.
  if (stable_step_ == 0.0) {
    double cage_mass = 0.0, lightest = std::numeric_limits<double>::infinity();
    for (int id : cage_) cage_mass += s.mass[id];
    for (const auto& r : rollers_) {
      double m = 0.0;
      for (int id : r) m += s.mass[id];
      lightest = std::min(lightest, m);
    }
    const double omega2 = options_.stiffness_n_per_m * (1.0 / lightest + 1.0 / cage_mass);
    stable_step_ = 0.9 * 2.0 / std::sqrt(omega2);
  }
  return stable_step_;
}

TiedNodes::TiedNodes(std::string name, std::vector<std::pair<int, int>> pairs)
    : name_(std::move(name)), pairs_(std::move(pairs)) {
  if (pairs_.empty()) throw InputError("tied nodes '" + name_ + "': no node pairs");
}

void TiedNodes::AddForces(fe::NodalState& s, double /*t*/, double /*dt*/) {
  for (const auto& [a, b] : pairs_) {
    const double ma = s.mass[a], mb = s.mass[b], m = ma + mb;
    const double wa = ma / m, wb = mb / m;
    const double dvx = s.vx[a] - s.vx[b], dvy = s.vy[a] - s.vy[b];
    dissipated_ += 0.5 * ma * mb / m * (dvx * dvx + dvy * dvy);
    const double vx = wa * s.vx[a] + wb * s.vx[b], vy = wa * s.vy[a] + wb * s.vy[b];
    const double x = wa * s.x[a] + wb * s.x[b], y = wa * s.y[a] + wb * s.y[b];
    const double fx = s.fx[a] + s.fx[b], fy = s.fy[a] + s.fy[b];
    s.vx[a] = s.vx[b] = vx, s.vy[a] = s.vy[b] = vy;
    s.x[a] = s.x[b] = x, s.y[a] = s.y[b] = y;
    s.fx[a] = wa * fx, s.fy[a] = wa * fy;
    s.fx[b] = wb * fx, s.fy[b] = wb * fy;
  }
}

std::string TiedNodes::SaveState() const {
  CheckpointWriter out;
  out.Put(dissipated_);
  return out.Take();
}

void TiedNodes::LoadState(const std::string& bytes) {
  if (bytes.size() != sizeof(double))
    throw InputError("checkpoint: bad state size for '" + name_ + "'");
  dissipated_ = CheckpointReader(bytes, "checkpoint: state of '" + name_ + "'").Get<double>();
}

}  // namespace spallkit::sim
