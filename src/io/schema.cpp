#include "alphaflex/io/schema.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <map>
#include <set>

namespace alphaflex::input {

namespace {

std::string number_text(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace

std::string Range::text() const {
  if (!bounded()) return "";
  if (std::isfinite(lo) && std::isfinite(hi))
    return std::string("in ") + (lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + (hi_open ? ")" : "]");
  if (std::isfinite(lo)) return (lo_open ? "> " : "≥ ") + number_text(lo);
  return (hi_open ? "< " : "≤ ") + number_text(hi);
}

std::string Key::type_text() const {
  if (!shape.empty()) return shape;
  switch (type) {
    case KeyType::Number: return range.bounded() ? "number " + range.text() : "number";
    case KeyType::Integer:
      if (std::isfinite(range.lo) && std::isfinite(range.hi))
        return "integer " + number_text(range.lo) + "…" + number_text(range.hi);
      return range.bounded() ? "integer " + range.text() : "integer";
    case KeyType::Flag: return "on/off";
    case KeyType::Text: return "string";
    case KeyType::Vec2: return "[x, y]";
    case KeyType::Vec3: return "[x, y, z]";
    case KeyType::Choice: {
      std::string l;
      for (const auto& c : choices) l += (l.empty() ? "" : ", ") + ("`" + c + "`");
      return "one of " + l;
    }
    case KeyType::Function: return "number or time function";
    case KeyType::Interval: return "integer or wall time";
    case KeyType::Numbers: return range.bounded() ? "number or list of numbers, each " + range.text() : "number or list of numbers";
    case KeyType::Texts: return "list of strings";
    case KeyType::List: return "list";
    case KeyType::Map: return "map";
  }
  return "";
}

const Key* Schema::find(const std::string& key) const {
  for (const auto& k : keys)
    if (k.name == key) return &k;
  return nullptr;
}

std::string Schema::allowed() const {
  std::set<std::string> sorted;
  for (const auto& k : keys) sorted.insert(k.name);
  std::string l;
  for (const auto& k : sorted) l += (l.empty() ? "" : ", ") + k;
  return l;
}

std::string Schema::markdown() const {
  std::string t = "| key | type | unit | default | meaning, constraints |\n|---|---|---|---|---|\n";
  auto cell = [](std::string s) {  // a '|' inside a cell would end it
    for (size_t p = 0; (p = s.find('|', p)) != std::string::npos; p += 2) s.replace(p, 1, "\\|");
    return s.empty() ? std::string("–") : s;
  };
  for (const auto& k : keys)
    t += "| `" + k.name + "` | " + cell(k.type_text()) + " | " + cell(k.unit) + " | " + cell(k.fallback) + " | " +
         cell(k.doc) + " |\n";
  return t;
}

YAML::Node apply_override(YAML::Node root, const std::string& assignment, const std::string& option,
                          const std::string& label) {
  const std::string head = label + ": " + option + " " + assignment + ": ";
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError(head + "expected key.path=value (e.g. solver.h=1e-3)");
  const std::string key = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  auto index = [&](const YAML::Node& seq, const std::string& part) {
    if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos)
      throw InputError(head + "'" + part + "' names an entry of a list: expected an index 0, 1, ...");
    if (part.size() > 9 || std::stoul(part) >= seq.size())
      throw InputError(head + "index " + part + " is out of range (the list has " + std::to_string(seq.size()) + " entries)");
    return std::stoul(part);
  };
  try {
    YAML::Node cur = root;
    std::string walked;
    for (size_t i = 0; i + 1 < parts.size(); ++i) {
      if (cur.IsScalar())
        throw InputError(head + "'" + walked + "' is a value, not a map: it has no key '" + parts[i] + "'");
      if (cur.IsSequence()) {
        cur.reset(cur[index(cur, parts[i])]);
      } else {
        if (!cur[parts[i]]) cur[parts[i]] = YAML::Node(YAML::NodeType::Map);
        cur.reset(cur[parts[i]]);
      }
      walked += (walked.empty() ? "" : ".") + parts[i];
    }
    if (cur.IsScalar())
      throw InputError(head + "'" + walked + "' is a value, not a map: it has no key '" + parts.back() + "'");
    const YAML::Node v = YAML::Load(value);
    // `key=~` (or null): the key is removed, as if the scene had never given it (its default, or
    // for a block's `reduction` the full mesh). A list entry cannot be removed (the indices of the
    // others would move under the later assignments).
    if (v.IsNull() && !value.empty()) {
      if (cur.IsSequence()) throw InputError(head + "a list entry cannot be removed (only a key of a map)");
      if (!cur.IsMap() || !cur[parts.back()])
        throw InputError(head + "there is no key '" + parts.back() + "'" + (walked.empty() ? "" : " in '" + walked + "'") + " to remove");
      cur.remove(parts.back());
      return v;
    }
    if (cur.IsSequence()) cur[index(cur, parts.back())] = v;
    else cur[parts.back()] = v;
    return v;
  } catch (const YAML::Exception& e) {
    throw InputError(head + e.msg);
  }
}

void Reader::add_override(const YAML::Node& value, const std::string& assignment) {
  overrides_.emplace_back(value, assignment);
  if (value.IsSequence() || value.IsMap())
    for (const auto& child : value) add_override(value.IsMap() ? child.second : child, assignment);
}

void Reader::fail(const YAML::Node& at, const std::string& key, const std::string& what) const {
  std::ostringstream os;
  const std::string* from_set = nullptr;
  for (const auto& [node, text] : overrides_)
    if (at.IsDefined() && node.is(at)) from_set = &text;
  if (from_set) {
    os << file_ << ": " << option_ << " " << *from_set;
  } else {
    os << file_;
    if (at.IsDefined() && at.Mark().line >= 0) os << ":" << (at.Mark().line + 1);
  }
  os << ": " << key << ": " << what;
  throw InputError(os.str());
}

std::string Reader::where(const YAML::Node& at, const std::string& key) const {
  std::ostringstream os;
  os << file_;
  if (at.IsDefined() && at.Mark().line >= 0) os << ":" << (at.Mark().line + 1);
  os << ": " << key;
  return os.str();
}

void Reader::keys(const YAML::Node& map, const std::string& path, const Schema& schema) const {
  if (!map.IsMap()) fail(map, path, "expected a map of keys");
  std::set<std::string> seen;
  for (const auto& kv : map) {
    const std::string k = key_name(kv.first, path);
    if (!schema.find(k)) fail(kv.first, join(path, k), "unknown key (allowed here: " + schema.allowed() + ")");
    // yaml-cpp keeps both entries of a repeated key and reads the first: refuse it.
    if (!seen.insert(k).second) fail(kv.first, join(path, k), "given twice");
  }
}

std::string Reader::key_name(const YAML::Node& key, const std::string& path) const {
  if (!key.IsScalar()) fail(key, path.empty() ? "(top level)" : path, "expected key names, found a list or a map used as a key");
  return key.Scalar();
}

double Reader::number(const YAML::Node& n, const std::string& key) const {
  if (!n.IsScalar()) fail(n, key, "expected a number or an expression");
  const std::string text = n.Scalar();
  try {
    const double v = evaluate_expression(text, scope_);
    if (!std::isfinite(v)) fail(n, key, "'" + text + "' is not a finite number");
    // The model multiplies values (k·L², m·v², E·I): a value whose square is not a normal double
    // overflows or vanishes there (a mass of 1e308 made the first matrix singular: tests/fuzz).
    if (v != 0.0 && !(std::fabs(v) >= 1e-150 && std::fabs(v) <= 1e150))
      fail(n, key, "'" + text.substr(0, 60) + "' is out of range: expected 0 or a magnitude from 1e-150 to 1e150");
    return v;
  } catch (const std::invalid_argument& e) {
    fail(n, key, std::string("expected a number, ") + e.what());
  }
}

bool Reader::flag(const YAML::Node& n, const std::string& key) const {
  if (n.IsScalar()) {
    const std::string s = n.Scalar();
    if (s == "true" || s == "on" || s == "yes" || s == "1") return true;
    if (s == "false" || s == "off" || s == "no" || s == "0") return false;
  }
  fail(n, key, "expected on/off (or true/false)");
}

std::string Reader::text(const YAML::Node& n, const std::string& key) const {
  if (!n.IsScalar()) fail(n, key, "expected a string");
  // Names, types and file names are quoted in later messages: none longer than a path may be
  // (PATH_MAX), so that no message repeats kilobytes of a damaged file.
  constexpr size_t kMaxText = 4096;
  if (n.Scalar().size() > kMaxText)
    fail(n, key, "expected a string of at most " + std::to_string(kMaxText) + " characters, got " +
                     std::to_string(n.Scalar().size()));
  return n.Scalar();
}

std::string name_problem(const std::string& name) {
  const bool printable = std::all_of(name.begin(), name.end(), [](char c) { return c >= 0x20 && c <= 0x7e; });
  if (!name.empty() && name.size() <= 100 && printable && name.front() != ' ' && name.back() != ' ') return "";
  return "expected a name of 1 to 100 printable ASCII characters (letters, digits, punctuation, inner spaces; no control "
         "characters, no leading or trailing space), got " + std::to_string(name.size()) + " characters" +
         (printable ? std::string() : " with a control or non-ASCII character");
}

std::string escaped_name(const std::string& name) {
  std::string out;
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u <= 0x7e) {
      out += c;
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 15];
    }
  }
  return out.size() > 60 ? out.substr(0, 57) + "..." : out;
}

std::string Reader::item_name(const YAML::Node& item, const char* list, size_t i, const char* not_a_map,
                              std::string& path) const {
  path = std::string(list) + "[" + std::to_string(i) + "]";
  if (!item.IsMap()) fail(item, path, not_a_map);
  const std::string name = text(need(item, "name", path), path + ".name");
  const std::string why = name_problem(name);
  if (!why.empty()) fail(item["name"], path + ".name", why);
  path = std::string(list) + "[" + name + "]";
  return name;
}

std::string Reader::sensor_name(const YAML::Node& s, size_t i, std::set<std::string>& names, std::string& path) const {
  const std::string name = item_name(s, "sensors", i, "expected a map with name, type, ...", path);
  if (name == "t") fail(s["name"], path + ".name", "'t' is reserved for the time column of the CSV");
  if (!names.insert(name).second) fail(s["name"], path + ".name", "another sensor is named '" + name + "' already");
  if (name.find_first_of(",\"\n") != std::string::npos)
    fail(s["name"], path + ".name", "a sensor name may not contain commas or quotes");
  return name;
}

int Reader::choice(const YAML::Node& n, const std::string& key, const std::vector<std::string>& allowed) const {
  const std::string c = text(n, key);
  for (size_t k = 0; k < allowed.size(); ++k)
    if (c == allowed[k]) return static_cast<int>(k);
  std::string l;
  for (const auto& a : allowed) l += (l.empty() ? "" : ", ") + a;
  fail(n, key, "unknown " + key.substr(key.rfind('.') + 1) + " '" + c + "' (expected one of " + l + ")");
}

const std::vector<Schema>& time_function_schemas() {
  static const std::vector<Schema> s{
      {"time_functions.constant",
       {{"type", KeyType::Text, "–", kRequired, "`constant`"},
        {"value", KeyType::Number, "of the key", kRequired, "the value at every time"}}},
      {"time_functions.ramp",
       {{"type", KeyType::Text, "–", kRequired, "`ramp` (linear from t0 to t1) or `smooth_step` (from + (to − from)·(10x³ − 15x⁴ + 6x⁵), x = (t − t0)/(t1 − t0): twice continuously differentiable)"},
        {"t0", KeyType::Number, "s", kRequired, "start of the change; `from` before it"},
        {"t1", KeyType::Number, "s", kRequired, "end of the change; `to` after it; t1 > t0"},
        {"from", KeyType::Number, "of the key", "0", "value until t0"},
        {"to", KeyType::Number, "of the key", kRequired, "value from t1 on"}}},
      {"time_functions.linear",
       {{"type", KeyType::Text, "–", kRequired, "`linear`: offset + rate·t"},
        {"rate", KeyType::Number, "of the key per s", kRequired, "slope"},
        {"offset", KeyType::Number, "of the key", "0", "value at t = 0"}}},
      {"time_functions.spin_up",
       {{"type", KeyType::Text, "–", kRequired, "`spin_up`: an angle whose rate rises smoothly from 0 to `rate` over `time`, then stays"},
        {"rate", KeyType::Number, "of the key per s", kRequired, "final rate"},
        {"time", KeyType::Number, "s", kRequired, "duration of the spin-up; positive"}}},
      {"time_functions.sine",
       {{"type", KeyType::Text, "–", kRequired, "`sine`: offset + amplitude·sin(2π·frequency·t + phase)"},
        {"amplitude", KeyType::Number, "of the key", kRequired, "amplitude"},
        {"frequency", KeyType::Number, "Hz", kRequired, "frequency"},
        {"phase", KeyType::Number, "rad", "0", "phase at t = 0"},
        {"offset", KeyType::Number, "of the key", "0", "mean value"}}},
      {"time_functions.table",
       {{"type", KeyType::Text, "–", kRequired, "`table`: piecewise linear through the points, constant outside"},
        {"t", KeyType::List, "s", kRequired, "times, increasing"},
        {"values", KeyType::List, "of the key", kRequired, "values at those times, as many as `t`"}}},
  };
  return s;
}

TimeFunctionPtr Reader::function(const YAML::Node& n, const std::string& key) const {
  if (n.IsScalar()) return make_constant(number(n, key));
  if (!n.IsMap()) fail(n, key, "expected a number or a time function {type: ...}");
  const std::string type = text(need(n, "type", key), key + ".type");
  // ramp and smooth_step share one schema (and one docs table).
  const std::string schema_name = "time_functions." + (type == "smooth_step" ? std::string("ramp") : type);
  const Schema* schema = nullptr;
  std::string names;
  for (const auto& s : time_function_schemas()) {
    if (s.name == schema_name) schema = &s;
    const std::string t = s.name.substr(s.name.find('.') + 1);
    names += (names.empty() ? "" : ", ") + t + (t == "ramp" ? ", smooth_step" : "");
  }
  if (!schema) fail(n, key + ".type", "unknown time function '" + type + "' (expected " + names + ")");
  const Section f(*this, n, key, *schema);
  try {
    if (type == "constant") return make_constant(f.number("value"));
    if (type == "ramp" || type == "smooth_step") {
      const double t0 = f.number("t0"), t1 = f.number("t1"), v0 = f.number("from", 0.0), v1 = f.number("to");
      breakpoints_.insert(breakpoints_.end(), {t0, t1});
      return type == "ramp" ? make_ramp(t0, t1, v0, v1) : make_smooth_step(t0, t1, v0, v1);
    }
    if (type == "linear") return make_linear(f.number("rate"), f.number("offset", 0.0));
    if (type == "spin_up") {
      breakpoints_.push_back(f.number("time"));
      return make_spin_up(f.number("rate"), f.number("time"));
    }
    if (type == "sine")
      return make_sine(f.number("amplitude"), f.number("frequency"), f.number("phase", 0.0), f.number("offset", 0.0));
    // table
    std::vector<double> t, v;
    const YAML::Node nt = f.node("t"), nv = f.node("values");
    if (!nt.IsSequence() || !nv.IsSequence()) fail(n, key, "t and values must be lists of numbers");
    for (size_t i = 0; i < nt.size(); ++i) t.push_back(number(nt[i], key + ".t"));
    for (size_t i = 0; i < nv.size(); ++i) v.push_back(number(nv[i], key + ".values"));
    breakpoints_.insert(breakpoints_.end(), t.begin(), t.end());
    return make_table(t, v);
  } catch (const std::invalid_argument& e) {
    fail(n, key, e.what());
  }
}

void Reader::read_parameters(const YAML::Node& p) {
  if (!p) return;
  if (!p.IsMap()) fail(p, "parameters", "expected a map name: value");
  std::set<std::string> seen;
  for (const auto& kv : p) {
    const std::string name = key_name(kv.first, "parameters");
    // yaml-cpp keeps both entries of a repeated key; the last would silently win here.
    if (!seen.insert(name).second) fail(kv.first, "parameters." + name, "given twice");
    scope_[name] = number(kv.second, "parameters." + name);
  }
}

Section::Section(const Reader& rd, const YAML::Node& map, std::string path, const Schema& schema)
    : rd_(rd), map_(map), present_(map.IsDefined()), path_(std::move(path)), schema_(schema) {
  // An absent section reads as empty; a present one must be a map (`solver:` with nothing is not).
  if (present_) rd_.keys(map_, path_.empty() ? "(top level)" : path_, schema_);
}

const Key& Section::key(const std::string& name, KeyType type) const {
  const Key* k = schema_.find(name);
  // A program error, not an input error: the code reads a key its schema does not declare, or
  // with another type than declared (the docs would then say something else than the reader does).
  if (!k) throw std::logic_error("schema " + schema_.name + " has no key " + name);
  if (k->type != type && !(type == KeyType::Text && k->type == KeyType::Choice))
    throw std::logic_error("schema " + schema_.name + ": key " + name + " is read with another type than declared");
  return *k;
}

YAML::Node Section::node(const std::string& name) const {
  const Key* k = schema_.find(name);
  if (!k) throw std::logic_error("schema " + schema_.name + " has no key " + name);
  if (k->required() && present_ && map_.IsMap()) return rd_.need(map_, name, path_);
  return has(name) ? map_[name] : YAML::Node(YAML::NodeType::Undefined);
}

double Section::checked(const Key& k, const YAML::Node& n, double v, const std::string& at) const {
  if (k.range.contains(v)) return v;
  const std::string key = at.empty() ? key_path(k.name) : at, got = ", got " + n.Scalar();
  const std::string noun = k.noun.empty() ? "value" + std::string(k.unit == "–" ? "" : " (" + k.unit + ")") : k.noun;
  if (k.range.lo == 0.0 && !std::isfinite(k.range.hi))
    rd_.fail(n, key, std::string("expected a ") + (k.range.lo_open ? "positive " : "non-negative ") + noun + got);
  rd_.fail(n, key, "expected " + noun + " " + k.range.text() + got);
}

double Section::number(const std::string& name, double fallback) const {
  const Key& k = key(name, KeyType::Number);
  const YAML::Node n = node(name);
  if (!n.IsDefined()) return fallback;
  return checked(k, n, rd_.number(n, key_path(name)));
}

int Section::integer(const std::string& name, int fallback) const {
  const Key& k = key(name, KeyType::Integer);
  const YAML::Node n = node(name);
  if (!n.IsDefined()) return fallback;
  const int lo = std::isfinite(k.range.lo) ? static_cast<int>(k.range.lo) : -1000000;
  const int hi = std::isfinite(k.range.hi) ? static_cast<int>(k.range.hi) : 1000000;
  return rd_.integer(n, key_path(name), lo, hi);
}

bool Section::flag(const std::string& name, bool fallback) const {
  return value<bool>(name, KeyType::Flag, fallback, &Reader::flag);
}

std::string Section::text(const std::string& name, const std::string& fallback) const {
  return value<std::string>(name, KeyType::Text, fallback, &Reader::text);
}

Eigen::Vector2d Section::vec2(const std::string& name, const Eigen::Vector2d& fallback) const {
  return value<Eigen::Vector2d>(name, KeyType::Vec2, fallback, &Reader::vec2);
}

Eigen::Vector3d Section::vec3(const std::string& name, const Eigen::Vector3d& fallback) const {
  return value<Eigen::Vector3d>(name, KeyType::Vec3, fallback, &Reader::vec3);
}

Eigen::Vector3d Section::direction(const std::string& name, const Eigen::Vector3d& fallback) const {
  return value<Eigen::Vector3d>(name, KeyType::Vec3, fallback, &Reader::direction);
}

int Section::choice(const std::string& name, int fallback) const {
  const Key& k = key(name, KeyType::Choice);
  const YAML::Node n = node(name);
  return n.IsDefined() ? rd_.choice(n, key_path(name), k.choices) : fallback;
}

TimeFunctionPtr Section::function(const std::string& name) const {
  key(name, KeyType::Function);
  const YAML::Node n = node(name);
  return n.IsDefined() ? rd_.function(n, key_path(name)) : nullptr;
}

Section::Interval Section::interval(const std::string& name) const {
  const Key& k = key(name, KeyType::Interval);
  Interval out;
  const YAML::Node n = node(name);
  if (!n.IsDefined()) return out;
  // A whole number of steps, or a wall time with its unit: "600 s", "10 min", "2 h".
  const std::string expected = "expected a number of steps (an integer >= " + number_text(k.range.lo) +
                               ") or a wall time with its unit, e.g. \"600 s\", \"10 min\", \"2 h\"";
  std::istringstream in(n.IsScalar() ? n.Scalar() : std::string());
  std::string number, unit, rest;
  in >> number >> unit;
  if (!unit.empty()) {
    in >> rest;
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(number.c_str(), &end);
    if (errno == ERANGE || !std::isfinite(value))  // "1e400 h": say so, not "unexpected 'h'" (issue 24)
      rd_.fail(n, key_path(name), expected + " (" + number + " is out of the range of a double)");
    if (*end != '\0' || !(value > 0.0) || !rest.empty() || (unit != "s" && unit != "min" && unit != "h"))
      rd_.fail(n, key_path(name), expected);
    out.seconds = value * (unit == "s" ? 1.0 : unit == "min" ? 60.0 : 3600.0);
    return out;
  }
  if (!n.IsScalar()) rd_.fail(n, key_path(name), expected);
  const int hi = std::isfinite(k.range.hi) ? static_cast<int>(k.range.hi) : 1000000000;
  out.steps = rd_.integer(n, key_path(name), static_cast<int>(k.range.lo), hi);
  return out;
}

std::vector<double> Section::numbers(const std::string& name) const {
  const Key& k = key(name, KeyType::Numbers);
  const YAML::Node n = node(name);
  if (!n.IsDefined()) return {};
  if (n.IsScalar()) return {checked(k, n, rd_.number(n, key_path(name)))};
  if (!n.IsSequence() || n.size() == 0) rd_.fail(n, key_path(name), "expected a list of " + k.noun + "s, e.g. [1e-3, 5e-4]");
  std::vector<double> v;
  for (size_t i = 0; i < n.size(); ++i) {
    const std::string at = key_path(name) + "[" + std::to_string(i) + "]";
    v.push_back(checked(k, n[i], rd_.number(n[i], at), at));
  }
  return v;
}

std::vector<std::string> Section::texts(const std::string& name) const {
  key(name, KeyType::Texts);
  const YAML::Node n = node(name);
  if (!n.IsDefined()) return {};
  const auto nonempty = [&](const YAML::Node& x, const std::string& at) {
    if (!x.IsScalar() || x.Scalar().empty()) rd_.fail(x, at, "expected a non-empty string");
    return rd_.text(x, at);
  };
  if (n.IsScalar()) return {nonempty(n, key_path(name))};  // one string for a list of one
  if (!n.IsSequence()) rd_.fail(n, key_path(name), "expected a list of strings");
  std::vector<std::string> v;
  for (size_t i = 0; i < n.size(); ++i) v.push_back(nonempty(n[i], key_path(name) + "[" + std::to_string(i) + "]"));
  return v;
}

std::string update_key_tables(const std::string& document, const std::vector<const Schema*>& schemas,
                              const std::string& label, std::vector<std::string>* unused) {
  std::set<std::string> used;
  std::map<std::string, const Schema*> by_name;
  for (const Schema* s : schemas) by_name[s->name] = s;
  const std::string open = "<!-- keys:", close = "<!-- /keys -->";
  std::string out;
  size_t pos = 0;
  for (;;) {
    const size_t a = document.find(open, pos);
    if (a == std::string::npos) break;
    const size_t name_end = document.find(" -->", a);
    if (name_end == std::string::npos) throw InputError(label + ": a `" + open + "NAME -->` marker is not closed");
    const std::string name = document.substr(a + open.size(), name_end - a - open.size());
    const auto it = by_name.find(name);
    if (it == by_name.end()) throw InputError(label + ": `" + open + name + " -->`: no schema is named '" + name + "'");
    const size_t b = document.find(close, name_end);
    if (b == std::string::npos) throw InputError(label + ": `" + open + name + " -->` has no `" + close + "`");
    out += document.substr(pos, name_end + 4 - pos) + "\n" + it->second->markdown();
    used.insert(name);
    pos = b;
  }
  if (unused)
    for (const Schema* s : schemas)
      if (!used.count(s->name)) unused->push_back(s->name);
  return out + document.substr(pos);
}

}  // namespace alphaflex::input
