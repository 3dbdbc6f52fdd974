#include "sim/bearing/mesher.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/constants.h"
#include "core/error.h"
#include "sim/fe/mesh_primitives.h"

namespace spallkit::sim {
namespace {

struct Vec {
  double x = 0, y = 0;
};
Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y}; }
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y}; }
Vec operator*(double s, Vec a) { return {s * a.x, s * a.y}; }
Vec Lerp(Vec a, Vec b, double t) { return a + t * (b - a); }

// Builds a one-part mesh from node positions and quads, fixing quad orientation to CCW.
class PartBuilder {
 public:
  explicit PartBuilder(std::string part) { mesh_.part_names.push_back(std::move(part)); }
  int AddNode(Vec p) {
    mesh_.x.push_back(p.x);
    mesh_.y.push_back(p.y);
    return mesh_.num_nodes() - 1;
  }
  void AddQuad(int a, int b, int c, int d) {
    std::array<int, 4> q{a, b, c, d};
    double area2 = 0;
    for (int i = 0; i < 4; ++i) {
      const int p = q[i], n = q[(i + 1) % 4];
      area2 += mesh_.x[p] * mesh_.y[n] - mesh_.x[n] * mesh_.y[p];
    }
    if (area2 < 0) std::swap(q[1], q[3]);
    mesh_.quads.push_back(q);
    mesh_.element_part.push_back(0);
  }
  fe::Mesh& mesh() { return mesh_; }
  fe::Mesh Take() {
    std::vector<int> all(mesh_.num_nodes());
    for (int i = 0; i < mesh_.num_nodes(); ++i) all[i] = i;
    mesh_.node_sets[mesh_.part_names[0] + ".all"] = all;
    return std::move(mesh_);
  }

 private:
  fe::Mesh mesh_;
};

// Renames a curve / node set of a primitive.
void Rename(fe::Mesh* m, const std::string& from, const std::string& to) {
  if (auto it = m->curves.find(from); it != m->curves.end()) {
    m->curves[to] = it->second;
    m->curves.erase(from);
  }
  if (auto it = m->node_sets.find(from); it != m->node_sets.end()) {
    m->node_sets[to] = it->second;
    m->node_sets.erase(from);
  }
}

// O-grid layout of a roller of radius r with 4n rim nodes (rim spacing s = 2 pi r / 4n, the
// contact size). The explicit step is set by the model's smallest element L_e = A / longest
// diagonal; a straight-sided core of half-width 0.4 r (layers of at most 1.5 s) has core cells
// of 0.5 s and 45/135 deg elements at the core corners (11.5 ns at 0.25 mm against 26-30 ns for
// the rings' raceway elements). So:
//  - the core is n x n quads inside a "rounded square" whose corners sit at kCoreCorner r
//    (half-width a = 0.59 r, core cells about 0.75 s); its four sides are circular arcs through
//    the corners, leaving them at kCoreBulge to the chord, so the three elements at a core corner
//    (a node where only three quads meet) get about 120 deg each instead of 90/135/135; the
//    interior is the Coons patch of the four arcs;
//  - m layers from the core boundary to the rim, m = round(gap / s) with gap the distance from
//    the middle of a core side to the rim, so layer cells are about s x s.
// At 0.25 mm the roller's step becomes 15.9 ns (the corner elements: a quad with 120 deg
// angles has L_e = side / 2). A roller whose spall is too deep for these layers (bottom less
// than half a layer above the core, or an angle below kMinNotchAngleDeg next to the walls) falls
// back to the straight-sided core, with its smaller step.
struct RollerGrid {
  int n = 0, m = 0;
  double a = 0.0, bulge = 0.0;  // core half-width at the corners, side tangent angle (rad)
};

constexpr double kCoreCorner = 0.83;               // core corners at this fraction of r
constexpr double kCoreBulge = 15.0 * kPi / 180.0;  // side arcs' angle to the chord at a corner
constexpr double kMinNotchAngleDeg = 25.0;  // smallest interior angle next to a spall's walls

// `legacy`: the straight-sided core of half-width 0.4 r, used only for a roller
// whose spall is too deep for the layers of the default one (MakeRoller retries with it).
RollerGrid MakeRollerGrid(double r, double contact_size, bool legacy) {
  RollerGrid g;
  g.n = std::max(4, static_cast<int>(std::lround(2.0 * kPi * r / (4.0 * contact_size))));
  if (g.n % 2) ++g.n;
  g.a = legacy ? 0.4 * r : kCoreCorner * r / std::sqrt(2.0);
  g.bulge = legacy ? 0.0 : kCoreBulge;
  const double s = 2.0 * kPi * r / (4 * g.n);
  const double side_mid = g.a * (1.0 + std::tan(0.5 * g.bulge));
  g.m = std::max(legacy ? 3 : 2, static_cast<int>(std::lround((r - side_mid) / s)));
  return g;
}

// A roller as an O-grid, optionally with a rectangular spall; see mesher.h and RollerGrid.
fe::Mesh MakeRoller(const std::string& part,
                    Vec centre,
                    double r,
                    double spall_angle,  // global angle of the spall centre (or orientation)
                    const Defect* defect,
                    double contact_size,
                    const std::string& defect_key,
                    bool legacy = false) {
  const RollerGrid grid = MakeRollerGrid(r, contact_size, legacy);
  const int n = grid.n, m = grid.m;
  const double a = grid.a;
  const int ncore = (n + 1) * (n + 1);
  const int nper = 4 * n;
  auto perim_pq = [&](int k, int* p, int* q) {
    const int s = k / n, u = k % n;
    if (s == 0)
      *p = n, *q = u;
    else if (s == 1)
      *p = n - u, *q = n;
    else if (s == 2)
      *p = 0, *q = n - u;
    else
      *p = u, *q = 0;
  };
  // Core side arcs, parameter u in [0, 1] uniform in arc length. Side 0 (right, p = n) runs
  // up, side 1 (top, q = n) left, 2 (left) down, 3 (bottom) right: the perimeter order.
  const double rad = grid.bulge > 0 ? a / std::sin(grid.bulge) : 0.0;  // arc radius (chord 2a)
  auto side_pt = [&](int side, double u) {
    const double psi = grid.bulge * (2.0 * u - 1.0);
    const double along = grid.bulge > 0 ? rad * std::sin(psi) : a * (2.0 * u - 1.0);
    const double out = grid.bulge > 0 ? a + rad * (std::cos(psi) - std::cos(grid.bulge)) : a;
    const double ang = kPi / 2 * side;  // outward normal of the side
    const double nx = std::cos(ang), ny = std::sin(ang);
    return Vec{out * nx - along * ny, out * ny + along * nx};
  };
  // Coons patch in (p, q): bottom(u) = side 3 at u, top(u) = side 1 at 1 - u, left(v) = side 2
  // at 1 - v, right(v) = side 0 at v.
  auto core_pt = [&](int p, int q) {
    const double u = double(p) / n, v = double(q) / n;
    const Vec bot = side_pt(3, u), top = side_pt(1, 1.0 - u);
    const Vec left = side_pt(2, 1.0 - v), right = side_pt(0, v);
    const Vec c00{-a, -a}, c10{a, -a}, c01{-a, a}, c11{a, a};
    return (1 - v) * bot + v * top + (1 - u) * left + u * right -
           ((1 - u) * (1 - v) * c00 + u * (1 - v) * c10 + (1 - u) * v * c01 + u * v * c11);
  };
  std::vector<Vec> pos(ncore + nper * m);
  std::vector<bool> alive(pos.size(), true);
  for (int q = 0; q <= n; ++q)
    for (int p = 0; p <= n; ++p) pos[q * (n + 1) + p] = core_pt(p, q);
  auto id = [&](int k, int j) {
    k = ((k % nper) + nper) % nper;
    if (j == 0) {
      int p, q;
      perim_pq(k, &p, &q);
      return q * (n + 1) + p;
    }
    return ncore + (j - 1) * nper + k;
  };
  for (int k = 0; k < nper; ++k) {
    const double phi = -kPi / 4 + 2 * kPi * k / nper;
    const Vec rim{r * std::cos(phi), r * std::sin(phi)};
    const Vec c = pos[id(k, 0)];
    for (int j = 1; j <= m; ++j) pos[id(k, j)] = Lerp(c, rim, double(j) / m);
  }

  int k_r = -1, k_l = -1, j_star = -1;
  if (defect) {
    if (defect->UnresolvedBy(contact_size))
      throw InputError(defect_key +
                       ": spall narrower than 1.5 elements or shallower than one "
                       "(refine mesh.contact_size_mm)");
    const double hw = 0.5 * defect->width_m;
    const double y_b = r - defect->depth_m;
    const double y_m = std::sqrt(r * r - hw * hw);
    double best_r = 1e9, best_l = 1e9;
    for (int k = n; k <= 2 * n; ++k) {
      const double xt = r * std::cos(-kPi / 4 + 2 * kPi * k / nper);
      if (std::abs(xt - hw) < best_r) best_r = std::abs(xt - hw), k_r = k;
      if (std::abs(xt + hw) < best_l) best_l = std::abs(xt + hw), k_l = k;
    }
    if (k_l - k_r < 2) {
      if (k_r > n + 1)
        --k_r;
      else
        ++k_l;
    }
    // The bottom replaces layer j_star of the notched columns; it must lie at least half a
    // layer above the core, else this roller gets a smaller core (more, thinner layers).
    double y_top = -r;
    for (int k = k_r; k <= k_l; ++k) y_top = std::max(y_top, pos[id(k, 0)].y);
    const double layer = (r - y_top) / m;
    j_star = static_cast<int>(std::lround((y_b - y_top) / layer));
    const bool columns_ok = k_r > n && k_l < 2 * n && k_l - k_r >= 2;
    const bool depth_ok = y_b - y_top >= 0.5 * layer && j_star >= 1 && j_star <= m - 1;
    if (columns_ok && !depth_ok && !legacy)
      return MakeRoller(part, centre, r, spall_angle, defect, contact_size, defect_key, true);
    if (!columns_ok || !depth_ok)
      throw InputError(defect_key + ": spall " + std::to_string(defect->width_m * 1e3) + " x " +
                       std::to_string(defect->depth_m * 1e3) +
                       " mm cannot be resolved by this mesh (refine mesh.contact_size_mm or "
                       "mesh.size_mm)");
    for (int k = k_r; k <= k_l; ++k) {
      const double xb = hw - defect->width_m * double(k - k_r) / (k_l - k_r);
      const Vec bottom{xb, y_b};
      const Vec c = pos[id(k, 0)];
      for (int j = 1; j < j_star; ++j) pos[id(k, j)] = Lerp(c, bottom, double(j) / j_star);
      pos[id(k, j_star)] = bottom;
      for (int j = j_star + 1; j <= m; ++j) {
        if (k == k_r || k == k_l) {
          const double x = (k == k_r) ? hw : -hw;
          pos[id(k, j)] = {x, y_b + (y_m - y_b) * double(j - j_star) / (m - j_star)};
        } else {
          alive[id(k, j)] = false;
        }
      }
    }
    // Under a deep spall the wall columns, moved onto x = +-w/2, can come close to their
    // neighbours, whose rays converge on the core: if a layer element next to the notch gets an
    // interior angle below kMinNotchAngleDeg, this roller falls back to the legacy layout.
    double min_cos_margin = 1.0;  // smallest sin of an interior angle, as a validity measure
    for (int k = k_r - 1; k <= k_l; ++k)
      for (int j = 0; j < m; ++j) {
        if (k >= k_r && k < k_l && j >= j_star) continue;
        const Vec c[4] = {
            pos[id(k, j)], pos[id(k + 1, j)], pos[id(k + 1, j + 1)], pos[id(k, j + 1)]};
        for (int i = 0; i < 4; ++i) {
          const Vec u = c[(i + 3) % 4] - c[i], v = c[(i + 1) % 4] - c[i];
          const double cross = std::abs(u.x * v.y - u.y * v.x);
          min_cos_margin =
              std::min(min_cos_margin, cross / (std::hypot(u.x, u.y) * std::hypot(v.x, v.y)));
        }
      }
    if (min_cos_margin < std::sin(kMinNotchAngleDeg * kPi / 180.0) && !legacy)
      return MakeRoller(part, centre, r, spall_angle, defect, contact_size, defect_key, true);
  }

  // Global placement: rotate local +y onto spall_angle, translate to the centre.
  const double beta = spall_angle - kPi / 2;
  const double cb = std::cos(beta), sb = std::sin(beta);
  PartBuilder b(part);
  std::vector<int> new_id(pos.size(), -1);
  for (std::size_t i = 0; i < pos.size(); ++i) {
    if (!alive[i]) continue;
    const Vec p = pos[i];
    new_id[i] = b.AddNode({centre.x + cb * p.x - sb * p.y, centre.y + sb * p.x + cb * p.y});
  }
  auto nid = [&](int k, int j) { return new_id[id(k, j)]; };
  for (int q = 0; q < n; ++q)
    for (int p = 0; p < n; ++p)
      b.AddQuad(new_id[q * (n + 1) + p],
                new_id[q * (n + 1) + p + 1],
                new_id[(q + 1) * (n + 1) + p + 1],
                new_id[(q + 1) * (n + 1) + p]);
  for (int k = 0; k < nper; ++k)
    for (int j = 0; j < m; ++j) {
      if (defect && k >= k_r && k < k_l && j >= j_star) continue;  // inside the spall
      b.AddQuad(nid(k, j), nid(k + 1, j), nid(k + 1, j + 1), nid(k, j + 1));
    }

  std::vector<int> rim, notch, bottom;
  for (int k = 0; k < nper; ++k) {
    if (!defect || k < k_r || k > k_l) {
      rim.push_back(nid(k, m));
    } else if (k == k_r) {
      for (int j = m; j >= j_star; --j) rim.push_back(nid(k, j)), notch.push_back(nid(k, j));
      bottom.push_back(nid(k, j_star));
    } else if (k < k_l) {
      rim.push_back(nid(k, j_star));
      notch.push_back(nid(k, j_star));
      bottom.push_back(nid(k, j_star));
    } else {
      for (int j = j_star; j <= m; ++j) rim.push_back(nid(k, j)), notch.push_back(nid(k, j));
      bottom.push_back(nid(k, j_star));
    }
  }
  fe::Mesh mesh = b.Take();
  mesh.curves[part + ".surface"] = {rim, true};
  mesh.node_sets[part + ".surface"] = rim;
  mesh.node_sets[part + ".center"] = {new_id[(n / 2) * (n + 1) + n / 2]};
  if (defect) {
    mesh.node_sets[part + ".spall"] = notch;
    mesh.node_sets[part + ".spall_bottom"] = bottom;
  }
  return mesh;
}

// Cage webs between the pockets (Coons patches), see mesher.h.
fe::Mesh MakeCage(const SceneGeometry& g,
                  const std::vector<double>& phi,
                  double contact_size,
                  double size) {
  const int z = static_cast<int>(phi.size());
  const double rci = 0.5 * g.cage_inner_diameter_m, rco = 0.5 * g.cage_outer_diameter_m;
  const double c = 0.5 * (g.bearing.element_diameter_m + g.pocket_clearance_m);
  const int n_eta = std::max(2, static_cast<int>(std::lround((rco - rci) / contact_size)));
  PartBuilder b("cage");
  auto er = [](double t) { return Vec{std::cos(t), std::sin(t)}; };
  auto et = [](double t) { return Vec{-std::sin(t), std::cos(t)}; };
  std::vector<std::vector<int>> lead(z), trail(z);  // walls of pocket j, inner -> outer
  std::map<std::string, fe::BoundaryCurve> webs;
  for (int k = 0; k < z; ++k) {
    const double t0 = phi[k], t1 = phi[(k + 1) % z] + (k + 1 == z ? 2 * kPi : 0.0);
    auto wall = [&](double t, double side, double rad) {
      const double s = std::sqrt(rad * rad - c * c);
      return side * c * et(t) + s * er(t);
    };
    const Vec A = wall(t0, +1, rci), C = wall(t0, +1, rco);
    const Vec B = wall(t1, -1, rci), D = wall(t1, -1, rco);
    const double aA = std::atan2(A.y, A.x),
                 aB = aA + std::remainder(std::atan2(B.y, B.x) - aA, 2 * kPi);
    const double aC = std::atan2(C.y, C.x),
                 aD = aC + std::remainder(std::atan2(D.y, D.x) - aC, 2 * kPi);
    const double mid_width = 0.5 * (rci + rco) * (aB - aA + aD - aC) * 0.5;
    const int n_xi = std::max(2, static_cast<int>(std::lround(mid_width / size)));
    std::vector<std::vector<int>> ids(n_xi + 1, std::vector<int>(n_eta + 1));
    for (int i = 0; i <= n_xi; ++i) {
      const double xi = double(i) / n_xi;
      const Vec bot = rci * er(aA + xi * (aB - aA));
      const Vec top = rco * er(aC + xi * (aD - aC));
      for (int j = 0; j <= n_eta; ++j) {
        const double eta = double(j) / n_eta;
        const Vec left = Lerp(A, C, eta), right = Lerp(B, D, eta);
        const Vec p =
            (1 - xi) * left + xi * right + (1 - eta) * bot + eta * top -
            ((1 - xi) * (1 - eta) * A + xi * (1 - eta) * B + (1 - xi) * eta * C + xi * eta * D);
        ids[i][j] = b.AddNode(p);
      }
    }
    for (int i = 0; i < n_xi; ++i)
      for (int j = 0; j < n_eta; ++j)
        b.AddQuad(ids[i][j], ids[i + 1][j], ids[i + 1][j + 1], ids[i][j + 1]);
    fe::BoundaryCurve outline{{}, true};
    for (int j = 0; j < n_eta; ++j) outline.nodes.push_back(ids[0][j]);
    for (int i = 0; i < n_xi; ++i) outline.nodes.push_back(ids[i][n_eta]);
    for (int j = n_eta; j > 0; --j) outline.nodes.push_back(ids[n_xi][j]);
    for (int i = n_xi; i > 0; --i) outline.nodes.push_back(ids[i][0]);
    webs["cage.web" + std::to_string(k)] = outline;
    for (int j = 0; j <= n_eta; ++j) {
      lead[k].push_back(ids[0][j]);
      trail[(k + 1) % z].push_back(ids[n_xi][j]);
    }
  }
  fe::Mesh mesh = b.Take();
  for (auto& [name, curve] : webs) mesh.curves[name] = curve;
  for (int j = 0; j < z; ++j) {
    const std::string p = "cage.pocket" + std::to_string(j);
    mesh.curves[p + ".leading"] = {lead[j], false};  // walked outward: web on the left
    std::vector<int> tr(trail[j].rbegin(), trail[j].rend());
    mesh.curves[p + ".trailing"] = {tr, false};  // walked inward
    std::vector<int> both = lead[j];
    both.insert(both.end(), trail[j].begin(), trail[j].end());
    mesh.node_sets[p] = both;
  }
  return mesh;
}

constexpr double kAdapterFirstLayer = 3.0;

// Layer fractions from the seat (0) to the bottom (1) of the adapter: the first layer about
// `first` thick, each next one up to 15 % thicker, at most `largest`, scaled to fill `height`.
std::vector<double> AdapterLayers(double height, double first, double largest) {
  std::vector<double> cum{0.0};
  double h = first;
  while (cum.back() + 0.5 * h < height) {
    cum.push_back(cum.back() + h);
    h = std::min(h * 1.15, largest);
  }
  if (cum.size() < 3) cum = {0.0, 0.5 * height, height};
  for (auto& v : cum) v /= cum.back();
  return cum;
}

// `first_layer_scale`: the first layer's thickness in contact sizes. The seat meets the block's
// vertical sides at 90 deg - asin(width / 2 seat radius) (40 deg for the paper's 40 mm block on
// the 52 mm ring): the corner elements are skewed, and with a first layer of one contact size
// they set the time step (area / long diagonal 0.1 mm at 0.25 mm). Both meshes use 3
// (kAdapterFirstLayer): the full-FE adapter's step goes from 17.6 to 25.4 ns at 0.25 mm.
fe::Mesh MakeAdapter(const SceneGeometry& g,
                     int ring_nodes,
                     double seat_radius,
                     const Scene& scene,
                     double* width,
                     double first_layer_scale = 1.0) {
  const double dth = 2 * kPi / ring_nodes;
  const double half = std::asin(std::min(0.999, 0.5 * g.adapter_width_m / seat_radius));
  const int kk = std::max(1, static_cast<int>(std::lround(half / dth)));
  *width = 2 * seat_radius * std::sin(kk * dth);
  const double y_bottom = -seat_radius - g.adapter_height_m;
  const std::vector<double> t = AdapterLayers(
      g.adapter_height_m,
      first_layer_scale * scene.mesh.contact_size_m,
      first_layer_scale > 1.0
          ? std::max(scene.mesh.adapter_size_m, first_layer_scale * scene.mesh.contact_size_m)
          : scene.mesh.adapter_size_m);  // the full-FE mesh as before
  const int ny = static_cast<int>(t.size()) - 1;
  PartBuilder b("adapter");
  std::vector<std::vector<int>> ids(2 * kk + 1, std::vector<int>(ny + 1));
  for (int i = -kk; i <= kk; ++i) {
    const double th = -kPi / 2 + i * dth;
    const Vec seat{seat_radius * std::cos(th), seat_radius * std::sin(th)};
    const Vec bot{0.5 * *width * double(i) / kk, y_bottom};
    for (int j = 0; j <= ny; ++j) ids[i + kk][j] = b.AddNode(Lerp(seat, bot, t[j]));
  }
  for (int i = 0; i < 2 * kk; ++i)
    for (int j = 0; j < ny; ++j)
      b.AddQuad(ids[i][j], ids[i + 1][j], ids[i + 1][j + 1], ids[i][j + 1]);
  fe::Mesh mesh = b.Take();
  std::vector<int> seat, bottom;
  for (int i = 2 * kk; i >= 0; --i) seat.push_back(ids[i][0]);  // -x direction: body below
  for (int i = 0; i <= 2 * kk; ++i) bottom.push_back(ids[i][ny]);
  mesh.curves["adapter.seat"] = {seat, false};
  mesh.node_sets["adapter.seat"] = seat;
  mesh.node_sets["adapter.bottom"] = bottom;
  return mesh;
}

// Radii (raceways moved out/in by P_d/4 each, so a centred roller has P_d/2 of play in all) and
// roller angles (roller 0 on the load line at the bottom), shared by both meshers.
BearingMesh BearingLayout(const SceneGeometry& g) {
  BearingMesh out;
  const int z = g.bearing.num_elements;
  out.roller_radius_m = 0.5 * g.bearing.element_diameter_m;
  out.pitch_radius_m = 0.5 * g.bearing.pitch_diameter_m;
  out.outer_raceway_radius_m =
      0.5 * g.bearing.outer_raceway_diameter_m + 0.25 * g.diametral_clearance_m;
  out.inner_raceway_radius_m =
      0.5 * g.bearing.inner_raceway_diameter_m - 0.25 * g.diametral_clearance_m;
  for (int j = 0; j < z; ++j)
    out.roller_angles_rad.push_back(-kPi / 2 + g.roller_phase_rad + 2 * kPi * j / z);
  return out;
}

// A ring between radii r_in and r_out with its raceway on the inside (outer ring) or the outside
// (inner ring): node 0 at the bottom so the adapter seat matches, the contact size hc along the
// raceway and radial layers graded from hc at the raceway to the mesh size h. The raceway's curve
// is "<name>.raceway", the other face's "<name>.<other_face>".
fe::Mesh MakeRing(const std::string& name,
                  double r_in,
                  double r_out,
                  bool raceway_inside,
                  const std::string& other_face,
                  double h,
                  double hc,
                  fe::AnnulusSpec* spec) {
  fe::AnnulusSpec& s = *spec;
  s.inner_radius = r_in;
  s.outer_radius = r_out;
  s.n_theta = static_cast<int>(std::lround(2 * kPi * (raceway_inside ? r_in : r_out) / hc));
  s.n_radial = std::max(2, static_cast<int>(std::lround((r_out - r_in) / h)));
  s.theta0 = -kPi / 2;
  s.radial_ratio = raceway_inside ? h / hc : hc / h;
  fe::Mesh ring = fe::MakeAnnulus(name, s);
  const std::string raceway = raceway_inside ? ".inner" : ".outer";
  const std::string other = raceway_inside ? ".outer" : ".inner";
  Rename(&ring, name + raceway, name + ".raceway");
  Rename(&ring, name + other, name + "." + other_face);
  return ring;
}

fe::Mesh MakeOuterRing(
    const SceneGeometry& g, double raceway_radius, double h, double hc, fe::AnnulusSpec* spec) {
  return MakeRing("outer_ring",
                  raceway_radius,
                  0.5 * g.outer_ring_outer_diameter_m,
                  /*raceway_inside=*/true,
                  "outside",
                  h,
                  hc,
                  spec);
}

}  // namespace

BearingMesh MeshBearing(const Scene& scene) {
  const SceneGeometry& g = scene.geometry;
  const double h = scene.mesh.size_m, hc = scene.mesh.contact_size_m;
  BearingMesh out = BearingLayout(g);

  std::vector<fe::Mesh> parts;
  // Outer ring: raceway on the inside; node 0 at the bottom so the adapter seat matches.
  fe::AnnulusSpec os;
  fe::Mesh outer = MakeOuterRing(g, out.outer_raceway_radius_m, h, hc, &os);
  // Inner ring: raceway on the outside.
  fe::AnnulusSpec is;
  fe::Mesh inner = MakeRing("inner_ring",
                            0.5 * g.inner_ring_bore_diameter_m,
                            out.inner_raceway_radius_m,
                            /*raceway_inside=*/false,
                            "bore",
                            h,
                            hc,
                            &is);
  parts.push_back(std::move(outer));
  parts.push_back(std::move(inner));
  parts.push_back(MakeCage(g, out.roller_angles_rad, hc, h));
  for (int j = 0; j < g.bearing.num_elements; ++j) {
    const double phi = out.roller_angles_rad[j];
    const Vec centre{out.pitch_radius_m * std::cos(phi), out.pitch_radius_m * std::sin(phi)};
    const Defect* defect = nullptr;
    std::string key;
    for (std::size_t i = 0; i < scene.defects.size(); ++i)
      if (scene.defects[i].roller == j) {
        defect = &scene.defects[i];
        key = scene.source + ": defects." + std::to_string(i);
      }
    const double spall_angle = phi + (defect ? defect->angle_rad : 0.0);
    parts.push_back(MakeRoller(
        "roller" + std::to_string(j), centre, out.roller_radius_m, spall_angle, defect, hc, key));
  }
  parts.push_back(
      MakeAdapter(g, os.n_theta, os.outer_radius, scene, &out.adapter_width_m, kAdapterFirstLayer));
  out.mesh = fe::MergeMeshes(parts);
  fe::ValidateMesh(out.mesh);
  return out;
}

BearingMesh MeshBearingHousing(const Scene& scene) {
  const SceneGeometry& g = scene.geometry;
  const double h = scene.mesh.size_m, hc = scene.mesh.contact_size_m;
  BearingMesh out = BearingLayout(g);
  fe::AnnulusSpec os;
  fe::Mesh outer = MakeOuterRing(g, out.outer_raceway_radius_m, h, hc, &os);
  std::vector<fe::Mesh> parts;
  parts.push_back(std::move(outer));
  parts.push_back(
      MakeAdapter(g, os.n_theta, os.outer_radius, scene, &out.adapter_width_m, kAdapterFirstLayer));
  out.mesh = fe::MergeMeshes(parts);
  fe::ValidateMesh(out.mesh);
  return out;
}

MeshQualityReport MeasureMeshQuality(const fe::Mesh& mesh) {
  MeshQualityReport r;
  r.parts.resize(mesh.num_parts());
  std::vector<std::vector<char>> seen(mesh.num_parts());
  for (int p = 0; p < mesh.num_parts(); ++p) {
    r.parts[p].part = mesh.part_names[p];
    r.parts[p].min_element_area_m2 = HUGE_VAL;
  }
  std::vector<int> node_part(mesh.num_nodes(), -1);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    PartQuality& q = r.parts[mesh.element_part[e]];
    const auto& quad = mesh.quads[e];
    double lmin = HUGE_VAL, lmax = 0;
    for (int i = 0; i < 4; ++i) {
      const int a = quad[(i + 3) % 4], b = quad[i], c = quad[(i + 1) % 4];
      const double ux = mesh.x[a] - mesh.x[b], uy = mesh.y[a] - mesh.y[b];
      const double vx = mesh.x[c] - mesh.x[b], vy = mesh.y[c] - mesh.y[b];
      const double ang = std::atan2(vx * uy - vy * ux, ux * vx + uy * vy) * 180 / kPi;
      // Interior angle at b for a CCW quad: angle from (c-b) to (a-b), counter-clockwise.
      const double interior = ang < 0 ? ang + 360 : ang;
      q.min_angle_deg = std::min(q.min_angle_deg, interior);
      q.max_angle_deg = std::max(q.max_angle_deg, interior);
      q.max_skew_deg = std::max(q.max_skew_deg, std::abs(interior - 90));
      const double len = std::hypot(vx, vy);
      lmin = std::min(lmin, len);
      lmax = std::max(lmax, len);
      node_part[b] = mesh.element_part[e];
    }
    const double area = fe::QuadArea(mesh, e);
    q.area_m2 += area;
    q.min_element_area_m2 = std::min(q.min_element_area_m2, area);
    q.max_aspect_ratio = std::max(q.max_aspect_ratio, lmax / lmin);
    ++q.elements;
  }
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (node_part[n] >= 0) ++r.parts[node_part[n]].nodes;
  r.total_elements = mesh.num_elements();
  r.total_nodes = mesh.num_nodes();
  return r;
}

MeshQualityReport MeshQualityReport::Merged() const {
  MeshQualityReport out;
  out.total_elements = total_elements;
  out.total_nodes = total_nodes;
  std::vector<std::string> stems;  // per merged entry: name without its trailing number
  std::vector<std::string> first;  // per merged entry: trailing number of the first part
  for (const PartQuality& p : parts) {
    size_t cut = p.part.size();
    while (cut > 0 && std::isdigit(static_cast<unsigned char>(p.part[cut - 1]))) --cut;
    const std::string stem = p.part.substr(0, cut), number = p.part.substr(cut);
    size_t k = 0;
    while (k < stems.size() && (stems[k] != stem || number.empty() || first[k].empty())) ++k;
    if (k == stems.size()) {
      stems.push_back(stem);
      first.push_back(number);
      out.parts.push_back(p);
      continue;
    }
    PartQuality& q = out.parts[k];
    q.part = stem + first[k] + ".." + number;
    q.elements += p.elements;
    q.nodes += p.nodes;
    q.area_m2 += p.area_m2;
    q.min_angle_deg = std::min(q.min_angle_deg, p.min_angle_deg);
    q.max_angle_deg = std::max(q.max_angle_deg, p.max_angle_deg);
    q.max_aspect_ratio = std::max(q.max_aspect_ratio, p.max_aspect_ratio);
    q.max_skew_deg = std::max(q.max_skew_deg, p.max_skew_deg);
    q.min_element_area_m2 = std::min(q.min_element_area_m2, p.min_element_area_m2);
  }
  return out;
}

std::string MeshQualityReport::Report() const {
  std::ostringstream os;
  os.precision(4);
  for (const auto& p : parts)
    os << p.part << ": " << p.elements << " elements, " << p.nodes << " nodes, area "
       << p.area_m2 * 1e6 << " mm^2, angles " << p.min_angle_deg << "-" << p.max_angle_deg
       << " deg, max aspect " << p.max_aspect_ratio << ", max skew " << p.max_skew_deg << " deg\n";
  os << "total: " << total_elements << " elements, " << total_nodes << " nodes\n";
  return os.str();
}

}  // namespace spallkit::sim
