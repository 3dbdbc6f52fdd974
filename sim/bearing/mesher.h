// Quadrilateral mesh of the 2-D bearing section of a Scene: outer ring, inner ring, brass cage,
// Z rollers (with rectangular spalls) and the adapter under the outer ring.
//
// Layout (bearing centre at the origin, y up; the radial load pushes the inner ring towards -y):
//  - roller j sits on the pitch circle at angle phi_j = -pi/2 + roller_phase + 2 pi j / Z, so
//    roller 0 is on the load line at the bottom; rollers are centred radially and in their pockets.
//  - raceways are moved by P_d/4 each (outer out, inner in): a centred roller has P_d/4 gap on
//    each side, P_d/2 in total (Harris's diametral clearance, as in quasistatic/harris_jones.h).
//  - the cage in the section plane is Z separate webs between the pockets (the side rims that
//    join them lie outside the plane): one part "cage"; the model builder must tie the webs
//    (rigid cage or rim constraint). Pocket walls are straight, parallel to the pocket's radial
//    centre line, (D + pocket clearance)/2 from it.
//  - the adapter is a block of the scene's width under the outer ring with a circular seat of the
//    ring's outer radius; its seat nodes coincide with the ring's outside nodes (so tied or
//    penalty contact starts without gap or overlap); its bottom (node set "adapter.bottom") is
//    fixed. Its width is snapped to the ring's node spacing (BearingMesh::adapter_width_m).
//
// Structured meshes are made in-house (gmsh's Debian package pulls OpenCASCADE). Rings are
// annuli (fe::MakeAnnulus) with uniform node spacing along the raceways; rollers are O-grids
// (square core + radial layers) with uniform rim spacing; a spall is cut out of the top block of
// the O-grid in the spall's frame: its walls and flat bottom are exact (nodes on them).
//
// Names: parts "outer_ring", "inner_ring", "cage", "roller<j>", "adapter". Curves (mesh.h
// convention, body on the left): "outer_ring.raceway", "outer_ring.outside", "inner_ring.raceway",
// "inner_ring.bore", "roller<j>.surface" (closed, follows the spall), "cage.web<k>" (closed web
// outline), "cage.pocket<j>.leading" / "cage.pocket<j>.trailing" (the two straight walls of pocket
// j, at larger / smaller angle; they belong to different webs, so a pocket is two open curves),
// "adapter.seat". Node sets: "<part>.all", "roller<j>.center", "roller<j>.spall" (rim nodes of
// the notch), "roller<j>.spall_bottom", "cage.pocket<j>" (both walls), "adapter.bottom".
#pragma once

#include <string>
#include <vector>

#include "sim/bearing/scene.h"
#include "sim/fe/mesh.h"

namespace spallkit::sim {

struct BearingMesh {
  fe::Mesh mesh;
  std::vector<double> roller_angles_rad;  // phi_j, centre of roller j on the pitch circle
  double outer_raceway_radius_m = 0.0;    // after the clearance shift
  double inner_raceway_radius_m = 0.0;
  double roller_radius_m = 0.0;
  double pitch_radius_m = 0.0;
  double adapter_width_m = 0.0;  // as meshed (snapped to the seat node spacing)
};

// Builds the mesh. Throws InputError (naming the scene key) when the mesh size cannot resolve
// the geometry (e.g. a spall narrower than 1.5 elements).
BearingMesh MeshBearing(const Scene& scene);

// The housing only, for the hybrid model (scene model.fidelity = "hybrid", sim/bearing/
// hybrid_rollers.h): parts "outer_ring" and "adapter", meshed exactly as in MeshBearing (same
// names, curves, node sets, clearance shift); rollers, cage and inner ring are rigid bodies with
// exact profiles there, not meshed. The other fields of BearingMesh are filled as in MeshBearing.
BearingMesh MeshBearingHousing(const Scene& scene);

// Element quality of one part: interior angles, aspect ratio (longest / shortest edge), skew
// (largest |interior angle - 90 deg|), counts and area.
struct PartQuality {
  std::string part;
  int elements = 0;
  int nodes = 0;
  double area_m2 = 0.0;
  double min_angle_deg = 180.0;
  double max_angle_deg = 0.0;
  double max_aspect_ratio = 0.0;
  double max_skew_deg = 0.0;
  double min_element_area_m2 = 0.0;
};

struct MeshQualityReport {
  std::vector<PartQuality> parts;
  int total_elements = 0;
  int total_nodes = 0;
  std::string Report() const;  // one line per part plus totals
  // Parts whose names differ only in a trailing number (roller0 .. roller12) merged into one
  // entry named "roller0..12": summed counts and area, worst angles, aspect ratio and skew. The
  // full model's 17 parts then print as 6 lines (spall simulate's model description).
  MeshQualityReport Merged() const;
};

MeshQualityReport MeasureMeshQuality(const fe::Mesh& mesh);

}  // namespace spallkit::sim
