#include "sim/fe/mesh_primitives.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <sstream>

#include "core/constants.h"
#include "core/error.h"

namespace spallkit::sim::fe {
namespace {

// n + 1 positions in [0, 1]; cell k has size proportional to r^k with r^(n-1) = ratio.
std::vector<double> GradedPositions(int n, double ratio) {
  std::vector<double> s(n + 1, 0.0);
  const double r = (n > 1) ? std::pow(ratio, 1.0 / (n - 1)) : 1.0;
  double size = 1.0, total = 0.0;
  for (int k = 0; k < n; ++k) {
    total += size;
    s[k + 1] = total;
    size *= r;
  }
  for (double& v : s) v /= total;
  s[n] = 1.0;
  return s;
}

void Require(bool ok, const std::string& what) {
  if (!ok) throw InputError(what);
}

Mesh OnePart(const std::string& part) {
  Require(!part.empty(), "mesh: empty part name");
  Mesh m;
  m.part_names.push_back(part);
  return m;
}

void AddQuad(Mesh& m, int a, int b, int c, int d) {
  m.quads.push_back({a, b, c, d});
  m.element_part.push_back(0);
}

void AddAllSet(Mesh& m, const std::string& part) {
  std::vector<int> all(m.num_nodes());
  std::iota(all.begin(), all.end(), 0);
  m.node_sets[part + ".all"] = std::move(all);
}

}  // namespace

double QuadArea(const Mesh& m, int e) {
  const auto& q = m.quads[e];
  const double x1 = m.x[q[0]], x2 = m.x[q[1]], x3 = m.x[q[2]], x4 = m.x[q[3]];
  const double y1 = m.y[q[0]], y2 = m.y[q[1]], y3 = m.y[q[2]], y4 = m.y[q[3]];
  return 0.5 * ((x3 - x1) * (y4 - y2) + (x2 - x4) * (y3 - y1));
}

Mesh MakeRectangle(const std::string& part, const RectangleSpec& s) {
  Require(s.nx >= 1 && s.ny >= 1, "rectangle '" + part + "': nx and ny must be >= 1");
  Require(s.width > 0 && s.height > 0, "rectangle '" + part + "': width and height must be > 0");
  Require(s.grade_ratio > 0, "rectangle '" + part + "': grade_ratio must be > 0");
  Mesh m = OnePart(part);
  // Grading towards an edge: sizes grow geometrically away from it.
  std::vector<double> sx = GradedPositions(s.nx, 1.0), sy = GradedPositions(s.ny, 1.0);
  switch (s.grade_edge) {
    case GradeEdge::kLeft:
      sx = GradedPositions(s.nx, s.grade_ratio);
      break;
    case GradeEdge::kRight:
      sx = GradedPositions(s.nx, s.grade_ratio);
      std::reverse(sx.begin(), sx.end());
      for (double& v : sx) v = 1.0 - v;
      break;
    case GradeEdge::kBottom:
      sy = GradedPositions(s.ny, s.grade_ratio);
      break;
    case GradeEdge::kTop:
      sy = GradedPositions(s.ny, s.grade_ratio);
      std::reverse(sy.begin(), sy.end());
      for (double& v : sy) v = 1.0 - v;
      break;
    case GradeEdge::kNone:
      break;
  }
  const int nxp = s.nx + 1;
  for (int j = 0; j <= s.ny; ++j)
    for (int i = 0; i <= s.nx; ++i) {
      m.x.push_back(s.x0 + s.width * sx[i]);
      m.y.push_back(s.y0 + s.height * sy[j]);
    }
  auto id = [&](int i, int j) { return j * nxp + i; };
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i)
      AddQuad(m, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));

  std::vector<int> bottom, right, top, left;
  for (int i = 0; i <= s.nx; ++i) bottom.push_back(id(i, 0));
  for (int j = 0; j <= s.ny; ++j) right.push_back(id(s.nx, j));
  for (int i = s.nx; i >= 0; --i) top.push_back(id(i, s.ny));
  for (int j = s.ny; j >= 0; --j) left.push_back(id(0, j));
  std::vector<int> outer;
  for (const auto* edge : {&bottom, &right, &top, &left})
    outer.insert(outer.end(), edge->begin(), edge->end() - 1);  // drop the shared corner
  m.curves[part + ".outer"] = {outer, true};
  m.curves[part + ".bottom"] = {bottom, false};
  m.curves[part + ".right"] = {right, false};
  m.curves[part + ".top"] = {top, false};
  m.curves[part + ".left"] = {left, false};
  auto sorted = [](std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  m.node_sets[part + ".bottom"] = sorted(bottom);
  m.node_sets[part + ".right"] = sorted(right);
  m.node_sets[part + ".top"] = sorted(top);
  m.node_sets[part + ".left"] = sorted(left);
  AddAllSet(m, part);
  return m;
}

Mesh MakeAnnulus(const std::string& part, const AnnulusSpec& s) {
  Require(s.n_theta >= 3 && s.n_radial >= 1,
          "annulus '" + part + "': need n_theta >= 3, n_radial >= 1");
  Require(s.inner_radius > 0 && s.outer_radius > s.inner_radius,
          "annulus '" + part + "': need 0 < inner_radius < outer_radius");
  Require(s.radial_ratio > 0, "annulus '" + part + "': radial_ratio must be > 0");
  Mesh m = OnePart(part);
  const std::vector<double> sr = GradedPositions(s.n_radial, s.radial_ratio);
  for (int j = 0; j <= s.n_radial; ++j) {
    const double r = s.inner_radius + (s.outer_radius - s.inner_radius) * sr[j];
    for (int i = 0; i < s.n_theta; ++i) {
      const double th = s.theta0 + 2.0 * kPi * i / s.n_theta;
      m.x.push_back(s.cx + r * std::cos(th));
      m.y.push_back(s.cy + r * std::sin(th));
    }
  }
  auto id = [&](int i, int j) { return j * s.n_theta + (i % s.n_theta); };
  // (r, theta) -> (x, y) preserves orientation, so (r_j, th_i), (r_j+1, th_i), ... is CCW.
  for (int j = 0; j < s.n_radial; ++j)
    for (int i = 0; i < s.n_theta; ++i)
      AddQuad(m, id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j));
  std::vector<int> inner, outer;
  for (int i = 0; i < s.n_theta; ++i) outer.push_back(id(i, s.n_radial));
  for (int i = 0; i < s.n_theta; ++i)
    inner.push_back(id((s.n_theta - i) % s.n_theta, 0));  // clockwise
  m.curves[part + ".outer"] = {outer, true};
  m.curves[part + ".inner"] = {inner, true};
  std::vector<int> inner_set = inner;
  std::sort(inner_set.begin(), inner_set.end());
  m.node_sets[part + ".inner"] = inner_set;
  m.node_sets[part + ".outer"] = outer;
  AddAllSet(m, part);
  return m;
}

Mesh MakeDisc(const std::string& part, const DiscSpec& s) {
  Require(s.n_core >= 1 && s.n_radial >= 1, "disc '" + part + "': need n_core >= 1, n_radial >= 1");
  Require(s.radius > 0, "disc '" + part + "': radius must be > 0");
  Require(s.core_fraction > 0 && s.core_fraction < 1.0 / std::sqrt(2.0),
          "disc '" + part + "': core_fraction must be in (0, 0.707)");
  Require(s.radial_ratio > 0, "disc '" + part + "': radial_ratio must be > 0");
  Mesh m = OnePart(part);
  const int n = s.n_core, nt = 4 * n;
  const double a = s.core_fraction * s.radius;
  auto core_id = [&](int i, int j) { return j * (n + 1) + i; };
  // Local frame (u, v): the core square is axis-aligned with half-width a and its corner
  // (a, -a) sits at local angle -pi/4; rotating the frame by theta0 + pi/4 puts that corner,
  // and rim node 0, at global angle theta0. The core corners point at rim nodes 0, n, 2n, 3n.
  const double c0 = std::cos(s.theta0 + kPi / 4.0), s0 = std::sin(s.theta0 + kPi / 4.0);
  auto place = [&](double u, double v) {
    m.x.push_back(s.cx + c0 * u - s0 * v);
    m.y.push_back(s.cy + s0 * u + c0 * v);
  };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) place(-a + 2.0 * a * i / n, -a + 2.0 * a * j / n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      AddQuad(m, core_id(i, j), core_id(i + 1, j), core_id(i + 1, j + 1), core_id(i, j + 1));

  // Square perimeter, counter-clockwise from corner (a, -a) (local angle -pi/4): perimeter
  // index k in [0, 4n) -> core node id, and its local coordinates.
  std::vector<int> perim(nt);
  std::vector<double> pu(nt), pv(nt);
  for (int k = 0; k < nt; ++k) {
    const int side = k / n, t = k % n;
    int i = 0, j = 0;
    switch (side) {
      case 0:
        i = n;
        j = t;
        break;  // right side, upwards
      case 1:
        i = n - t;
        j = n;
        break;  // top side, leftwards
      case 2:
        i = 0;
        j = n - t;
        break;  // left side, downwards
      default:
        i = t;
        j = 0;
        break;  // bottom side, rightwards
    }
    perim[k] = core_id(i, j);
    pu[k] = -a + 2.0 * a * i / n;
    pv[k] = -a + 2.0 * a * j / n;
  }
  // Ring layers: blend from the square perimeter (layer 0) to the circle (layer n_radial),
  // rim node k at local angle -pi/4 + 2 pi k / nt (uniform spacing).
  const std::vector<double> sr_pos = GradedPositions(s.n_radial, s.radial_ratio);
  std::vector<int> prev = perim;
  for (int layer = 1; layer <= s.n_radial; ++layer) {
    const double w = sr_pos[layer];
    std::vector<int> cur(nt);
    for (int k = 0; k < nt; ++k) {
      const double th = -kPi / 4.0 + 2.0 * kPi * k / nt;
      const double cu = s.radius * std::cos(th), cv = s.radius * std::sin(th);
      place((1.0 - w) * pu[k] + w * cu, (1.0 - w) * pv[k] + w * cv);
      cur[k] = m.num_nodes() - 1;
    }
    // Outwards first, then along the counter-clockwise perimeter: a CCW quad.
    for (int k = 0; k < nt; ++k) {
      const int k1 = (k + 1) % nt;
      AddQuad(m, prev[k], cur[k], cur[k1], prev[k1]);
    }
    prev = cur;
  }
  m.curves[part + ".outer"] = {prev, true};
  m.node_sets[part + ".outer"] = prev;
  // Centre: the core node nearest (cx, cy).
  int centre = 0;
  double best = 1e300;
  for (int id = 0; id < (n + 1) * (n + 1); ++id) {
    const double d = std::hypot(m.x[id] - s.cx, m.y[id] - s.cy);
    if (d < best) best = d, centre = id;
  }
  m.node_sets[part + ".center"] = {centre};
  AddAllSet(m, part);
  return m;
}

Mesh MergeMeshes(const std::vector<Mesh>& meshes) {
  Mesh out;
  for (const Mesh& m : meshes) {
    const int node_offset = out.num_nodes();
    const int part_offset = out.num_parts();
    for (const auto& name : m.part_names) {
      Require(std::find(out.part_names.begin(), out.part_names.end(), name) == out.part_names.end(),
              "merge meshes: part '" + name + "' defined twice");
      out.part_names.push_back(name);
    }
    out.x.insert(out.x.end(), m.x.begin(), m.x.end());
    out.y.insert(out.y.end(), m.y.begin(), m.y.end());
    for (int e = 0; e < m.num_elements(); ++e) {
      auto q = m.quads[e];
      for (int& id : q) id += node_offset;
      out.quads.push_back(q);
      out.element_part.push_back(m.element_part[e] + part_offset);
    }
    for (const auto& [name, set] : m.node_sets) {
      Require(!out.node_sets.count(name), "merge meshes: node set '" + name + "' defined twice");
      auto& dst = out.node_sets[name];
      for (int id : set) dst.push_back(id + node_offset);
    }
    for (const auto& [name, curve] : m.curves) {
      Require(!out.curves.count(name), "merge meshes: curve '" + name + "' defined twice");
      BoundaryCurve c = curve;
      for (int& id : c.nodes) id += node_offset;
      out.curves[name] = std::move(c);
    }
  }
  return out;
}

void ValidateMesh(const Mesh& m) {
  const int nn = m.num_nodes();
  Require(m.y.size() == m.x.size(), "mesh: x and y have different lengths");
  Require(m.element_part.size() == m.quads.size(),
          "mesh: element_part must have one entry per quad");
  for (int e = 0; e < m.num_elements(); ++e) {
    for (int id : m.quads[e]) {
      if (id < 0 || id >= nn) {
        std::ostringstream os;
        os << "mesh: quad " << e << " refers to node " << id << " (have " << nn << " nodes)";
        throw InputError(os.str());
      }
    }
    if (m.element_part[e] < 0 || m.element_part[e] >= m.num_parts()) {
      std::ostringstream os;
      os << "mesh: quad " << e << " has part index " << m.element_part[e] << " (have "
         << m.num_parts() << " parts)";
      throw InputError(os.str());
    }
    if (!(QuadArea(m, e) > 0.0)) {
      std::ostringstream os;
      os << "mesh: quad " << e << " has non-positive area " << QuadArea(m, e)
         << " (nodes must be counter-clockwise)";
      throw InputError(os.str());
    }
  }
  for (const auto& [name, set] : m.node_sets)
    for (int id : set)
      Require(id >= 0 && id < nn, "mesh: node set '" + name + "' has a node id out of range");
  for (const auto& [name, c] : m.curves)
    for (int id : c.nodes)
      Require(id >= 0 && id < nn, "mesh: curve '" + name + "' has a node id out of range");
}

std::vector<int> ReorderForLocality(Mesh* mesh) {
  Mesh& m = *mesh;
  const int nn = m.num_nodes(), ne = m.num_elements();
  // Node adjacency through shared elements (CSR).
  std::vector<std::vector<int>> adj(nn);
  for (const auto& q : m.quads)
    for (int a : q)
      for (int b : q)
        if (a != b) adj[a].push_back(b);
  std::vector<int> degree(nn);
  for (int i = 0; i < nn; ++i) {
    std::sort(adj[i].begin(), adj[i].end());
    adj[i].erase(std::unique(adj[i].begin(), adj[i].end()), adj[i].end());
    degree[i] = static_cast<int>(adj[i].size());
  }
  // Cuthill-McKee from a minimum-degree node of each connected component, then reverse.
  std::vector<int> order;
  order.reserve(nn);
  std::vector<char> seen(nn, 0);
  std::vector<int> by_degree(nn);
  std::iota(by_degree.begin(), by_degree.end(), 0);
  std::stable_sort(
      by_degree.begin(), by_degree.end(), [&](int a, int b) { return degree[a] < degree[b]; });
  for (int start : by_degree) {
    if (seen[start]) continue;
    std::queue<int> q;
    q.push(start);
    seen[start] = 1;
    while (!q.empty()) {
      const int v = q.front();
      q.pop();
      order.push_back(v);
      std::vector<int> next;
      for (int w : adj[v])
        if (!seen[w]) next.push_back(w), seen[w] = 1;
      std::stable_sort(
          next.begin(), next.end(), [&](int a, int b) { return degree[a] < degree[b]; });
      for (int w : next) q.push(w);
    }
  }
  std::reverse(order.begin(), order.end());
  std::vector<int> new_id(nn);
  for (int k = 0; k < nn; ++k) new_id[order[k]] = k;

  Mesh out;
  out.part_names = m.part_names;
  out.x.resize(nn);
  out.y.resize(nn);
  for (int i = 0; i < nn; ++i) out.x[new_id[i]] = m.x[i], out.y[new_id[i]] = m.y[i];
  std::vector<int> eorder(ne);
  std::iota(eorder.begin(), eorder.end(), 0);
  auto key = [&](int e) {
    int k = nn;
    for (int id : m.quads[e]) k = std::min(k, new_id[id]);
    return k;
  };
  std::stable_sort(eorder.begin(), eorder.end(), [&](int a, int b) { return key(a) < key(b); });
  for (int e : eorder) {
    auto q = m.quads[e];
    for (int& id : q) id = new_id[id];
    out.quads.push_back(q);
    out.element_part.push_back(m.element_part[e]);
  }
  for (const auto& [name, set] : m.node_sets) {
    auto& dst = out.node_sets[name];
    for (int id : set) dst.push_back(new_id[id]);
    std::sort(dst.begin(), dst.end());
  }
  for (const auto& [name, c] : m.curves) {
    BoundaryCurve nc = c;
    for (int& id : nc.nodes) id = new_id[id];
    out.curves[name] = std::move(nc);
  }
  m = std::move(out);
  return new_id;
}

}  // namespace spallkit::sim::fe
