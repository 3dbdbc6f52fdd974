#include "sim/bearing/model_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/error.h"
#include "sim/contact/penalty.h"

namespace spallkit::sim {
namespace {

const std::vector<int>& NodeSet(const fe::Mesh& mesh, const std::string& name) {
  auto it = mesh.node_sets.find(name);
  if (it == mesh.node_sets.end())
    throw InputError("bearing model: mesh has no node set '" + name + "'");
  return it->second;
}

const Material& PartMaterial(const Scene& scene, const std::string& part) {
  const SceneMaterials& m = scene.materials;
  if (part == "outer_ring") return m.outer_ring;
  if (part == "inner_ring") return m.inner_ring;
  if (part == "cage") return m.cage;
  if (part == "adapter") return m.adapter;
  if (part.rfind("roller", 0) == 0) return m.roller;
  throw InputError("bearing model: no material for mesh part '" + part + "'");
}

BodyMotion FitMotion(const fe::NodalState& s, const std::vector<int>& nodes) {
  double m = 0, sx = 0, sy = 0, px = 0, py = 0, lz = 0, j0 = 0;
  for (int id : nodes) {
    const double mi = s.mass[id];
    m += mi, sx += mi * s.x[id], sy += mi * s.y[id], px += mi * s.vx[id], py += mi * s.vy[id];
    lz += mi * (s.x[id] * s.vy[id] - s.y[id] * s.vx[id]);
    j0 += mi * (s.x[id] * s.x[id] + s.y[id] * s.y[id]);
  }
  BodyMotion b;
  b.cx = sx / m, b.cy = sy / m, b.vx = px / m, b.vy = py / m;
  const double j = j0 - m * (b.cx * b.cx + b.cy * b.cy);
  b.omega = j > 0 ? (lz - m * (b.cx * b.vy - b.cy * b.vx)) / j : 0.0;
  return b;
}

}  // namespace

FeBearingModel::FeBearingModel(const Scene& scene, const BearingModelOptions& options)
    : BearingModel(scene, options) {
  const bool housing_only = options_.housing_only;
  const bool hybrid = scene_.model.fidelity == Fidelity::kHybrid || housing_only;
  mesh_ = hybrid ? MeshBearingHousing(scene_) : MeshBearing(scene_);
  mesh_quality_ = MeasureMeshQuality(mesh_.mesh);
  const fe::Mesh& mesh = mesh_.mesh;
  const double t = scene_.geometry.thickness_m;

  std::vector<fe::Section> sections;
  std::vector<double> bulk;
  for (const std::string& part : mesh.part_names) {
    const Material& mat = PartMaterial(scene_, part);
    fe::Section s;
    s.material = {mat.youngs_modulus_pa, mat.poisson_ratio, mat.density_kg_m3};
    s.mode = fe::PlaneMode::kPlaneStrain;
    // Rings and adapter: their axial width (bending stiffness, mass); rollers and cage: the
    // roller's effective length, the section every contact force is for.
    const bool ring = part == "outer_ring" || part == "inner_ring" || part == "adapter";
    s.thickness = ring ? scene_.geometry.ring_width_m : t;
    sections.push_back(s);
    bulk.push_back(contact::BulkModulus(mat.youngs_modulus_pa, mat.poisson_ratio));
  }

  solver::SolverOptions so;
  so.time_step_scale = scene_.solver.time_step_safety;
  so.mass_damping_ratio = scene_.damping.ratio;
  so.damping_frequency = scene_.damping.reference_hz;
  so.damping_relative_to_rigid_motion = true;
  so.num_threads = scene_.solver.threads;
  so.track_contributor_work = options_.track_contributor_work;
  so.energy_terms = options_.energy_books || options_.track_contributor_work;
  so.output_every_steps = 1;  // the recorder samples sensor velocities every step
  solver_ = std::make_unique<solver::ExplicitSolver>(mesh, std::move(sections), so);

  // Adapter bottom fixed.
  solver_->FixNodes(NodeSet(mesh, "adapter.bottom"), true, true);
  // Rigid adapter (scene model.adapter = "rigid"): all its nodes fixed, and the outer ring's
  // nodes tied to the seat (below) with them.
  if (scene_.model.adapter == AdapterModel::kRigid)
    solver_->FixNodes(NodeSet(mesh, "adapter.all"), true, true);

  // Shaft: inner-ring bore as a rigid body, rotation prescribed, translation free, load down.
  const double omega = scene_.operation.inner_ring_speed_rad_s;
  const double ramp = scene_.operation.ramp_s;
  if (housing_only) {
    // The housing alone (the lumped model's fit applies its own loads).
  } else if (hybrid) {
    // Rollers, cage and inner ring: rigid bodies in one contributor (before the tie, which
    // must see the contact forces on the ring nodes).
    hybrid_ = std::make_unique<HybridRollers>(
        scene_, mesh_, solver_->state(), options_.hybrid, options_.cage_guide);
    solver_->AddContributor(hybrid_.get());
  } else {
    auto bore = mesh.curves.find("inner_ring.bore");
    if (bore == mesh.curves.end()) throw InputError("bearing model: mesh has no 'inner_ring.bore'");
    solver::RigidBody shaft;
    shaft.name = "shaft";
    shaft.nodes = bore->second.nodes;
    shaft.angle = solver::RampedRotation(omega, ramp);
    const double load = scene_.operation.radial_load_n;
    shaft.force_y = solver::LinearRamp(-load, scene_.operation.load_ramp_s);
    shaft_body_ = solver_->AddRigidBody(std::move(shaft));
  }

  // Contact pairs (FE model).
  contact::ContactPairOptions race;
  race.penalty_law = contact::PenaltyLaw::kBulkModulus;
  race.penalty_scale = options_.race_penalty_scale;
  race.friction.static_coefficient = scene_.friction.mu_static;
  race.friction.dynamic_coefficient = scene_.friction.mu_dynamic;
  race.friction.decay = scene_.friction.decay_s_m;
  race.normal_damping_ratio = options_.contact_damping_ratio;
  contact::ContactPairOptions cage = race;
  cage.penalty_scale = options_.cage_penalty_scale;
  const int z = hybrid ? 0 : scene_.geometry.bearing.num_elements;
  for (int j = 0; j < z; ++j) {
    const std::string roller = "roller" + std::to_string(j);
    const std::string surf = roller + ".surface";
    auto make = [&](const std::string& master, const contact::ContactPairOptions& o) {
      return std::make_unique<contact::ContactPair>(
          contact::MakeContactPair(mesh, surf, master, bulk, t, o));
    };
    if (scene_.model.race_contact == RaceContact::kCurved ||
        scene_.model.race_contact == RaceContact::kSmooth) {
      // Rim segments on the roller's circle and the raceways' segments become arcs; the spall's
      // walls and bottom stay straight, so its corners touch as vertices.
      const double cx = mesh_.pitch_radius_m * std::cos(mesh_.roller_angles_rad[j]);
      const double cy = mesh_.pitch_radius_m * std::sin(mesh_.roller_angles_rad[j]);
      const double tol = 1e-6 * mesh_.roller_radius_m;
      auto make_curved = [&](const std::string& master, double race_radius) {
        contact::ContactSurface s = contact::MakeSurface(mesh, surf, bulk, t);
        contact::ContactSurface m = contact::MakeSurface(mesh, master, bulk, t);
        contact::MarkCircularArcs(
            &s, mesh.x.data(), mesh.y.data(), {cx, cy, mesh_.roller_radius_m}, tol);
        contact::MarkCircularArcs(&m, mesh.x.data(), mesh.y.data(), {0, 0, race_radius}, tol);
        contact::ContactPairOptions o = race;
        o.smooth_surfaces =
            scene_.model.race_contact == RaceContact::kSmooth && !KeepsArcsOnItsSpall(j);
        return std::make_unique<contact::ContactPair>(
            surf + "/" + master, std::move(s), std::move(m), o);
      };
      outer_pairs_.push_back(make_curved("outer_ring.raceway", mesh_.outer_raceway_radius_m));
      inner_pairs_.push_back(make_curved("inner_ring.raceway", mesh_.inner_raceway_radius_m));
    } else {
      outer_pairs_.push_back(make("outer_ring.raceway", race));
      inner_pairs_.push_back(make("inner_ring.raceway", race));
    }
    // Pocket j lies between web j (its leading wall) and web j-1 (its trailing wall). The
    // masters are the webs' closed outlines, not the open walls: a node past the free end of an
    // open wall projects onto the end with the wall's normal and counts as penetrating while
    // beside the web, a force field that is not conservative (energy created when a drifting
    // cage's web corner met a roller); the outline's corner is a convex vertex, which is.
    cage_pairs_.push_back(make("cage.web" + std::to_string(j), cage));
    cage_pairs_.push_back(make("cage.web" + std::to_string((j + z - 1) % z), cage));
    roller_nodes_.push_back(NodeSet(mesh, roller + ".all"));
  }
  for (auto& p : outer_pairs_) solver_->AddContributor(p.get());
  for (auto& p : inner_pairs_) solver_->AddContributor(p.get());
  for (auto& p : cage_pairs_) solver_->AddContributor(p.get());

  // Constraints last: they see every force.
  if (!hybrid) {
    std::vector<std::vector<int>> pockets;
    for (int j = 0; j < z; ++j) pockets.push_back(NodeSet(mesh, "cage.pocket" + std::to_string(j)));
    cage_guide_ = std::make_unique<CagePocketGuide>("cage_guide",
                                                    roller_nodes_,
                                                    std::move(pockets),
                                                    NodeSet(mesh, "cage.all"),
                                                    mesh_.pitch_radius_m,
                                                    options_.cage_guide);
    solver_->AddContributor(cage_guide_.get());
    cage_ = std::make_unique<RigidPart>("cage_rigid", NodeSet(mesh, "cage.all"));
    solver_->AddContributor(cage_.get());
  }
  {
    const std::vector<int>& seat = NodeSet(mesh, "adapter.seat");
    auto outside = mesh.curves.find("outer_ring.outside");
    if (outside == mesh.curves.end())
      throw InputError("bearing model: mesh has no 'outer_ring.outside'");
    std::vector<std::pair<int, int>> pairs;
    const double tol = 1e-3 * scene_.mesh.contact_size_m;
    for (int a : seat) {
      int best = -1;
      double best_d = std::numeric_limits<double>::infinity();
      for (int b : outside->second.nodes) {
        const double d = std::hypot(mesh.x[a] - mesh.x[b], mesh.y[a] - mesh.y[b]);
        if (d < best_d) best_d = d, best = b;
      }
      if (!(best_d <= tol)) {
        std::ostringstream os;
        os << "bearing model: adapter seat node " << a << " has no coincident outer-ring node ("
           << best_d * 1e3 << " mm away); the tie needs matching nodes";
        throw InputError(os.str());
      }
      pairs.emplace_back(best, a);
    }
    if (scene_.model.adapter == AdapterModel::kRigid) {
      std::vector<int> ring_seat;
      for (const auto& p : pairs) ring_seat.push_back(p.first);
      solver_->FixNodes(ring_seat, true, true);
    }
    tie_ = std::make_unique<TiedNodes>("ring_adapter_tie", std::move(pairs));
    solver_->AddContributor(tie_.get());
  }

  // Sensors: nearest node of the outer ring or adapter.
  std::vector<int> candidates = NodeSet(mesh, "outer_ring.all");
  const auto& adapter = NodeSet(mesh, "adapter.all");
  candidates.insert(candidates.end(), adapter.begin(), adapter.end());
  for (const Sensor& sensor : scene_.sensors) {
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (int id : candidates) {
      const double d = std::hypot(mesh.x[id] - sensor.x_m, mesh.y[id] - sensor.y_m);
      if (d < best_d) best_d = d, best = id;
    }
    // Within one element of the point (a coarse mesh resolves the sensor no better), and 2 mm
    // on fine meshes.
    const double reach = std::max(2e-3, scene_.mesh.size_m);
    if (best_d > reach) {
      std::ostringstream os;
      os << "sensors." << sensor.name << ": no outer-ring or adapter node within " << reach * 1e3
         << " mm (2 mm or mesh.size_mm) of the sensor point (the nearest is " << best_d * 1e3
         << " mm away): put the point on the outer ring or the adapter";
      throw InputError(os.str());
    }
    for (Axis dir : sensor.directions) channels_.push_back({sensor.name, dir, best, best_d});
  }
}

void FeBearingModel::ElementVonMises(double* out) const {
  const fe::QuadElements& e = solver_->elements();
  for (int i = 0; i < num_elements(); ++i) out[i] = e.VonMises(i);
}

double FeBearingModel::RollerOuterForce(int j) const {
  if (hybrid_) return hybrid_->rollers().OuterForce(j);
  return outer_pairs_[j]->Resultant().NormalMagnitude();
}
double FeBearingModel::RollerInnerForce(int j) const {
  if (hybrid_) return hybrid_->rollers().InnerForce(j);
  return inner_pairs_[j]->Resultant().NormalMagnitude();
}
double FeBearingModel::RollerCageForce(int j) const {
  if (hybrid_) return hybrid_->rollers().CageForce(j);
  return cage_pairs_[2 * j]->Resultant().NormalMagnitude() +
         cage_pairs_[2 * j + 1]->Resultant().NormalMagnitude() + cage_guide_->Force(j);
}

BodyMotion FeBearingModel::RollerMotion(int j) const {
  if (hybrid_) {
    const PlanarBody& b = hybrid_->rollers().roller(j);
    return {b.x, b.y, b.vx, b.vy, b.omega};
  }
  return FitMotion(solver_->state(), roller_nodes_[j]);
}

void FeBearingModel::SetObserver(std::function<void()> observer) {
  if (!observer) {
    solver_->SetOutputCallback(nullptr);
    return;
  }
  solver_->SetOutputCallback([observer](const solver::ExplicitSolver&) { observer(); });
}

double FeBearingModel::SensorVelocity(int channel) const {
  const SensorChannel& ch = channels_[channel];
  const fe::NodalState& s = solver_->state();
  return ch.direction == Axis::kX ? s.vx[ch.node] : s.vy[ch.node];
}

std::string FeBearingModel::SaveState() const { return solver_->SaveState(); }

void FeBearingModel::LoadState(const std::string& bytes) { solver_->LoadState(bytes); }

BodyMotion FeBearingModel::CageMotion() const {
  if (hybrid_) {
    const PlanarBody& b = hybrid_->rollers().cage();
    return {b.x, b.y, b.vx, b.vy, b.omega};
  }
  const RigidPart::Motion m = cage_->ComputeMotion(solver_->state());
  return {m.cx, m.cy, m.vx, m.vy, m.omega};
}

BodyMotion FeBearingModel::InnerRingMotion() const {
  if (hybrid_) {
    const PlanarBody& b = hybrid_->rollers().shaft();
    return {b.x, b.y, b.vx, b.vy, speed_(solver_->time())};
  }
  const solver::RigidBodyState& s = solver_->rigid_body_state(shaft_body_);
  return {s.x, s.y, s.vx, s.vy, speed_(solver_->time())};
}

BodyMotion FeBearingModel::OuterRingMotion() const {
  const fe::NodalState& st = solver_->state();
  BodyMotion m;
  const std::vector<int>& nodes = mesh_.mesh.curves.at("outer_ring.raceway").nodes;
  for (int n : nodes) {
    m.cx += st.x[n] - st.x0[n], m.cy += st.y[n] - st.y0[n];
    m.vx += st.vx[n], m.vy += st.vy[n];
  }
  const double k = nodes.empty() ? 0.0 : 1.0 / static_cast<double>(nodes.size());
  m.cx *= k, m.cy *= k, m.vx *= k, m.vy *= k;
  return m;
}

bool FeBearingModel::KeepsArcsOnItsSpall(int roller) const {
  bool spalled = false;
  for (const Defect& d : scene_.defects) spalled = spalled || d.roller == roller;
  return spalled && scene_.mesh.contact_size_m >= kCurvedMinRimSpacing;
}

std::vector<std::string> FeBearingModel::Warnings() const {
  std::vector<std::string> out;
  if (hybrid_) return out;  // exact circles: no facets, no arcs
  // Rim facets of the healthy rollers (a notched roller's surface has extra notch nodes).
  int facets = 0;
  for (int j = 0; j < num_rollers(); ++j) {
    bool defective = false;
    for (const Defect& d : scene_.defects) defective = defective || d.roller == j;
    if (defective) continue;
    const auto it = mesh_.mesh.curves.find("roller" + std::to_string(j) + ".surface");
    if (it != mesh_.mesh.curves.end()) facets = static_cast<int>(it->second.nodes.size());
    break;
  }
  if (facets == 0) return out;
  const double rim_spacing = 2.0 * std::numbers::pi * mesh_.roller_radius_m / facets;
  if (scene_.model.race_contact == RaceContact::kSmooth)
    return out;  // no blend to kink (spline_surface.h)
  if (scene_.model.race_contact != RaceContact::kFaceted) {
    // The curved race contact rolls the meshed rims as circles (measured at mu 0.01 on 0.5 and
    // 1.0 mm meshes), but on finer rims dented loaded nodes kink the fixed-curvature arcs and the
    // blend creates energy (docs/CONTACT.md, "Limits").
    if (rim_spacing < kCurvedMinRimSpacing) {
      std::ostringstream os;
      os.precision(3);
      os << "the curved race contact on rims of " << facets << " facets (" << rim_spacing * 1e3
         << " mm) creates energy where a loaded rim node dents "
         << "(docs/CONTACT.md, \"Limits\"); "
         << "the run stops if the balance passes solver.max_energy_error_percent; "
         << "model.race_contact = \"smooth\" (the default) balances on this mesh";
      out.push_back(os.str());
    }
    return out;
  }
  // Faceted race contact stands on its facets.
  const SceneFriction& f = scene_.friction;
  const double mu = f.decay_s_m > 0.0 ? f.mu_dynamic : f.mu_static;
  if (!(mu > 0.0)) return out;  // frictionless: nothing drives the rollers anyway
  if (mu * facets >= kRollingMinMuFacets) return out;
  const double needed_spacing =
      2.0 * std::numbers::pi * mesh_.roller_radius_m * mu / kRollingMinMuFacets;
  std::ostringstream os;
  os.precision(3);
  os << "the FE rollers' rims have " << facets << " facets: at friction mu = " << mu
     << " they may stand on their facets and slide instead of rolling (mu x facets = "
     << mu * facets << " < " << kRollingMinMuFacets
     << "; docs/BEARING_MODEL.md); use model.race_contact = \"smooth\" or refine "
     << "mesh.contact_size_mm to <= " << needed_spacing * 1e3;
  out.push_back(os.str());
  return out;
}

std::string FeBearingModel::Describe() const {
  std::ostringstream os;
  const fe::Mesh& m = mesh_.mesh;
  if (hybrid_) {
    const RollerContacts& h = hybrid_->rollers();
    os << "model: hybrid (rigid rollers, cage and inner ring with exact profiles; FE outer ring "
          "and adapter): "
       << m.num_elements() << " elements, " << m.num_nodes()
       << " nodes; Palmgren K_c = " << h.contact_stiffness() / std::pow(1e3, 10.0 / 9.0) * 1e-3
       << " kN/mm^(10/9), spread +-" << hybrid_->kernel().half_width() * 1e3 << " mm, roller mass "
       << h.roller_mass(0) * 1e3 << " g, cage " << h.cage_mass() * 1e3 << " g, inner ring "
       << h.shaft_mass() * 1e3 << " g; ring-adapter tie " << tie_->num_pairs() << " node pairs"
       << "\ncontact stable step: roller side " << h.roller_time_step() * 1e9 << " ns, ring side "
       << h.ring_time_step() * 1e9 << " ns (raceway kernel mass " << h.outer_race_mass() * 1e6
       << " mg), x 0.8";
  } else {
    os << "model: fe, " << m.num_elements() << " elements, " << m.num_nodes() << " nodes, "
       << m.num_parts() << " parts; "
       << outer_pairs_.size() + inner_pairs_.size() + cage_pairs_.size()
       << " contact pairs (penalty f = " << options_.race_penalty_scale << " races, "
       << options_.cage_penalty_scale << " cage, damping " << options_.contact_damping_ratio
       << "; race contact " << RaceContactName(scene_.model.race_contact);
    for (int j = 0; j < num_rollers(); ++j)
      if (scene_.model.race_contact == RaceContact::kSmooth && KeepsArcsOnItsSpall(j))
        os << ", roller " << j << " arcs (spalled)";
    os << "); cage rigid (" << cage_->nodes().size() << " nodes, roller-guided: radial play +-"
       << options_.cage_guide.radial_play_m * 1e3 << " mm); ring-adapter tie " << tie_->num_pairs()
       << " node pairs";
  }
  for (const SensorChannel& c : channels_)
    os << "\nsensor " << c.sensor << " " << AxisName(c.direction) << ": node " << c.node << " ("
       << c.distance_m * 1e3 << " mm from the point)";
  // Angles are interior angles, aspect = longest / shortest edge, skew = largest |angle - 90|.
  std::string quality = mesh_quality_.Merged().Report();
  if (!quality.empty() && quality.back() == '\n') quality.pop_back();
  os << "\nmesh quality:";
  std::istringstream lines(quality);
  for (std::string line; std::getline(lines, line);) os << "\n  " << line;
  return os.str();
}

}  // namespace spallkit::sim
