#include "mutator.hpp"

#include <algorithm>
#include <cctype>
#include <utility>

namespace alphaflex::fuzz {

std::uint64_t Rng::next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::uint64_t stable_hash(const std::string& text, std::uint64_t basis) {
  std::uint64_t h = basis;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

namespace {

// Lines without their '\n'; join() puts them back (the last line keeps whether it had one).
struct Lines {
  std::vector<std::string> lines;
  bool final_newline = true;
};

Lines split(const std::string& text) {
  Lines l;
  std::string cur;
  for (char c : text) {
    if (c == '\n') {
      l.lines.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  l.final_newline = cur.empty();
  if (!cur.empty()) l.lines.push_back(cur);
  return l;
}

std::string join(const Lines& l) {
  std::string out;
  for (size_t i = 0; i < l.lines.size(); ++i) {
    out += l.lines[i];
    if (i + 1 < l.lines.size() || l.final_newline) out += '\n';
  }
  return out;
}

/// A line as it appears in a log entry: short, control bytes escaped.
std::string shown(const std::string& s, size_t max = 60) {
  std::string out;
  for (unsigned char c : s.substr(0, max)) {
    if (c >= 32 && c < 127) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (s.size() > max) out += "...(" + std::to_string(s.size()) + " bytes)";
  return "'" + out + "'";
}

std::string where(size_t line) { return "line " + std::to_string(line + 1); }

bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

/// [begin, end) of every number in `s` (outside comments): 12, -3.5, .5, 1e-3, +2E+8.
std::vector<std::pair<size_t, size_t>> numbers(const std::string& s) {
  std::vector<std::pair<size_t, size_t>> out;
  const size_t stop = std::min(s.find('#'), s.size());
  size_t i = 0;
  while (i < stop) {
    const bool boundary = i == 0 || !(ident_char(s[i - 1]) || s[i - 1] == '.');
    size_t j = i;
    if (boundary && j < stop && (s[j] == '-' || s[j] == '+')) ++j;
    const size_t digits_from = j;
    while (j < stop && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
    if (j < stop && s[j] == '.') {
      ++j;
      while (j < stop && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
    }
    const bool has_digit = j > digits_from && !(j == digits_from + 1 && s[digits_from] == '.');
    if (boundary && has_digit) {
      if (j < stop && (s[j] == 'e' || s[j] == 'E')) {
        size_t k = j + 1;
        if (k < stop && (s[k] == '-' || s[k] == '+')) ++k;
        if (k < stop && std::isdigit(static_cast<unsigned char>(s[k]))) {
          while (k < stop && std::isdigit(static_cast<unsigned char>(s[k]))) ++k;
          j = k;
        }
      }
      if (j >= stop || !ident_char(s[j])) {
        out.emplace_back(i, j);
        i = j;
        continue;
      }
    }
    ++i;
  }
  return out;
}

/// [begin, end) of every `key` followed by ':' and a blank or the end of the line (YAML keys).
std::vector<std::pair<size_t, size_t>> keys(const std::string& s) {
  std::vector<std::pair<size_t, size_t>> out;
  const size_t stop = std::min(s.find('#'), s.size());
  for (size_t i = 0; i < stop; ++i) {
    if (!(std::isalpha(static_cast<unsigned char>(s[i])) || s[i] == '_') || (i > 0 && ident_char(s[i - 1]))) continue;
    size_t j = i;
    while (j < stop && ident_char(s[j])) ++j;
    if (j < stop && s[j] == ':' && (j + 1 >= s.size() || s[j + 1] == ' ')) out.emplace_back(i, j);
    i = j;
  }
  return out;
}

/// Whitespace-separated tokens of an MSH line: [begin, end).
std::vector<std::pair<size_t, size_t>> tokens(const std::string& s) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    if (j > i) out.emplace_back(i, j);
    i = j;
  }
  return out;
}

// Edge values for numbers in a scene: zero, signs, the ends of double and of int, non-finite
// spellings (YAML's and C's), non-numbers, expressions that overflow or divide by zero.
const std::vector<std::string> kSceneValues = {
    "0", "-1", "1", "-0", "0.5", "1e308", "-1e308", "1e-308", "4.9e-324", "1e400", "nan", ".nan", "NaN", "inf",
    ".inf", "-.inf", "-inf", "2147483647", "2147483648", "-2147483649", "4294967296", "9223372036854775808",
    "18446744073709551616", "99999999999999999999999", "abc", "''", "\"\"", "~", "null", "true", "0x10", "1/0",
    "0/0", "1e308*10", "sqrt(-1)", "log(0)", "(", "1e", "--1", "[]", "{}", "[1, 2]"};
// Values a key could hold instead of its own: another type, or an empty one.
const std::vector<std::string> kShapes = {"[]", "{}", "~", "''", "[1, 2, 3]", "{a: 1}", "[[1, 2], [3, 4]]", "[x]", "-"};
// Bytes that mean something to YAML, to the expression parser, or to nothing (NUL, invalid UTF-8).
const std::string kSpecialBytes = std::string("\0\t\r\n :-[]{},#&*!|>'\"%@`?^()/\\", 28) + "\xff\xfe\xc3\x80\x7f";
// Edge values for MSH integers: counts and tags.
const std::vector<std::string> kMshInts = {"0", "-1", "1", "2", "3", "7", "1000000", "2147483647", "2147483648",
                                           "4294967295", "4294967296", "9223372036854775807", "18446744073709551615",
                                           "99999999999999999999", "-2147483648", "x", "1.5", ""};
const std::vector<std::string> kMshReals = {"nan", "-nan", "inf", "-inf", "1e308", "-1e308", "1e400", "1e-320", "0", "x",
                                            "1e200", "-1e160"};  // finite, but their squares are not (issue 24)

/// Replaces [b, e) of `s`.
std::string replaced(const std::string& s, size_t b, size_t e, const std::string& with) {
  return s.substr(0, b) + with + s.substr(e);
}

/// A random line index whose line satisfies `ok`, or npos.
template <class F>
size_t line_where(const Lines& l, Rng& rng, F ok) {
  std::vector<size_t> c;
  for (size_t i = 0; i < l.lines.size(); ++i)
    if (ok(l.lines[i])) c.push_back(i);
  return c.empty() ? std::string::npos : rng.pick(c);
}

bool contentful(const std::string& s) {
  const size_t p = s.find_first_not_of(' ');
  return p != std::string::npos && s[p] != '#';
}

/// Line-level mutations common to both kinds of file; false if the file has no lines.
bool line_mutation(Lines& l, Rng& rng, std::vector<std::string>& log) {
  if (l.lines.empty()) return false;
  const size_t i = rng.below(l.lines.size());
  switch (rng.below(3)) {
    case 0:
      log.push_back(where(i) + ": deleted " + shown(l.lines[i]));
      l.lines.erase(l.lines.begin() + static_cast<long>(i));
      break;
    case 1:
      log.push_back(where(i) + ": duplicated " + shown(l.lines[i]));
      l.lines.insert(l.lines.begin() + static_cast<long>(i), l.lines[i]);
      break;
    default: {
      const size_t k = rng.percent(50) ? std::min(i + 1, l.lines.size() - 1) : rng.below(l.lines.size());
      log.push_back(where(i) + " and " + where(k) + ": swapped " + shown(l.lines[i]) + " and " + shown(l.lines[k]));
      std::swap(l.lines[i], l.lines[k]);
    }
  }
  return true;
}

std::string truncate(const std::string& text, Rng& rng, std::vector<std::string>& log) {
  const size_t at = text.empty() ? 0 : rng.below(text.size());
  log.push_back("cut off after byte " + std::to_string(at) + " of " + std::to_string(text.size()));
  return text.substr(0, at);
}

std::string random_bytes(std::string text, Rng& rng, std::vector<std::string>& log) {
  const size_t n = 1 + rng.below(8);
  for (size_t k = 0; k < n; ++k) {
    const char c = rng.percent(60) ? kSpecialBytes[rng.below(kSpecialBytes.size())] : static_cast<char>(rng.below(256));
    const size_t at = text.empty() ? 0 : rng.below(text.size() + 1);
    const bool overwrite = at < text.size() && rng.percent(50);
    log.push_back(std::string(overwrite ? "overwrote" : "inserted") + " byte " + shown(std::string(1, c)) + " at " +
                  std::to_string(at));
    if (overwrite) text[at] = c;
    else text.insert(at, 1, c);
  }
  return text;
}

/// A number token of some line replaced by `values`' pick (or a neighbour of it); false if none.
bool replace_number(Lines& l, Rng& rng, std::vector<std::string>& log, const std::vector<std::string>& values) {
  const size_t i = line_where(l, rng, [](const std::string& s) { return !numbers(s).empty(); });
  if (i == std::string::npos) return false;
  const auto nums = numbers(l.lines[i]);
  const auto [b, e] = rng.pick(nums);
  const std::string v = rng.pick(values);
  log.push_back(where(i) + ": number '" + l.lines[i].substr(b, e - b) + "' -> " + shown(v));
  l.lines[i] = replaced(l.lines[i], b, e, v);
  return true;
}

/// The value after "key:" on line i ([b, end of line before a comment)), if any.
bool value_span(const std::string& s, size_t& b, size_t& e) {
  const auto k = keys(s);
  if (k.empty()) return false;
  b = k.back().second + 1;
  while (b < s.size() && s[b] == ' ') ++b;
  e = s.size();
  if (b >= e) return false;
  return true;
}

void scene_mutation(Lines& l, std::string& text, Rng& rng, std::vector<std::string>& log) {
  const size_t kind = rng.below(100);
  if (kind < 15) {  // lines deleted, duplicated, swapped
    if (line_mutation(l, rng, log)) return;
  } else if (kind < 40) {  // a number's value
    if (replace_number(l, rng, log, kSceneValues)) return;
  } else if (kind < 52) {  // a key renamed: to another key of the file, a map or list, or misspelt
    const size_t i = line_where(l, rng, [](const std::string& s) { return !keys(s).empty(); });
    if (i != std::string::npos) {
      const auto ks = keys(l.lines[i]);
      const auto [b, e] = rng.pick(ks);
      std::string name = l.lines[i].substr(b, e - b);
      std::string to;
      if (rng.percent(40)) {
        const size_t j = line_where(l, rng, [](const std::string& s) { return !keys(s).empty(); });
        const auto kj = keys(l.lines[j]);
        const auto [bj, ej] = rng.pick(kj);
        to = l.lines[j].substr(bj, ej - bj);
      } else if (rng.percent(10)) {
        // A flow map or list used as a key (`{mode: 1}: ...`): a reader that takes every key for
        // a string fails on it with a conversion error.
        to = rng.percent(50) ? "{" + name + ": 1}" : "[" + name + "]";
      } else {
        to = name;
        const size_t at = rng.below(to.size());
        switch (rng.below(4)) {
          case 0: to.erase(at, 1); break;
          case 1: to.insert(at, 1, static_cast<char>('a' + rng.below(26))); break;
          case 2: to[at] = static_cast<char>(std::toupper(static_cast<unsigned char>(to[at]))); break;
          default: to += "_";
        }
        if (to.empty()) to = "x";
      }
      log.push_back(where(i) + ": key '" + name + "' -> '" + to + "'");
      l.lines[i] = replaced(l.lines[i], b, e, to);
      return;
    }
  } else if (kind < 60) {  // indentation
    const size_t i = line_where(l, rng, contentful);
    if (i != std::string::npos) {
      std::string& s = l.lines[i];
      const size_t indent = s.find_first_not_of(' ');
      const size_t r = rng.below(4);
      const std::string before = s;
      if (r == 0 && indent > 0) s.erase(0, std::min(indent, static_cast<size_t>(1 + rng.below(4))));
      else if (r == 1) s.insert(0, 1 + rng.below(4), ' ');
      else if (r == 2) s.insert(0, "\t");
      else s.erase(0, indent);
      log.push_back(where(i) + ": re-indented " + shown(before) + " -> " + shown(s));
      return;
    }
  } else if (kind < 74) {  // a value's type: scalar ↔ list ↔ map, or a list item unwrapped
    const size_t i = line_where(l, rng, contentful);
    if (i != std::string::npos) {
      std::string& s = l.lines[i];
      const std::string before = s;
      size_t b = 0, e = 0;
      const size_t dash = s.find_first_not_of(' ');
      if (rng.percent(25) && dash != std::string::npos && s.compare(dash, 2, "- ") == 0) {
        s.erase(dash, 2);  // a list item becomes a plain value
      } else if (value_span(s, b, e)) {
        const std::string v = s.substr(b, e - b);
        const size_t r = rng.below(5);
        if (r == 0) s = replaced(s, b, e, "[" + v + "]");
        else if (r == 1) s = replaced(s, b, e, "{x: " + v + "}");
        else if (r == 2 && v.size() > 2 && (v[0] == '[' || v[0] == '{')) s = replaced(s, b, e, v.substr(1, v.find_first_of(",]}") - 1));
        else s = replaced(s, b, e, rng.pick(kShapes));
      } else {
        s += rng.percent(50) ? " [1]" : " {a: b}";
      }
      log.push_back(where(i) + ": type changed " + shown(before) + " -> " + shown(s));
      return;
    }
  } else if (kind < 80) {  // deep nesting: YAML flow lists, parentheses, unary minus, powers
    const size_t i = line_where(l, rng, [](const std::string& s) {
      size_t b, e;
      return value_span(s, b, e);
    });
    if (i != std::string::npos) {
      size_t b = 0, e = 0;
      value_span(l.lines[i], b, e);
      const size_t depth = rng.percent(50) ? 100 + rng.below(100) : 5000 + rng.below(100000);
      std::string v;
      switch (rng.below(4)) {
        case 0: v = std::string(depth, '[') + "1" + std::string(depth, ']'); break;
        case 1: v = std::string(depth, '(') + "1" + std::string(depth, ')'); break;
        case 2: v = std::string(depth, '-') + "1"; break;
        default:
          for (size_t k = 0; k < depth; ++k) v += "2^";
          v += "2";
      }
      log.push_back(where(i) + ": value " + shown(l.lines[i].substr(b, e - b)) + " -> nested to depth " +
                    std::to_string(depth) + " " + shown(v, 12));
      l.lines[i] = replaced(l.lines[i], b, e, v);
      return;
    }
  } else if (kind < 86) {  // the file cut short
    text = truncate(join(l), rng, log);
    l = split(text);
    return;
  } else if (kind < 92) {  // issue 24: a key given twice, a merge key, a control character, a second document
    const size_t i = line_where(l, rng, contentful);
    if (i != std::string::npos) {
      std::string& s = l.lines[i];
      const size_t indent = s.find_first_not_of(' ');
      size_t b = 0, e = 0;
      switch (rng.below(4)) {
        // Cases 0, 1 and 3 insert a line: `s` refers into l.lines, which the insertion may move,
        // so the line is copied first (the log reads the copy).
        case 0: {  // the same line again: its key twice in one map (parameters: and mesh.parameters: among others)
          const std::string line = s;
          l.lines.insert(l.lines.begin() + static_cast<long>(i) + 1, line);
          log.push_back(where(i) + ": repeated " + shown(line));
          return;
        }
        case 1: {  // a YAML merge key, which yaml-cpp reads as an ordinary key
          const std::string line = s;
          l.lines.insert(l.lines.begin() + static_cast<long>(i) + 1,
                         std::string(indent == std::string::npos ? 0 : indent, ' ') + "<<: {mass: 1}");
          log.push_back(where(i) + ": merge key inserted after " + shown(line));
          return;
        }
        case 2:  // a control character (tab, NUL, newline, DEL) inside a value
          if (value_span(s, b, e)) {
            const char* c = rng.pick(std::vector<const char*>{"\\t", "\\0", "\\n", "\\x7f"});
            const std::string before = s;
            s = replaced(s, b, e, "\"a" + std::string(c) + "b\"");
            log.push_back(where(i) + ": control character in " + shown(before) + " -> " + shown(s));
            return;
          }
          break;
        default: {  // a second document
          const std::string line = s;
          l.lines.insert(l.lines.begin() + static_cast<long>(i) + 1, "---");
          log.push_back(where(i) + ": '---' inserted after " + shown(line));
          return;
        }
      }
    }
  }
  // random bytes (also the fallback when a mutation found nothing to act on)
  text = random_bytes(join(l), rng, log);
  l = split(text);
}

/// Index of the line "$Name" and of its "$EndName" (npos if absent).
std::pair<size_t, size_t> section(const Lines& l, const std::string& name) {
  size_t b = std::string::npos;
  for (size_t i = 0; i < l.lines.size(); ++i) {
    if (b == std::string::npos && l.lines[i] == "$" + name) b = i;
    else if (b != std::string::npos && l.lines[i] == "$End" + name) return {b, i};
  }
  return {b, std::string::npos};
}

std::vector<std::string> section_names(const Lines& l) {
  std::vector<std::string> out;
  for (const auto& s : l.lines)
    if (s.size() > 1 && s[0] == '$' && s.compare(0, 4, "$End") != 0) out.push_back(s.substr(1));
  return out;
}

/// One token of a line within section `name` (rows `from` lines after its start; 1: its header)
/// replaced by a value from `values` or a neighbour of the old one.
bool replace_token(Lines& l, Rng& rng, std::vector<std::string>& log, const std::string& name, bool header_only,
                   const std::vector<std::string>& values, bool reals) {
  const auto [b, e] = section(l, name);
  if (b == std::string::npos || e == std::string::npos || e <= b + 1) return false;
  size_t i = b + 1;
  if (!header_only) {
    std::vector<size_t> c;
    for (size_t k = b + 1; k < e; ++k) {
      const auto t = tokens(l.lines[k]);
      const bool has_real = std::any_of(t.begin(), t.end(), [&](const auto& p) {
        return l.lines[k].substr(p.first, p.second - p.first).find_first_of(".eE") != std::string::npos;
      });
      if (!t.empty() && (!reals || has_real)) c.push_back(k);
    }
    if (c.empty()) return false;
    i = rng.pick(c);
  }
  const auto t = tokens(l.lines[i]);
  if (t.empty()) return false;
  const auto [tb, te] = rng.pick(t);
  const std::string old = l.lines[i].substr(tb, te - tb);
  std::string v = rng.pick(values);
  if (!reals && rng.percent(30)) {  // a neighbour: off by one either way
    try {
      const long long n = std::stoll(old);
      v = std::to_string(rng.percent(50) ? n + 1 : n - 1);
    } catch (const std::exception&) {
    }
  }
  log.push_back("$" + name + " " + where(i) + ": token '" + old + "' -> " + shown(v));
  l.lines[i] = replaced(l.lines[i], tb, te, v);
  return true;
}

void msh_mutation(Lines& l, std::string& text, Rng& rng, std::vector<std::string>& log) {
  const size_t kind = rng.below(100);
  if (kind < 10) {
    text = truncate(join(l), rng, log);
    l = split(text);
    return;
  }
  if (kind < 20) {  // a whole section removed
    const auto names = section_names(l);
    if (!names.empty()) {
      const std::string name = rng.pick(names);
      const auto [b, e] = section(l, name);
      if (b != std::string::npos) {
        const size_t end = e == std::string::npos ? l.lines.size() - 1 : e;
        log.push_back("section $" + name + " removed (" + std::to_string(end - b + 1) + " lines)");
        l.lines.erase(l.lines.begin() + static_cast<long>(b), l.lines.begin() + static_cast<long>(end) + 1);
        return;
      }
    }
  } else if (kind < 38) {  // a count in a section header
    static const std::vector<std::string> counted = {"Nodes", "Elements", "Entities", "PhysicalNames"};
    if (replace_token(l, rng, log, rng.pick(counted), true, kMshInts, false)) return;
  } else if (kind < 58) {  // a tag or count inside nodes, elements, entities
    static const std::vector<std::string> tagged = {"Nodes", "Elements", "Entities", "PhysicalNames"};
    if (replace_token(l, rng, log, rng.pick(tagged), false, kMshInts, false)) return;
  } else if (kind < 68) {  // a coordinate
    if (replace_token(l, rng, log, "Nodes", false, kMshReals, true)) return;
  } else if (kind < 74) {  // the format line: version, binary flag, size of double
    static const std::vector<std::string> formats = {"4.1 1 8", "4.1 0 4", "4.0 0 8", "2.2 0 8", "4 0 8", "3.0 0 8",
                                                     "5.0 0 8", "4.1 0 0", "4.1", "", "-1 0 8", "nan 0 8"};
    const auto [b, e] = section(l, "MeshFormat");
    if (b != std::string::npos && b + 1 < l.lines.size()) {
      const std::string v = rng.pick(formats);
      log.push_back("$MeshFormat: '" + l.lines[b + 1] + "' -> " + shown(v));
      l.lines[b + 1] = v;
      return;
    }
  } else if (kind < 88) {
    if (line_mutation(l, rng, log)) return;
  }
  text = random_bytes(join(l), rng, log);
  l = split(text);
}

}  // namespace

Mutation mutate_scene(const std::string& text, Rng& rng, int count) {
  Mutation m;
  std::string t = text;
  Lines l = split(t);
  for (int k = 0; k < count; ++k) scene_mutation(l, t, rng, m.log);
  m.text = join(l);
  return m;
}

Mutation mutate_msh(const std::string& text, Rng& rng, int count) {
  Mutation m;
  std::string t = text;
  Lines l = split(t);
  for (int k = 0; k < count; ++k) msh_mutation(l, t, rng, m.log);
  m.text = join(l);
  return m;
}

}  // namespace alphaflex::fuzz
