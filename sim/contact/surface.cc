#include "sim/contact/surface.h"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <unordered_map>

#include "core/error.h"

namespace spallkit::sim::contact {

double ContactSurface::MeanSegmentLength(const double* x, const double* y) const {
  if (segment_a.empty()) return 0.0;
  double sum = 0.0;
  for (int s = 0; s < num_segments(); ++s) {
    const int a = nodes[segment_a[s]], b = nodes[segment_b[s]];
    sum += std::hypot(x[b] - x[a], y[b] - y[a]);
  }
  return sum / num_segments();
}

ContactSurface MakeSurfaceFromChain(const std::string& name,
                                    const std::vector<int>& nodes,
                                    bool closed) {
  const int n = static_cast<int>(nodes.size());
  if (n < 1 || (closed && n < 3)) {
    throw InputError("contact surface '" + name + "': needs at least " +
                     std::string(closed ? "3" : "1") + " nodes, got " + std::to_string(n));
  }
  ContactSurface s;
  s.name = name;
  s.closed = closed;
  s.nodes = nodes;
  s.segment_before.assign(n, -1);
  s.segment_after.assign(n, -1);
  const int num_segments = closed ? n : n - 1;
  for (int i = 0; i < num_segments; ++i) {
    const int j = (i + 1) % n;
    s.segment_a.push_back(i);
    s.segment_b.push_back(j);
    s.segment_after[i] = i;
    s.segment_before[j] = i;
  }
  return s;
}

ContactSurface MakeSurface(const fe::Mesh& mesh,
                           const std::string& curve_name,
                           const std::vector<double>& bulk_modulus,
                           double thickness) {
  const auto it = mesh.curves.find(curve_name);
  if (it == mesh.curves.end()) {
    throw InputError("contact surface '" + curve_name + "': no such boundary curve in the mesh");
  }
  if (bulk_modulus.size() != 1 && static_cast<int>(bulk_modulus.size()) != mesh.num_parts()) {
    throw InputError("contact surface '" + curve_name + "': expected 1 or " +
                     std::to_string(mesh.num_parts()) + " bulk moduli, got " +
                     std::to_string(bulk_modulus.size()));
  }
  if (!(thickness > 0.0)) {
    throw InputError("contact surface '" + curve_name + "': thickness must be > 0");
  }
  for (int node : it->second.nodes) {
    if (node < 0 || node >= mesh.num_nodes()) {
      throw InputError("contact surface '" + curve_name + "': node id " + std::to_string(node) +
                       " out of range");
    }
  }
  ContactSurface s = MakeSurfaceFromChain(curve_name, it->second.nodes, it->second.closed);

  // Directed quad edges (a -> b, counter-clockwise) touching the surface, keyed by (a, b).
  std::vector<char> on_surface(mesh.num_nodes(), 0);
  for (int node : s.nodes) on_surface[node] = 1;
  std::unordered_map<std::uint64_t, int> edge_to_element;
  auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
           static_cast<std::uint32_t>(b);
  };
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto& q = mesh.quads[e];
    for (int k = 0; k < 4; ++k) {
      const int a = q[k], b = q[(k + 1) % 4];
      if (on_surface[a] && on_surface[b]) edge_to_element.emplace(key(a, b), e);
    }
  }
  s.bulk_stiffness.resize(s.num_segments());
  for (int seg = 0; seg < s.num_segments(); ++seg) {
    const int a = s.nodes[s.segment_a[seg]], b = s.nodes[s.segment_b[seg]];
    const auto found = edge_to_element.find(key(a, b));
    if (found == edge_to_element.end()) {
      std::ostringstream os;
      os << "contact surface '" << curve_name << "': segment " << seg << " (nodes " << a << " -> "
         << b << ") is not a counter-clockwise quad edge; the curve must keep the body on its left";
      throw InputError(os.str());
    }
    const auto& q = mesh.quads[found->second];
    const double area = 0.5 * ((mesh.x[q[2]] - mesh.x[q[0]]) * (mesh.y[q[3]] - mesh.y[q[1]]) +
                               (mesh.x[q[1]] - mesh.x[q[3]]) * (mesh.y[q[2]] - mesh.y[q[0]]));
    const double length = std::hypot(mesh.x[b] - mesh.x[a], mesh.y[b] - mesh.y[a]);
    const int part = mesh.element_part.empty() ? 0 : mesh.element_part[found->second];
    const double k_bulk = bulk_modulus.size() == 1 ? bulk_modulus[0] : bulk_modulus[part];
    if (!(area > 0.0)) {
      throw InputError("contact surface '" + curve_name + "': element " +
                       std::to_string(found->second) + " has non-positive area");
    }
    s.bulk_stiffness[seg] = k_bulk * length * length / area * thickness;
  }
  return s;
}

int MarkCircularArcs(ContactSurface* surface,
                     const double* x,
                     const double* y,
                     const Circle& circle,
                     double tolerance) {
  const double cx = circle.cx, cy = circle.cy, radius = circle.radius;
  surface->segment_curvature.resize(surface->num_segments(), 0.0);
  int arcs = 0;
  for (int k = 0; k < surface->num_segments(); ++k) {
    const int a = surface->nodes[surface->segment_a[k]], b = surface->nodes[surface->segment_b[k]];
    if (std::abs(std::hypot(x[a] - cx, y[a] - cy) - radius) > tolerance ||
        std::abs(std::hypot(x[b] - cx, y[b] - cy) - radius) > tolerance)
      continue;
    // Outward normal (dy, -dx): the centre lies behind it (body side) for a convex arc.
    const double nx = y[b] - y[a], ny = -(x[b] - x[a]);
    const double behind = (cx - 0.5 * (x[a] + x[b])) * nx + (cy - 0.5 * (y[a] + y[b])) * ny;
    surface->segment_curvature[k] = behind < 0.0 ? 1.0 / radius : -1.0 / radius;
    ++arcs;
  }
  return arcs;
}

}  // namespace spallkit::sim::contact
