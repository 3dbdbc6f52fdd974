// One pass of a ContactPair: the slave surface's nodes and points against the master surface.
// Holds what every contact strategy shares: the search grid, the node contacts' slots and stick
// springs, and the point contact's (arc blend or spline) slot and spring.
#pragma once

#include <utility>
#include <vector>

#include "sim/contact/contact_law.h"
#include "sim/contact/segment_grid.h"
#include "sim/contact/surface.h"

namespace spallkit::sim::contact {

struct ContactPass {
  ContactSurface slave, master;
  SegmentGrid grid;
  std::vector<double> x_built, y_built;  // master node positions at the last grid build
  double margin = 0.0, capture = 0.0;    // m: search margin, deepest penetration in contact

  // Node-to-segment contact, per slave node.
  std::vector<double> tangential_force;  // stick spring, along the master tangent
  std::vector<double> tangential_stiffness;
  std::vector<double> gap;
  std::vector<ContactSlot> slots;
  // Per slave node: a point contact stands for it (no node contact). Empty without one.
  std::vector<char> node_owned;

  // The point contact (curved slave surface: arc blend or spline), one per pass.
  ContactSlot point_slot;
  double point_spring = 0.0, point_spring_stiffness = 0.0;

  StickSpring NodeSpring(int i) { return {&tangential_force[i], &tangential_stiffness[i]}; }
  StickSpring PointSpring() { return {&point_spring, &point_spring_stiffness}; }

  // Hand-over: a point contact without a loaded spring takes over the loaded spring of slave
  // node `local` when that node has no node contact this step (the contact walked from it).
  void TakeNodeSpring(int local) {
    if (point_spring == 0.0 && slots[local].segment < 0 && tangential_force[local] != 0.0)
      std::swap(point_spring, tangential_force[local]);
  }
  // After the point contact's law: the springs of slave nodes not in node contact this step
  // give up their energy (into their slots' friction work).
  void ReleaseIdleNodeSprings() {
    for (int i = 0; i < slave.num_nodes(); ++i)
      if (slots[i].segment < 0)
        slots[i].friction_work += ReleaseSpring(&tangential_force[i], tangential_stiffness[i]);
  }
  // Out of contact: the point contact's spring energy is dissipated, as for a node.
  void ReleasePointSpring() {
    point_slot.friction_work += ReleaseSpring(&point_spring, point_spring_stiffness);
  }
};

}  // namespace spallkit::sim::contact
