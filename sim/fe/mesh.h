// A 2-D quadrilateral mesh of one or more parts, plus the named node sets and boundary curves
// that loads, constraints and contact refer to.
//
// Conventions:
//  - Coordinates in metres; quads list their 4 node ids counter-clockwise (positive area).
//  - A BoundaryCurve is an ordered chain of boundary nodes walked with the body's material on the
//    LEFT (counter-clockwise around an outer boundary, clockwise around a hole). Contact uses
//    it as a surface: segment i joins nodes[i] and nodes[i+1] (and last -> first if closed), and
//    the outward normal of a segment from a to b is (b - a) rotated by -90 degrees.
//  - Names are "<part>.<what>", e.g. "roller3.surface", "inner_ring.bore", "outer_ring.raceway".
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace spallkit::sim::fe {

struct BoundaryCurve {
  std::vector<int> nodes;
  bool closed = false;
};

struct Mesh {
  std::vector<double> x, y;               // node coordinates, m
  std::vector<std::array<int, 4>> quads;  // counter-clockwise node ids
  std::vector<int> element_part;          // part index per element
  std::vector<std::string> part_names;    // part index -> name
  std::map<std::string, std::vector<int>> node_sets;
  std::map<std::string, BoundaryCurve> curves;

  int num_nodes() const { return static_cast<int>(x.size()); }
  int num_elements() const { return static_cast<int>(quads.size()); }
  int num_parts() const { return static_cast<int>(part_names.size()); }
};

}  // namespace spallkit::sim::fe
