// The lumped model's outer ring: one rigid circle of the raceway radius, centre (x, y), no
// rotation. Its methods are inline and the class final so that the roller contacts, which reach
// the race at every roller and step, call them directly when it is the race (RollerContacts).
#pragma once

#include <cmath>

#include "sim/bearing/roller_contacts.h"

namespace spallkit::sim {

class RigidOuterRace final : public OuterRace {
 public:
  explicit RigidOuterRace(double radius) : radius_(radius) {}
  void Gap(double qx, double qy, double rad, RacePoint* p) const override {
    const double dx = qx - x_, dy = qy - y_, d = std::sqrt(dx * dx + dy * dy);
    p->nx = -dx / d, p->ny = -dy / d;
    p->px = qx - rad * p->nx, p->py = qy - rad * p->ny;
    p->delta = d + rad - radius_;
  }
  void Velocity(double, double, double* vx, double* vy) const override { *vx = vx_, *vy = vy_; }
  void Apply(double, double, double fx, double fy) override { fx_ += fx, fy_ += fy; }
  bool MayTouch(double cx, double cy, double radius) const override {
    const double dx = cx - x_, dy = cy - y_, reach = radius_ - radius;
    return reach < 0 || dx * dx + dy * dy > reach * reach;
  }
  RigidOuterRace* AsRigid() override { return this; }

  double radius_ = 0, x_ = 0, y_ = 0, vx_ = 0, vy_ = 0;
  double fx_ = 0, fy_ = 0;  // force of the rollers this step
};

}  // namespace spallkit::sim
