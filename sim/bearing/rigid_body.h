// Rigid bodies in the section plane and their time integration: the rollers, cage and inner
// ring of the hybrid and lumped bearing models, advanced with the explicit solver's
// central-difference scheme (forces at x^n with velocities v^(n-1/2), then v^(n+1/2), x^(n+1)).
#pragma once

namespace spallkit::sim {

// Pose and velocity of a rigid body: mass centre (x, y), rotation angle from the initial pose,
// velocities at t^(n-1/2) (after a step: n+1/2).
struct PlanarBody {
  double x = 0, y = 0, angle = 0, vx = 0, vy = 0, omega = 0;

  // One central-difference step under force (fx, fy) and torque about the mass centre:
  // dt_avg = (dt_prev + dt) / 2 for the velocities, dt for the positions.
  void Advance(
      double fx, double fy, double torque, double mass, double inertia, double dt_avg, double dt) {
    vx += dt_avg * fx / mass;
    vy += dt_avg * fy / mass;
    omega += dt_avg * torque / inertia;
    x += dt * vx, y += dt * vy, angle += dt * omega;
  }
  // The same without rotation (a body whose angle is prescribed or irrelevant).
  void Translate(double fx, double fy, double mass, double dt_avg, double dt) {
    vx += dt_avg * fx / mass;
    vy += dt_avg * fy / mass;
    x += dt * vx, y += dt * vy;
  }
  double TranslationalEnergy(double mass) const { return 0.5 * mass * (vx * vx + vy * vy); }
  double KineticEnergy(double mass, double inertia) const {
    return TranslationalEnergy(mass) + 0.5 * inertia * omega * omega;
  }
};

}  // namespace spallkit::sim
