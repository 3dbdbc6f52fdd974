#include "study/sweep.h"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"
#include "study/random_stream.h"

namespace spallkit::study {
namespace {

constexpr const char* kCountKey = "defects.count";
constexpr const char* kRollersKey = "defects.rollers";
constexpr const char* kEveryDefect = "defects.*.";

std::string Where(const std::string& source, const toml::node& node, const std::string& key) {
  std::string out = source;
  if (const auto line = node.source().begin.line; line > 0) {
    out += ':';
    out += std::to_string(line);
  }
  out += ": ";
  return out + key;
}

// A TOML value (scalar or array of them) as JSON; tables are not parameter values.
nlohmann::json ToJson(const toml::node& node, const std::string& where) {
  if (auto v = node.as_integer()) return v->get();
  if (auto v = node.as_floating_point()) return v->get();
  if (auto v = node.as_boolean()) return v->get();
  if (auto v = node.as_string()) return v->get();
  if (auto a = node.as_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const toml::node& e : *a) out.push_back(ToJson(e, where));
    return out;
  }
  throw InputError(where + ": expected a number, string, boolean or array");
}

double Number(const toml::node& node, const std::string& where) {
  if (auto v = node.as_integer()) return static_cast<double>(v->get());
  if (auto v = node.as_floating_point())
    if (std::isfinite(v->get())) return v->get();
  throw InputError(where + ": expected a finite number");
}

RandomParameter ParseRandom(const std::string& key,
                            const toml::node& node,
                            const std::string& where) {
  const toml::table* t = node.as_table();
  if (!t || t->size() != 1)
    throw InputError(where +
                     ": expected one of { uniform = [lo, hi] }, { log_uniform = [lo, hi] }, "
                     "{ integers = [lo, hi] }, { choice = [...] }");
  RandomParameter p;
  p.key = key;
  const auto entry = t->begin();  // the iterator owns the key/value pair it yields
  const auto& [kind, value] = *entry;
  const std::string kind_name(kind.str());
  const toml::array* a = value.as_array();
  if (!a || a->empty()) throw InputError(where + "." + kind_name + ": expected a non-empty array");
  if (kind_name == "choice") {
    p.kind = RandomParameter::Kind::kChoice;
    for (const toml::node& e : *a) p.choices.push_back(ToJson(e, where + ".choice"));
    return p;
  }
  if (a->size() != 2) throw InputError(where + "." + kind_name + ": expected [lo, hi]");
  p.low = Number(*a->get(0), where + "." + kind_name);
  p.high = Number(*a->get(1), where + "." + kind_name);
  if (!(p.low <= p.high)) throw InputError(where + "." + kind_name + ": expected lo <= hi");
  if (kind_name == "uniform") {
    p.kind = RandomParameter::Kind::kUniform;
  } else if (kind_name == "log_uniform") {
    p.kind = RandomParameter::Kind::kLogUniform;
    if (!(p.low > 0)) throw InputError(where + ".log_uniform: expected 0 < lo <= hi");
  } else if (kind_name == "integers") {
    p.kind = RandomParameter::Kind::kIntegers;
    if (p.low != std::floor(p.low) || p.high != std::floor(p.high))
      throw InputError(where + ".integers: expected integer bounds");
  } else {
    throw InputError(where + ": unknown distribution '" + kind_name +
                     "' (expected uniform, log_uniform, integers or choice)");
  }
  return p;
}

void CheckSweepKey(const std::string& key, const nlohmann::json& value, const std::string& where) {
  if (key == kCountKey && !(value.is_number_integer() && value.get<long long>() >= 0))
    throw InputError(where + ": expected an integer >= 0");
  if (key == kRollersKey) {
    bool ok = value.is_array();
    if (ok)
      for (const auto& r : value) ok = ok && r.is_number_integer() && r.get<long long>() >= 0;
    if (!ok) throw InputError(where + ": expected an array of roller indices (integers >= 0)");
  }
}

std::string Quote(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    if (ch == '\n') {
      out += "\\n";
      continue;
    }
    out += ch;
  }
  return out + "\"";
}

// Index of the defect a "defects.<i>.<key>" assignment names; -1 for other keys.
int DefectIndex(const std::string& key) {
  if (key.rfind("defects.", 0) != 0) return -1;
  const std::string rest = key.substr(8);
  const auto dot = rest.find('.');
  const std::string idx = rest.substr(0, dot);
  if (idx.empty() || !std::all_of(idx.begin(), idx.end(), ::isdigit)) return -1;
  return std::stoi(idx);
}

// The base scene's defects (as tables), for copying when a case adds defects.
std::vector<toml::table> BaseDefects(const Sweep& sweep) {
  std::vector<toml::table> out;
  toml::table root = sim::ParseToml(sweep.base_text, sweep.base_scene);
  if (auto* arr = root["defects"].as_array())
    for (auto& d : *arr)
      if (auto* t = d.as_table()) out.push_back(*t);
  return out;
}

// How many defects the base scene has: its [[defects]], or the scene's default (the paper's
// spall) when it lists none.
int BaseDefectCount(const Sweep& sweep) {
  const toml::table root = sim::ParseToml(sweep.base_text, sweep.base_scene);
  if (const auto* arr = root["defects"].as_array()) return static_cast<int>(arr->size());
  static const int kDefault = static_cast<int>(sim::ParseScene("", "default.toml").defects.size());
  return kDefault;
}

// Assignments that give the scene exactly `rollers.size()` defects on those rollers.
void DefectAssignments(const Sweep& sweep,
                       const std::vector<long long>& rollers,
                       std::vector<std::string>* out) {
  const std::vector<toml::table> base = BaseDefects(sweep);
  out->push_back("defects=[]");
  for (size_t i = 0; i < rollers.size(); ++i) {
    const std::string prefix = "defects." + std::to_string(i) + ".";
    out->push_back(prefix + "roller=" + std::to_string(rollers[i]));
    if (base.empty()) continue;
    const toml::table& tmpl = base[std::min(i, base.size() - 1)];
    for (const auto& [k, v] : tmpl) {
      if (k.str() == "roller") continue;
      out->push_back(prefix + std::string(k.str()) + "=" +
                     TomlValueText(ToJson(v, sweep.base_scene + ": defects")));
    }
  }
}

// Rollers for "defects.count" = n: the base defects' rollers, then the next roller numbers.
std::vector<long long> RollersForCount(const Sweep& sweep, long long n) {
  // A bound before the list is built (a bearing has tens of rollers; the case scene checks the
  // numbers against its own).
  if (n < 0 || n > 1000)
    throw InputError(std::string(kCountKey) + " = " + std::to_string(n) +
                     ": expected 0 to 1000 defective rollers (at most the bearing's roller count)");
  std::vector<long long> rollers;
  long long next = 0;
  for (const toml::table& d : BaseDefects(sweep)) {
    if ((long long)rollers.size() == n) break;
    long long r = 0;
    if (auto v = d["roller"].value<long long>()) r = *v;
    rollers.push_back(r);
    next = r + 1;
  }
  while ((long long)rollers.size() < n) rollers.push_back(next++);
  return rollers;
}

}  // namespace

std::string TomlValueText(const nlohmann::json& value) {
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_integer()) return std::to_string(value.get<long long>());
  if (value.is_number_unsigned()) return std::to_string(value.get<unsigned long long>());
  if (value.is_number_float()) {
    // Shortest text that reads back bit-exactly, always with a '.' or an exponent (a float).
    char buf[64];
    const double x = value.get<double>();
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
    std::string s(buf, end);
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return s;
  }
  if (value.is_string()) return Quote(value.get<std::string>());
  if (value.is_array()) {
    std::string s = "[";
    for (size_t i = 0; i < value.size(); ++i) {
      if (i) s += ", ";
      s += TomlValueText(value[i]);
    }
    return s + "]";
  }
  throw InputError("sweep: unsupported value " + value.dump());
}

int Sweep::num_cases() const {
  long long n = random_cases;
  for (const auto& [key, values] : grid) n *= static_cast<long long>(values.size());
  return static_cast<int>(n);
}

std::vector<std::string> Sweep::ParameterKeys() const {
  std::vector<std::string> keys;
  for (const auto& g : grid) keys.push_back(g.first);
  for (const auto& r : random) keys.push_back(r.key);
  return keys;
}

Sweep ParseSweep(const std::string& toml_text,
                 const std::string& source_name,
                 const std::string& base_dir) {
  toml::table root = sim::ParseToml(toml_text, source_name);
  Sweep sweep;
  sweep.path = source_name;
  sweep.text = toml_text;
  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (key != "base" && key != "grid" && key != "random" && key != "post")
      throw InputError(Where(source_name, v, key) +
                       ": unknown table (expected [base], [grid], [random], [post])");
  }

  // [base]
  const toml::table* base = root["base"].as_table();
  if (!base) throw InputError(source_name + ": [base] with scene = \"...\" is required");
  for (const auto& [k, v] : *base) {
    const std::string key(k.str());
    const std::string where = Where(source_name, v, "base." + key);
    if (key == "scene") {
      auto s = v.value<std::string>();
      if (!s || s->empty()) throw InputError(where + ": expected a file name");
      std::filesystem::path p(*s);
      if (p.is_relative() && !base_dir.empty()) p = std::filesystem::path(base_dir) / p;
      sweep.base_scene = p.lexically_normal().string();
    } else if (key == "set") {
      const toml::table* set = v.as_table();
      if (!set) throw InputError(where + ": expected a table of \"key\" = value");
      for (const auto& [sk, sv] : *set) {
        const std::string skey(sk.str());
        const std::string swhere = Where(source_name, sv, "base.set." + skey);
        if (sv.is_table())
          throw InputError(swhere + ": expected a value; quote dotted keys (\"a.b\" = 1)");
        nlohmann::json value = ToJson(sv, swhere);
        CheckSweepKey(skey, value, swhere);
        sweep.base_set.emplace_back(skey, std::move(value));
      }
    } else {
      throw InputError(where + ": unknown key (expected scene, set)");
    }
  }
  if (sweep.base_scene.empty()) throw InputError(source_name + ": [base] scene is required");
  try {
    sweep.base_text = ReadInputFile(sweep.base_scene, "a scene file (TOML)");
  } catch (const InputError& e) {
    throw InputError(source_name + ": base.scene: " + e.what());
  }

  std::set<std::string> varied;
  // [grid]
  if (const toml::node* g = root.get("grid")) {
    const toml::table* grid = g->as_table();
    if (!grid) throw InputError(Where(source_name, *g, "grid") + ": expected a table");
    for (const auto& [k, v] : *grid) {
      const std::string key(k.str());
      const std::string where = Where(source_name, v, "grid." + key);
      const toml::array* a = v.as_array();
      if (!a || a->empty())
        throw InputError(where + ": expected a non-empty list of values; quote dotted keys");
      std::vector<nlohmann::json> values;
      for (const toml::node& e : *a) {
        values.push_back(ToJson(e, where));
        CheckSweepKey(key, values.back(), where);
      }
      sweep.grid.emplace_back(key, std::move(values));
      varied.insert(key);
    }
  }
  // [random]
  if (const toml::node* r = root.get("random")) {
    const toml::table* random = r->as_table();
    if (!random) throw InputError(Where(source_name, *r, "random") + ": expected a table");
    for (const auto& [k, v] : *random) {
      const std::string key(k.str());
      const std::string where = Where(source_name, v, "random." + key);
      if (key == "cases") {
        auto n = v.value<long long>();
        if (!v.is_integer() || !n || *n < 1 || *n > 10000000)
          throw InputError(where + ": expected an integer >= 1");
        sweep.random_cases = static_cast<int>(*n);
      } else if (key == "seed") {
        auto s = v.value<long long>();
        if (!v.is_integer() || !s || *s < 0) throw InputError(where + ": expected an integer >= 0");
        sweep.seed = static_cast<unsigned long long>(*s);
      } else {
        if (varied.count(key)) throw InputError(where + ": already varied in [grid]");
        sweep.random.push_back(ParseRandom(key, v, where));
        if (sweep.random.back().kind == RandomParameter::Kind::kChoice)
          for (const auto& c : sweep.random.back().choices) CheckSweepKey(key, c, where);
        varied.insert(key);
      }
    }
  }
  // [post]
  if (const toml::node* p = root.get("post")) {
    const toml::table* post = p->as_table();
    if (!post) throw InputError(Where(source_name, *p, "post") + ": expected a table");
    for (const auto& [k, v] : *post) {
      const std::string key(k.str());
      const std::string where = Where(source_name, v, "post." + key);
      if (key == "noise_snr_db") {
        sweep.post.noise_snr_db = Number(v, where);
        if (!(std::abs(sweep.post.noise_snr_db) <= 200.0))
          throw InputError(where + ": expected a signal-to-noise ratio in [-200, 200] dB");
      } else if (key == "diagnose") {
        if (!v.is_boolean()) throw InputError(where + ": expected true or false");
        sweep.post.diagnose = *v.value<bool>();
      } else {
        throw InputError(where + ": unknown key (expected noise_snr_db, diagnose)");
      }
    }
  }
  if (varied.count(kCountKey) && varied.count(kRollersKey))
    throw InputError(source_name + ": vary either defects.count or defects.rollers, not both");
  const long long total = [&] {
    long long n = sweep.random_cases;
    for (const auto& g : sweep.grid) n *= static_cast<long long>(g.second.size());
    return n;
  }();
  if (total > 10000000) throw InputError(source_name + ": more than 10^7 cases");
  // Every case must make a valid scene: check the first one now, so a typo fails up front.
  CaseScene(sweep, MakeCase(sweep, 0));
  return sweep;
}

Sweep LoadSweep(const std::string& path) {
  return ParseSweep(ReadInputFile(path, "a sweep file (TOML)"),
                    path,
                    std::filesystem::path(path).parent_path().string());
}

std::string CaseId(int index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "case-%05d", index);
  return buf;
}

SweepCase MakeCase(const Sweep& sweep, int index) {
  if (index < 0 || index >= sweep.num_cases())
    throw InputError(sweep.path + ": case " + std::to_string(index) + " out of range (" +
                     std::to_string(sweep.num_cases()) + " cases)");
  SweepCase c;
  c.index = index;
  c.id = CaseId(index);
  // Grid point (first key slowest), then the draw.
  int rest = index / sweep.random_cases;
  std::vector<int> pick(sweep.grid.size());
  for (size_t g = sweep.grid.size(); g-- > 0;) {
    const int n = static_cast<int>(sweep.grid[g].second.size());
    pick[g] = rest % n;
    rest /= n;
  }
  for (size_t g = 0; g < sweep.grid.size(); ++g)
    c.parameters.emplace_back(sweep.grid[g].first, sweep.grid[g].second[pick[g]]);
  RandomStream rng(sweep.seed, static_cast<unsigned long long>(index));
  for (const RandomParameter& p : sweep.random) {
    nlohmann::json value;
    switch (p.kind) {
      case RandomParameter::Kind::kUniform:
        value = p.low + (p.high - p.low) * rng.Uniform();
        break;
      case RandomParameter::Kind::kLogUniform:
        value = std::exp(std::log(p.low) + (std::log(p.high) - std::log(p.low)) * rng.Uniform());
        break;
      case RandomParameter::Kind::kIntegers:
        value =
            static_cast<long long>(p.low) +
            static_cast<long long>(rng.Below(static_cast<unsigned long long>(p.high - p.low) + 1));
        break;
      case RandomParameter::Kind::kChoice:
        value = p.choices[rng.Below(p.choices.size())];
        break;
    }
    c.parameters.emplace_back(p.key, std::move(value));
  }
  return c;
}

std::vector<SweepCase> MakeCases(const Sweep& sweep) {
  std::vector<SweepCase> cases;
  for (int i = 0; i < sweep.num_cases(); ++i) cases.push_back(MakeCase(sweep, i));
  return cases;
}

std::vector<std::string> CaseOverrides(const Sweep& sweep, const SweepCase& c) {
  std::vector<std::pair<std::string, nlohmann::json>> all = sweep.base_set;
  all.insert(all.end(), c.parameters.begin(), c.parameters.end());
  std::vector<std::string> out;
  // Which rollers are defective first; later entries win.
  int defects = -1;  // -1: the case does not set the defect list
  for (const auto& [key, value] : all) {
    std::vector<long long> rollers;
    if (key == kCountKey) {
      rollers = RollersForCount(sweep, value.get<long long>());
    } else if (key == kRollersKey) {
      for (const auto& r : value) rollers.push_back(r.get<long long>());
    } else {
      continue;
    }
    std::vector<std::string> assignments;
    DefectAssignments(sweep, rollers, &assignments);
    out.swap(assignments);
    defects = static_cast<int>(rollers.size());
  }
  for (const auto& [key, value] : all) {
    if (key == kCountKey || key == kRollersKey) continue;
    if (key.rfind(kEveryDefect, 0) == 0) {  // "defects.*.width_mm": every defect of the case
      // Without a count or roller list, the base scene's own defects.
      const int n = defects >= 0 ? defects : BaseDefectCount(sweep);
      for (int i = 0; i < n; ++i)
        out.push_back("defects." + std::to_string(i) + "." + key.substr(10) + "=" +
                      TomlValueText(value));
      continue;
    }
    if (defects >= 0 && DefectIndex(key) >= defects) continue;
    out.push_back(key + "=" + TomlValueText(value));
  }
  return out;
}

sim::Scene CaseScene(const Sweep& sweep, const SweepCase& c) {
  std::vector<std::string> overrides;
  const bool threads_set = std::any_of(sweep.base_set.begin(),
                                       sweep.base_set.end(),
                                       [](const auto& kv) { return kv.first == "solver.threads"; });
  if (!threads_set) overrides.push_back("solver.threads=1");
  for (std::string& o : CaseOverrides(sweep, c)) overrides.push_back(std::move(o));
  try {
    return sim::ParseScene(sweep.base_text, sweep.base_scene, overrides);
  } catch (const InputError& e) {
    throw InputError(sweep.path + ": " + c.id + ": " + e.what());
  }
}

}  // namespace spallkit::study
