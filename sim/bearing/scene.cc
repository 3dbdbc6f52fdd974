#include "sim/bearing/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include "core/constants.h"
#include "core/error.h"
#include "core/format.h"
#include "core/input_file.h"
#include "sim/bearing/fidelity_choice.h"
#include "sim/bearing/scene_limits.h"

namespace spallkit::sim {
namespace {

constexpr double kMm = 1e-3;

bool IsDigit(char c) { return c >= '0' && c <= '9'; }

// "file:line" for a node parsed from a file, "--set" for a value from an override, the file
// name alone for a default that has no source.
std::string Where(const std::string& file, const toml::node* node) {
  if (node) {
    const auto& src = node->source();
    if (src.path && src.path->rfind("--set", 0) == 0) return *src.path;
    if (src.begin.line > 0) return file + ":" + std::to_string(src.begin.line);
    // A table an override created has no source; its values name their --set.
    if (const toml::table* t = node->as_table())
      for (auto&& [k, v] : *t) {
        const std::string inner = Where(file, &v);
        if (inner.rfind("--set", 0) == 0) return inner;
      }
  }
  return file;
}

// "<where>: <key>: <what>", the key said once when <where> is already "--set <key>".
std::string Located(const std::string& where, const std::string& key, const std::string& what) {
  if (where == "--set " + key) return where + ": " + what;
  return where + ": " + key + ": " + what;
}

// Inclusive/exclusive numeric range with a message.
struct Range {
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  bool lo_open = false, hi_open = false;
  bool Contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (lo_open ? !(v > lo) : !(v >= lo)) return false;
    if (hi_open ? !(v < hi) : !(v <= hi)) return false;
    return true;
  }
  std::string Describe() const {
    if (hi == HUGE_VAL) return std::string(lo_open ? "> " : ">= ") + FormatNumber("%.6g", lo);
    return std::string("in ") + (lo_open ? "(" : "[") + FormatNumber("%.6g", lo) + ", " +
           FormatNumber("%.6g", hi) + (hi_open ? ")" : "]");
  }
};
const Range kPositive{0.0, HUGE_VAL, true, false};
const Range kNonNegative{0.0, HUGE_VAL, false, false};

// The scene-file names of the [model] choices, in the order error messages list them.
template <typename E>
struct NamedValue {
  E value;
  const char* name;
};
constexpr NamedValue<Fidelity> kFidelityNames[] = {{Fidelity::kFe, "fe"},
                                                   {Fidelity::kHybrid, "hybrid"},
                                                   {Fidelity::kLumped, "lumped"},
                                                   {Fidelity::kAuto, "auto"}};
constexpr NamedValue<AdapterModel> kAdapterModelNames[] = {{AdapterModel::kElastic, "elastic"},
                                                           {AdapterModel::kRigid, "rigid"}};
constexpr NamedValue<RaceContact> kRaceContactNames[] = {{RaceContact::kFaceted, "faceted"},
                                                         {RaceContact::kCurved, "curved"},
                                                         {RaceContact::kSmooth, "smooth"}};
constexpr NamedValue<StartPose> kStartPoseNames[] = {{StartPose::kSeated, "seated"},
                                                     {StartPose::kCentred, "centred"}};
constexpr NamedValue<LumpedStep> kLumpedStepNames[] = {{LumpedStep::kAccurate, "accurate"},
                                                       {LumpedStep::kFast, "fast"}};
constexpr NamedValue<Axis> kAxisNames[] = {{Axis::kX, "x"}, {Axis::kY, "y"}};
constexpr NamedValue<Output> kOutputNames[] = {{Output::kContactForces, "contact_forces"},
                                               {Output::kAcceleration, "acceleration"},
                                               {Output::kCage, "cage"},
                                               {Output::kRollers, "rollers"},
                                               {Output::kEnergy, "energy"},
                                               {Output::kField, "field"}};

template <typename E, std::size_t N>
const char* NameOf(const NamedValue<E> (&table)[N], E value) {
  for (const auto& e : table)
    if (e.value == value) return e.name;
  return "?";
}

template <typename E, std::size_t N>
bool ParseName(const NamedValue<E> (&table)[N], const std::string& name, E* value) {
  for (const auto& e : table)
    if (name == e.name) {
      *value = e.value;
      return true;
    }
  return false;
}

// One TOML table being read: remembers which keys were used, fills in defaults (so the table
// becomes the effective scene), and reports unknown keys.
class Section {
 public:
  Section(toml::table* table, std::string prefix, const std::string* file)
      : table_(table), prefix_(std::move(prefix)), file_(file) {}

  std::string Key(const std::string& key) const { return prefix_ + key; }
  [[noreturn]] void Fail(const std::string& key, const std::string& what) const {
    throw InputError(Located(Where(*file_, table_->get(key)), Key(key), what));
  }

  double Number(const std::string& key, double def, const Range& range) {
    used_.insert(key);
    toml::node* n = table_->get(key);
    if (!n) {
      table_->insert(key, def);
      return def;
    }
    double v;
    if (auto f = n->as_floating_point())
      v = f->get();
    else if (auto i = n->as_integer())
      v = static_cast<double>(i->get());
    else
      Fail(key, std::string("expected a number, got ") + TypeName(*n));
    if (!range.Contains(v))
      Fail(key, "must be " + range.Describe() + " (got " + FormatNumber("%.6g", v) + ")");
    return v;
  }

  int Integer(const std::string& key, int def, int lo, int hi) {
    used_.insert(key);
    toml::node* n = table_->get(key);
    if (!n) {
      table_->insert(key, def);
      return def;
    }
    auto i = n->as_integer();
    if (!i) Fail(key, std::string("expected an integer, got ") + TypeName(*n));
    if (i->get() < lo || i->get() > hi)
      Fail(key,
           "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
               std::to_string(i->get()) + ")");
    return static_cast<int>(i->get());
  }

  std::string String(const std::string& key, const std::string& def) {
    used_.insert(key);
    toml::node* n = table_->get(key);
    if (!n) {
      table_->insert(key, def);
      return def;
    }
    auto s = n->as_string();
    if (!s) Fail(key, std::string("expected a string, got ") + TypeName(*n));
    return s->get();
  }

  std::vector<std::string> Strings(const std::string& key, const std::vector<std::string>& def) {
    used_.insert(key);
    toml::node* n = table_->get(key);
    if (!n) {
      toml::array a;
      for (const auto& s : def) a.push_back(s);
      table_->insert(key, std::move(a));
      return def;
    }
    auto a = n->as_array();
    if (!a) Fail(key, std::string("expected an array of strings, got ") + TypeName(*n));
    std::vector<std::string> out;
    for (auto& e : *a) {
      auto s = e.as_string();
      if (!s) Fail(key, "expected an array of strings");
      out.push_back(s->get());
    }
    return out;
  }

  bool Has(const std::string& key) const { return table_->contains(key); }

  // A sub-table (created empty if absent, so defaults land in the effective scene).
  Section Table(const std::string& key) {
    used_.insert(key);
    toml::node* n = table_->get(key);
    if (!n) {
      table_->insert(key, toml::table{});
      n = table_->get(key);
    }
    if (!n->is_table()) Fail(key, std::string("expected a table, got ") + TypeName(*n));
    return Section(n->as_table(), prefix_ + key + ".", file_);
  }

  // Marks a key as known without reading it (arrays of tables handled by the caller).
  toml::node* Take(const std::string& key) {
    used_.insert(key);
    return table_->get(key);
  }

  void RejectUnknown() const {
    for (auto&& [k, v] : *table_) {
      const std::string key(k.str());
      if (used_.count(key)) continue;
      std::string known;
      for (const auto& u : used_) known += (known.empty() ? "" : ", ") + u;
      throw InputError(Where(*file_, &v) + ": unknown key '" + prefix_ + key + "'" +
                       (known.empty() ? "" : " (known here: " + known + ")"));
    }
  }

  static const char* TypeName(const toml::node& n) {
    switch (n.type()) {
      case toml::node_type::string:
        return "a string";
      case toml::node_type::integer:
        return "an integer";
      case toml::node_type::floating_point:
        return "a float";
      case toml::node_type::boolean:
        return "a boolean";
      case toml::node_type::array:
        return "an array";
      case toml::node_type::table:
        return "a table";
      default:
        return "a date/time";
    }
  }

  toml::table* table() { return table_; }
  const std::string& file() const { return *file_; }

 private:
  toml::table* table_;
  std::string prefix_;
  const std::string* file_;
  std::set<std::string> used_;
};

Material ReadMaterial(Section s, const Material& def) {
  Material m;
  m.youngs_modulus_pa = s.Number("youngs_modulus_pa", def.youngs_modulus_pa, kPositive);
  m.poisson_ratio = s.Number("poisson_ratio", def.poisson_ratio, {-1.0, 0.5, true, true});
  m.density_kg_m3 = s.Number("density_kg_m3", def.density_kg_m3, kPositive);
  // The explicit step is element size / wave speed: a wave faster than 1000 km/s (50 x any solid)
  // would need billions of steps per millisecond.
  const double wave_speed = std::sqrt(m.youngs_modulus_pa / m.density_kg_m3);
  if (!(wave_speed <= 1e6))
    s.Fail("density_kg_m3",
           "sqrt(youngs_modulus_pa / density_kg_m3) = " + FormatNumber("%.3g", wave_speed) +
               " m/s, above the 1e+06 m/s bound (no solid is that stiff for its density)");
  s.RejectUnknown();
  return m;
}

void ReadGeometry(Section s, SceneGeometry* g) {
  const std::string catalog = s.String("catalog", "N205EM");
  try {
    g->bearing = CatalogBearing(catalog);
  } catch (const InputError& e) {
    s.Fail("catalog", e.what());
  }
  BearingGeometry& b = g->bearing;
  const BearingGeometry cat = b;
  b.num_elements = s.Integer("roller_count", b.num_elements, 3, 1000);
  b.element_diameter_m =
      s.Number("roller_diameter_mm", b.element_diameter_m / kMm, kPositive) * kMm;
  b.pitch_diameter_m = s.Number("pitch_diameter_mm", b.pitch_diameter_m / kMm, kPositive) * kMm;
  b.inner_raceway_diameter_m =
      s.Number("inner_raceway_diameter_mm", b.inner_raceway_diameter_m / kMm, kPositive) * kMm;
  b.outer_raceway_diameter_m =
      s.Number("outer_raceway_diameter_mm", b.outer_raceway_diameter_m / kMm, kPositive) * kMm;
  if (b.num_elements != cat.num_elements || b.element_diameter_m != cat.element_diameter_m ||
      b.pitch_diameter_m != cat.pitch_diameter_m ||
      b.inner_raceway_diameter_m != cat.inner_raceway_diameter_m ||
      b.outer_raceway_diameter_m != cat.outer_raceway_diameter_m)
    b.name = cat.name + " (modified)";
  g->thickness_m = s.Number("thickness_mm", 9.0, kPositive) * kMm;
  g->ring_width_m = s.Number("ring_width_mm", 15.0, kPositive) * kMm;
  if (!(g->ring_width_m >= g->thickness_m))
    s.Fail("ring_width_mm",
           "must be >= thickness_mm (" + FormatNumber("%.6g", g->thickness_m / kMm) +
               " mm): the rings are at least as wide as the rollers' contact");
  g->diametral_clearance_m = s.Number("diametral_clearance_mm", 0.02, {0.0, 1.0}) * kMm;
  g->pocket_clearance_m = s.Number("pocket_clearance_mm", 0.2, {0.0, 5.0}) * kMm;
  g->cage_radial_play_m = s.Number("cage_radial_play_mm", 0.5, {0.0, 5.0}) * kMm;
  g->outer_ring_outer_diameter_m = s.Number("outer_ring_outer_diameter_mm", 52.0, kPositive) * kMm;
  g->inner_ring_bore_diameter_m = s.Number("inner_ring_bore_diameter_mm", 25.0, kPositive) * kMm;
  g->cage_inner_diameter_m = s.Number("cage_inner_diameter_mm", 35.5, kPositive) * kMm;
  g->cage_outer_diameter_m = s.Number("cage_outer_diameter_mm", 42.0, kPositive) * kMm;
  g->adapter_width_m = s.Number("adapter_width_mm", 40.0, kPositive) * kMm;
  g->adapter_height_m = s.Number("adapter_height_mm", 31.0, kPositive) * kMm;
  g->roller_phase_rad = s.Number("roller_phase_deg", 0.0, {-360.0, 360.0}) * kPi / 180.0;
  s.RejectUnknown();

  // Consistency, each message naming the key to change.
  try {
    b.Validate();
  } catch (const InputError& e) {
    s.Fail("roller_count", e.what());
  }
  const double d = b.element_diameter_m, dm = b.pitch_diameter_m;
  if (std::abs(b.outer_raceway_diameter_m - b.inner_raceway_diameter_m - 2 * d) > 0.05 * d)
    s.Fail("outer_raceway_diameter_mm",
           "raceway diameters must differ by two roller diameters (nominal, zero clearance; "
           "clearance is diametral_clearance_mm)");
  if (std::abs(0.5 * (b.outer_raceway_diameter_m + b.inner_raceway_diameter_m) - dm) > 0.05 * d)
    s.Fail("pitch_diameter_mm", "must be the mean of the raceway diameters");
  if (!(g->outer_ring_outer_diameter_m > b.outer_raceway_diameter_m + 0.5e-3))
    s.Fail("outer_ring_outer_diameter_mm",
           "must exceed the outer raceway diameter (" +
               FormatNumber("%.6g", b.outer_raceway_diameter_m / kMm) + " mm) by at least 0.5 mm");
  if (!(g->inner_ring_bore_diameter_m < b.inner_raceway_diameter_m - 0.5e-3))
    s.Fail("inner_ring_bore_diameter_mm",
           "must be smaller than the inner raceway diameter (" +
               FormatNumber("%.6g", b.inner_raceway_diameter_m / kMm) + " mm) by at least 0.5 mm");
  if (!(g->cage_inner_diameter_m > b.inner_raceway_diameter_m && g->cage_inner_diameter_m < dm))
    s.Fail("cage_inner_diameter_mm", "must lie between the inner raceway and pitch diameters");
  if (!(g->cage_outer_diameter_m < b.outer_raceway_diameter_m && g->cage_outer_diameter_m > dm))
    s.Fail("cage_outer_diameter_mm", "must lie between the pitch and outer raceway diameters");
  const double c = 0.5 * (d + g->pocket_clearance_m);  // pocket half width
  const double rci = 0.5 * g->cage_inner_diameter_m;
  if (!(c < rci) || !(2.0 * std::asin(c / rci) < 2.0 * kPi / b.num_elements * 0.9))
    s.Fail("pocket_clearance_mm", "pockets leave no cage web at the cage inner diameter");
  if (!(g->adapter_width_m < g->outer_ring_outer_diameter_m * 0.98))
    s.Fail("adapter_width_mm", "must be smaller than the outer ring outer diameter");
}

void ReadMaterials(Section m, SceneMaterials* mat) {
  const SceneMaterials def;
  mat->outer_ring = ReadMaterial(m.Table("outer_ring"), def.outer_ring);
  mat->inner_ring = ReadMaterial(m.Table("inner_ring"), def.inner_ring);
  mat->roller = ReadMaterial(m.Table("roller"), def.roller);
  mat->cage = ReadMaterial(m.Table("cage"), def.cage);
  mat->adapter = ReadMaterial(m.Table("adapter"), def.adapter);
  m.RejectUnknown();
}

// An array of tables under `key`; when absent, `defaults` is inserted (so it lands in the
// effective scene) and returned.
toml::array* TableArray(Section& top, const std::string& key, toml::array defaults) {
  toml::node* n = top.Take(key);
  if (!n) {
    top.table()->insert(key, std::move(defaults));
    n = top.table()->get(key);
  }
  auto* arr = n->as_array();
  if (!arr) top.Fail(key, "expected an array of tables ([[" + key + "]])");
  for (std::size_t i = 0; i < arr->size(); ++i)
    if (!arr->get(i)->is_table())
      throw InputError(Where(top.file(), arr->get(i)) + ": " + key + "." + std::to_string(i) +
                       ": expected a table");
  return arr;
}

Defect ReadDefect(Section s, const SceneGeometry& g) {
  const int z = g.bearing.num_elements;
  const double roller_d = g.bearing.element_diameter_m;
  Defect d;
  d.roller = s.Integer("roller", 0, 0, 1 << 20);
  if (d.roller >= z)
    s.Fail("roller",
           "roller index " + std::to_string(d.roller) + " >= roller count " + std::to_string(z));
  d.width_m = s.Number("width_mm", 1.38, kPositive) * kMm;
  d.depth_m = s.Number("depth_mm", 0.59, kPositive) * kMm;
  d.angle_rad = s.Number("angle_deg", 0.0, {-360.0, 360.0}) * kPi / 180.0;
  d.edge_radius_m = s.Number("edge_radius_mm", 0.0, {0.0, 1.0}) * kMm;
  const double t_mm = g.thickness_m / kMm;
  d.length_m = s.Number("length_mm", t_mm, {0.0, t_mm}) * kMm;
  if (!(d.length_m > 0)) s.Fail("length_mm", "must be > 0 (the spall's axial length)");
  s.RejectUnknown();
  if (!(d.width_m < roller_d))
    s.Fail("width_mm",
           "spall wider than the roller (" + FormatNumber("%.6g", d.width_m / kMm) +
               " mm >= roller diameter " + FormatNumber("%.6g", roller_d / kMm) + " mm)");
  const double r = 0.5 * roller_d;
  const double sag = r - std::sqrt(r * r - 0.25 * d.width_m * d.width_m);
  if (!(d.depth_m > sag))
    s.Fail("depth_mm",
           "must exceed " + FormatNumber("%.6g", sag / kMm) +
               " mm, the rise of the roller surface over the " +
               "spall mouth (else the flat bottom lies above the mouth)");
  if (!(d.depth_m < 0.5 * r))
    s.Fail("depth_mm",
           "must be below half the roller radius (" + FormatNumber("%.6g", 0.5 * r / kMm) + " mm)");
  return d;
}

// [[defects]]: absent -> the paper's one spall; an empty array -> a healthy bearing.
void ReadDefects(Section& top, const SceneGeometry& g, std::vector<Defect>* defects) {
  toml::array paper_spall;
  paper_spall.push_back(toml::table{});
  toml::array* arr = TableArray(top, "defects", std::move(paper_spall));
  std::set<int> rollers;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    Section s(arr->get(i)->as_table(), "defects." + std::to_string(i) + ".", &top.file());
    const Defect d = ReadDefect(s, g);
    if (!rollers.insert(d.roller).second)
      s.Fail("roller",
             "roller " + std::to_string(d.roller) +
                 " already has a spall (one spall per roller is supported)");
    defects->push_back(d);
  }
}

void ReadOperation(Section s, SceneOperation* op) {
  op->radial_load_n = s.Number("radial_load_n", 10000.0, kNonNegative);
  op->inner_ring_speed_rad_s = s.Number("speed_rpm", 1200.0, {0.0, 1e5}) * 2.0 * kPi / 60.0;
  op->ramp_s = s.Number("ramp_s", 0.005, kNonNegative);
  op->load_ramp_s = s.Number("load_ramp_s", op->ramp_s, kNonNegative);
  s.RejectUnknown();
}

void ReadFriction(Section s, SceneFriction* f) {
  f->mu_static = s.Number("mu_static", 0.01, {0.0, 2.0});
  f->mu_dynamic = s.Number("mu_dynamic", 0.005, {0.0, 2.0});
  f->decay_s_m = s.Number("decay_s_m", 0.0, kNonNegative);
  const std::string model = s.String("model", "coulomb");
  if (!contact::ParseTractionModel(model, &f->model))
    s.Fail("model", "expected \"coulomb\" or \"ehl\" (got \"" + model + "\")");
  f->ehl.limiting_coefficient = s.Number("ehl_limit", 0.08, {0.0, 1.0, true, true});
  f->ehl.slide_roll_scale = s.Number("ehl_slide_roll", 0.01, {0.0, 1.0, true, false});
  f->ehl.inlet_viscosity_pa_s = s.Number("ehl_viscosity_pa_s", 0.05, {0.0, 10.0});
  s.RejectUnknown();
  if (f->mu_dynamic > f->mu_static) s.Fail("mu_dynamic", "must not exceed mu_static");
}

void ReadDamping(Section s, SceneDamping* d) {
  d->ratio = s.Number("ratio", 0.02, {0.0, 1.0});
  d->reference_hz = s.Number("reference_hz", 1000.0, kPositive);
  s.RejectUnknown();
}

// A string key that must name one of `table`'s values.
template <typename E, std::size_t N>
E Choice(Section& s, const std::string& key, E def, const NamedValue<E> (&table)[N]) {
  const std::string v = s.String(key, NameOf(table, def));
  E out;
  if (ParseName(table, v, &out)) return out;
  std::string list;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) list += i + 1 == N ? " or " : ", ";
    list += '"';
    list += table[i].name;
    list += '"';
  }
  s.Fail(key, "expected " + list + ", got \"" + v + "\"");
}

void ReadModel(Section s,
               const SceneGeometry& g,
               const std::vector<Defect>& defects,
               const SceneFriction& friction,
               SceneModel* model) {
  model->fidelity = Choice(s, "fidelity", Fidelity::kAuto, kFidelityNames);
  model->adapter = Choice(s, "adapter", AdapterModel::kElastic, kAdapterModelNames);
  model->race_contact = Choice(s, "race_contact", RaceContact::kSmooth, kRaceContactNames);
  model->start = Choice(s, "start", StartPose::kSeated, kStartPoseNames);
  if (s.Has("contact_damping"))
    model->contact_damping = s.Number("contact_damping", 0.1, {0.0, 1.0, false, false});
  // The FE section is 2-D: a spall runs through its whole thickness.
  for (std::size_t i = 0; model->fidelity == Fidelity::kFe && i < defects.size(); ++i)
    if (defects[i].ShorterThan(g.thickness_m))
      s.Fail("fidelity",
             "defects." + std::to_string(i) +
                 ".length_mm is shorter than bearing.thickness_mm (a partial-length spall); "
                 "that needs model.fidelity = \"hybrid\"");
  // The lubricant traction needs the contact's entrainment speed, which the rigid rollers have
  // and the FE's node-to-surface contact does not.
  if (model->fidelity == Fidelity::kFe && friction.model != contact::TractionModel::kCoulomb)
    s.Fail("fidelity",
           "friction.model = \"ehl\" needs model.fidelity = \"hybrid\" or \"lumped\" (the "
           "full FE has Coulomb friction only)");
  s.RejectUnknown();
}

void ReadMesh(Section s,
              const SceneModel& model,
              const std::vector<Defect>& defects,
              SceneMesh* mesh) {
  mesh->size_m = s.Number("size_mm", 0.25, {0.0, 5.0, true, false}) * kMm;
  mesh->contact_size_m =
      s.Number("contact_size_mm", mesh->size_m / kMm, {0.0, mesh->size_m / kMm, true}) * kMm;
  mesh->adapter_size_m =
      s.Number("adapter_size_mm", std::max(1.0, mesh->size_m / kMm), {mesh->size_m / kMm, 20.0}) *
      kMm;
  s.RejectUnknown();
  // The hybrid model's rollers are not meshed: their spalls are exact profiles.
  for (std::size_t i = 0; model.fidelity == Fidelity::kFe && i < defects.size(); ++i) {
    const auto& d = defects[i];
    if (d.UnresolvedBy(mesh->contact_size_m))
      s.Fail("contact_size_mm",
             "too coarse for defects." + std::to_string(i) + " (" +
                 FormatNumber("%.6g", d.width_m / kMm) + " x " +
                 FormatNumber("%.6g", d.depth_m / kMm) +
                 " mm): need width >= 1.5 and depth >= 1 element; refine mesh.size_mm");
  }
}

Sensor ReadSensor(Section s, std::size_t index) {
  Sensor sensor;
  sensor.name = s.String("name", "sensor" + std::to_string(index));
  sensor.x_m = s.Number("x_mm", 0.0, {-1000.0, 1000.0}) * kMm;
  sensor.y_m = s.Number("y_mm", 0.0, {-1000.0, 1000.0}) * kMm;
  for (const std::string& name : s.Strings("directions", {"x", "y"})) {
    Axis axis;
    if (!ParseAxis(name, &axis))
      s.Fail("directions", "expected \"x\" or \"y\", got \"" + name + "\"");
    sensor.directions.push_back(axis);
  }
  s.RejectUnknown();
  return sensor;
}

// [[sensors]]: absent -> one vertical sensor on top of the outer ring and one horizontal on its
// side.
void ReadSensors(Section& top, const SceneGeometry& g, std::vector<Sensor>* sensors) {
  const double r_mm = g.outer_ring_outer_diameter_m / 2 / kMm;
  toml::array defaults;
  defaults.push_back(toml::table{
      {"name", "top"}, {"x_mm", 0.0}, {"y_mm", r_mm}, {"directions", toml::array{"y"}}});
  defaults.push_back(toml::table{
      {"name", "side"}, {"x_mm", r_mm}, {"y_mm", 0.0}, {"directions", toml::array{"x"}}});
  toml::array* arr = TableArray(top, "sensors", std::move(defaults));
  // Each channel is found on the mesh and recorded at the output rate: a bound, well above any
  // test rig's channel count.
  constexpr std::size_t kMaxSensors = 256;
  if (arr->size() > kMaxSensors)
    top.Fail("sensors",
             std::to_string(arr->size()) + " sensors, at most " + std::to_string(kMaxSensors));
  std::set<std::string> names;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    Section s(arr->get(i)->as_table(), "sensors." + std::to_string(i) + ".", &top.file());
    sensors->push_back(ReadSensor(s, i));
    if (!names.insert(sensors->back().name).second)
      s.Fail(
          "name",
          "\"" + sensors->back().name + "\" is the name of an earlier sensor (names must differ)");
  }
}

void ReadRun(Section s, SceneRun* run, std::vector<Output>* outputs) {
  run->duration_s = s.Number("duration_s", 0.2, kPositive);
  run->output_rate_hz = s.Number("output_rate_hz", 20000.0, kPositive);
  run->field_rate_hz = s.Number("field_rate_hz", std::min(1000.0, run->output_rate_hz), kPositive);
  if (run->field_rate_hz > run->output_rate_hz)
    s.Fail("field_rate_hz",
           "must be at most run.output_rate_hz (" + FormatNumber("%.6g", run->output_rate_hz) +
               " Hz; got " + FormatNumber("%.6g", run->field_rate_hz) + ")");
  for (const std::string& name :
       s.Strings("outputs", {"contact_forces", "acceleration", "cage", "rollers", "energy"})) {
    Output o;
    if (!ParseOutput(name, &o)) {
      std::string list;
      for (const auto& k : KnownOutputs()) list += (list.empty() ? "" : ", ") + k;
      s.Fail("outputs", "unknown output \"" + name + "\" (known: " + list + ")");
    }
    outputs->push_back(o);
  }
  Section tol = s.Table("tolerance");
  SceneTolerance& t = run->tolerance;
  t.f_b = tol.Number("f_b", t.f_b, kPositive);
  t.f_c = tol.Number("f_c", t.f_c, kPositive);
  t.cage_slip = tol.Number("cage_slip", t.cage_slip, kPositive);
  t.roller_load = tol.Number("roller_load", t.roller_load, kPositive);
  tol.RejectUnknown();
  s.RejectUnknown();
}

void ReadSolver(Section s, SceneSolver* solver) {
  solver->time_step_safety = s.Number("time_step_safety", 0.9, {1e-3, 1.0, false, false});
  solver->threads = s.Integer("threads", 0, 0, 1024);
  solver->checkpoint_interval_s = s.Number("checkpoint_interval_s", 0.0, kNonNegative);
  solver->max_energy_error_percent =
      s.Number("max_energy_error_percent", 5.0, {0.0, 100.0, false, false});
  solver->lumped_step = Choice(s, "lumped_step", LumpedStep::kAccurate, kLumpedStepNames);
  s.RejectUnknown();
}

}  // namespace

const char* FidelityName(Fidelity fidelity) { return NameOf(kFidelityNames, fidelity); }
bool ParseFidelity(const std::string& name, Fidelity* fidelity) {
  return ParseName(kFidelityNames, name, fidelity);
}
const char* AdapterModelName(AdapterModel adapter) { return NameOf(kAdapterModelNames, adapter); }
bool ParseAdapterModel(const std::string& name, AdapterModel* adapter) {
  return ParseName(kAdapterModelNames, name, adapter);
}
const char* RaceContactName(RaceContact race_contact) {
  return NameOf(kRaceContactNames, race_contact);
}
bool ParseRaceContact(const std::string& name, RaceContact* race_contact) {
  return ParseName(kRaceContactNames, name, race_contact);
}
const char* StartPoseName(StartPose start) { return NameOf(kStartPoseNames, start); }
bool ParseStartPose(const std::string& name, StartPose* start) {
  return ParseName(kStartPoseNames, name, start);
}
const char* LumpedStepName(LumpedStep step) { return NameOf(kLumpedStepNames, step); }
bool ParseLumpedStep(const std::string& name, LumpedStep* step) {
  return ParseName(kLumpedStepNames, name, step);
}

bool Asks(const std::vector<Output>& outputs, Output output) {
  return std::find(outputs.begin(), outputs.end(), output) != outputs.end();
}

const char* AxisName(Axis axis) { return NameOf(kAxisNames, axis); }
bool ParseAxis(const std::string& name, Axis* axis) { return ParseName(kAxisNames, name, axis); }

const char* OutputName(Output output) { return NameOf(kOutputNames, output); }
bool ParseOutput(const std::string& name, Output* output) {
  return ParseName(kOutputNames, name, output);
}

std::vector<std::string> KnownOutputs() {
  std::vector<std::string> names;
  for (const auto& e : kOutputNames) names.push_back(e.name);
  return names;
}

toml::table ParseToml(const std::string& toml_text, const std::string& source_name) {
  try {
    return toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw InputError(source_name + ":" + std::to_string(e.source().begin.line) + ": " +
                     std::string(e.description()));
  }
}

void ApplyOverride(toml::table& table, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set '" + assignment + "': expected key.path=value");
  const std::string path = assignment.substr(0, eq);
  const std::string value = assignment.substr(eq + 1);
  std::vector<std::string> parts;
  for (std::size_t start = 0;;) {
    const auto dot = path.find('.', start);
    parts.push_back(path.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  for (const auto& p : parts)
    if (p.empty()) throw InputError("--set " + path + ": empty key component");

  // Parse the value as TOML; a bare word that is not TOML is a string.
  const std::string where = "--set " + path;
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value, where);
  } catch (const toml::parse_error&) {
    // A bare word: re-parse it as a quoted string so it keeps the "--set" source in messages.
    std::string quoted = "\"";
    for (char ch : value) {
      if (ch == '"' || ch == '\\') quoted += '\\';
      quoted += ch;
    }
    quoted += '"';
    try {
      parsed = toml::parse("v = " + quoted, where);
    } catch (const toml::parse_error& e) {
      throw InputError(where + ": cannot parse value '" + value + "'");
    }
  }
  toml::node& new_value = *parsed.get("v");

  // Walk to the parent container.
  toml::node* cur = &table;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& p = parts[i];
    if (auto t = cur->as_table()) {
      if (!t->contains(p)) {
        // Numeric next component: an array of tables; else a table.
        const bool next_index =
            !parts[i + 1].empty() && std::all_of(parts[i + 1].begin(), parts[i + 1].end(), IsDigit);
        if (next_index)
          t->insert(p, toml::array{});
        else
          t->insert(p, toml::table{});
      }
      cur = t->get(p);
    } else if (auto a = cur->as_array()) {
      if (!std::all_of(p.begin(), p.end(), IsDigit) || p.size() > 9)
        throw InputError(where + ": '" + p + "' must be an array index (at most 9 digits)");
      const std::size_t idx = std::stoul(p);
      if (idx == a->size()) a->push_back(toml::table{});
      if (idx >= a->size())
        throw InputError(where + ": index " + p + " out of range (array has " +
                         std::to_string(a->size()) + " elements)");
      cur = a->get(idx);
    } else {
      throw InputError(where + ": '" + p + "' is not a table");
    }
  }
  auto* parent = cur->as_table();
  if (!parent) throw InputError(where + ": parent of '" + parts.back() + "' is not a table");
  const std::string& leaf = parts.back();
  if (toml::node* old = parent->get(leaf)) {
    const bool float_from_int = old->is_floating_point() && new_value.is_integer();
    if (old->type() != new_value.type() && !float_from_int)
      throw InputError(where + ": expected " +
                       std::string(old->is_floating_point() ? "a number"
                                   : old->is_integer()      ? "an integer"
                                   : old->is_string()       ? "a string"
                                   : old->is_boolean()      ? "a boolean"
                                   : old->is_array()        ? "an array"
                                                            : "a table") +
                       " (got '" + value + "')");
    if (float_from_int) {
      parent->insert_or_assign(leaf, static_cast<double>(new_value.as_integer()->get()));
      return;
    }
  }
  parent->insert_or_assign(leaf, std::move(new_value));
}

Scene ParseScene(const std::string& toml_text,
                 const std::string& source_name,
                 const std::vector<std::string>& overrides) {
  toml::table root = ParseToml(toml_text, source_name);
  for (const auto& o : overrides) ApplyOverride(root, o);

  Scene scene;
  scene.source = source_name;
  Section top(&root, "", &scene.source);
  // Order matters: defects need the geometry, the model and mesh checks need the defects.
  ReadGeometry(top.Table("bearing"), &scene.geometry);
  ReadMaterials(top.Table("materials"), &scene.materials);
  ReadDefects(top, scene.geometry, &scene.defects);
  ReadOperation(top.Table("operation"), &scene.operation);
  ReadFriction(top.Table("friction"), &scene.friction);
  ReadDamping(top.Table("damping"), &scene.damping);
  ReadModel(top.Table("model"), scene.geometry, scene.defects, scene.friction, &scene.model);
  ReadMesh(top.Table("mesh"), scene.model, scene.defects, &scene.mesh);
  ReadSensors(top, scene.geometry, &scene.sensors);
  ReadRun(top.Table("run"), &scene.run, &scene.outputs);
  ReadSolver(top.Table("solver"), &scene.solver);
  top.RejectUnknown();
  // "auto" must find a model that runs the scene; the limits are those of the model it picks.
  if (scene.model.fidelity == Fidelity::kAuto) {
    const std::string conflict = AutoFidelityConflict(scene);
    if (!conflict.empty()) {
      const toml::node* node = root.at_path("run.outputs").node();
      throw InputError(Located(Where(scene.source, node), "run.outputs", conflict));
    }
  }
  if (const auto v = FindSceneLimitViolation(WithChosenFidelity(scene))) {
    const toml::node* node = root.at_path(v->key).node();
    throw InputError(Located(Where(scene.source, node), v->key, v->reason));
  }

  std::ostringstream os;
  os << root;
  scene.effective_toml = os.str();
  return scene;
}

Scene LoadScene(const std::string& path, const std::vector<std::string>& overrides) {
  // A folder opens as an empty stream on Linux and would run the default scene: refused, as are
  // read errors and endless devices.
  return ParseScene(ReadInputFile(path, "a scene file (TOML)"), path, overrides);
}

}  // namespace spallkit::sim
