// Structured quadrilateral meshes for the bearing parts and the verification problems.
//
// Every generator returns a one-part Mesh (part name = `part`) that follows the conventions of
// sim/fe/mesh.h: counter-clockwise quads, boundary curves walked with the material on the left,
// names "<part>.<what>". Node set "<part>.all" holds every node of the part. Parts are combined
// with MergeMeshes, which renumbers nodes and never joins nodes of different parts (contact
// couples them).
#pragma once

#include <string>
#include <vector>

#include "sim/fe/mesh.h"

namespace spallkit::sim::fe {

// Which edge of a rectangle the grading concentrates elements towards.
enum class GradeEdge { kNone, kLeft, kRight, kBottom, kTop };

// Axis-parallel rectangle [x0, x0 + width] x [y0, y0 + height] with nx x ny quads.
struct RectangleSpec {
  double x0 = 0.0, y0 = 0.0;
  double width = 1.0, height = 1.0;  // m
  int nx = 1, ny = 1;
  // Geometric grading: element size at the far edge divided by the size at `grade_edge`
  // (> 1 refines towards grade_edge). Ignored with GradeEdge::kNone.
  GradeEdge grade_edge = GradeEdge::kNone;
  double grade_ratio = 1.0;
};

// Node sets: "<part>.all", "<part>.left", "<part>.right", "<part>.bottom", "<part>.top" (corners
// belong to both edges). Curves: "<part>.outer" (closed, counter-clockwise) and the open edge
// curves "<part>.left/right/bottom/top", each walked with the block on its left.
// Node (i, j), 0 <= i <= nx, 0 <= j <= ny, has id j * (nx + 1) + i.
Mesh MakeRectangle(const std::string& part, const RectangleSpec& spec);

// Annulus (ring) centred at (cx, cy). Node (i_theta, j_radial) has id j * n_theta + i, node 0 at
// angle theta0 on the inner radius, angles increasing counter-clockwise.
struct AnnulusSpec {
  double cx = 0.0, cy = 0.0;
  double inner_radius = 0.5, outer_radius = 1.0;  // m
  int n_theta = 16, n_radial = 1;
  double theta0 = 0.0;  // angle of the first node, rad
  // Radial grading: outermost layer thickness / innermost layer thickness (< 1 refines towards
  // the outer radius, e.g. a raceway on the outside of an inner ring).
  double radial_ratio = 1.0;
};

// Node sets "<part>.all", "<part>.inner", "<part>.outer". Curves "<part>.outer" (closed,
// counter-clockwise) and "<part>.inner" (closed, clockwise around the hole).
Mesh MakeAnnulus(const std::string& part, const AnnulusSpec& spec);

// Full disc (e.g. a roller) as an O-grid: a square core of n_core x n_core quads surrounded by a
// ring of n_radial layers whose rim has 4 * n_core nodes at uniform angular spacing (uniform
// surface node spacing matters for contact noise).
struct DiscSpec {
  double cx = 0.0, cy = 0.0;
  double radius = 1.0;          // m
  int n_core = 4;               // quads per side of the core; the rim has 4 * n_core nodes
  int n_radial = 4;             // layers between the core and the rim
  double core_fraction = 0.45;  // half-width of the core square / radius
  double theta0 = 0.0;          // angle of the first rim node, rad
  // Outermost layer thickness / innermost layer thickness (< 1 refines towards the rim).
  double radial_ratio = 1.0;
};

// Node sets "<part>.all", "<part>.outer" (rim), "<part>.center" (the node nearest the centre).
// Curve "<part>.outer" (closed, counter-clockwise, first node at theta0).
Mesh MakeDisc(const std::string& part, const DiscSpec& spec);

// Concatenates meshes as separate parts: node ids of meshes[k] are shifted by the number of
// nodes before it, part indices likewise; node sets and curves keep their names. Throws
// InputError if two meshes define the same part, node set or curve name.
Mesh MergeMeshes(const std::vector<Mesh>& meshes);

// Checks the invariants of mesh.h (node ids in range, positive quad areas, one part index per
// element, node-set and curve ids in range). Throws InputError naming the first violation.
void ValidateMesh(const Mesh& mesh);

// Signed area of quad e (positive for counter-clockwise).
double QuadArea(const Mesh& mesh, int e);

// Renumbers nodes (reverse Cuthill-McKee over the element graph) and elements (by their
// smallest new node id) for memory locality; node sets and curves are renumbered consistently.
// Returns new_id_of_old_node. Call it before building the solver and the contact pairs.
std::vector<int> ReorderForLocality(Mesh* mesh);

}  // namespace spallkit::sim::fe
