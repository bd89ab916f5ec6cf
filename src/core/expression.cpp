#include "alphaflex/core/expression.hpp"
#include "alphaflex/core/expression_names.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <type_traits>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace alphaflex {
namespace {

/// A number with its gradient with respect to an ExpressionFunction's variables (forward AD):
/// the same parser then gives a value and its exact first derivatives.
struct Jet {
  double v = 0.0;
  std::array<double, ExpressionFunction::kMaxVariables> d{};
  Jet() = default;
  Jet(double value) : v(value) {}  // NOLINT: constants convert implicitly, as doubles do
  Jet chain(double value, double slope) const {  // f(this) with f' = slope
    Jet r(value);
    for (size_t i = 0; i < d.size(); ++i) r.d[i] = slope * d[i];
    return r;
  }
};
Jet operator+(const Jet& a, const Jet& b) {
  Jet r(a.v + b.v);
  for (size_t i = 0; i < r.d.size(); ++i) r.d[i] = a.d[i] + b.d[i];
  return r;
}
Jet operator-(const Jet& a) { return a.chain(-a.v, -1.0); }
Jet operator-(const Jet& a, const Jet& b) { return a + (-b); }
Jet operator*(const Jet& a, const Jet& b) {
  Jet r(a.v * b.v);
  for (size_t i = 0; i < r.d.size(); ++i) r.d[i] = a.d[i] * b.v + a.v * b.d[i];
  return r;
}
Jet operator/(const Jet& a, const Jet& b) {
  Jet r(a.v / b.v);
  for (size_t i = 0; i < r.d.size(); ++i) r.d[i] = (a.d[i] * b.v - a.v * b.d[i]) / (b.v * b.v);
  return r;
}
Jet& operator+=(Jet& a, const Jet& b) { return a = a + b; }
Jet& operator-=(Jet& a, const Jet& b) { return a = a - b; }
Jet& operator*=(Jet& a, const Jet& b) { return a = a * b; }
Jet& operator/=(Jet& a, const Jet& b) { return a = a / b; }
bool has_gradient(const Jet& a) {
  return std::any_of(a.d.begin(), a.d.end(), [](double x) { return x != 0.0; });
}

// The elementary functions on both number types (value, and the chain rule on a Jet).
double value_of(double x) { return x; }
double value_of(const Jet& x) { return x.v; }
double power(double a, double b) { return std::pow(a, b); }
Jet power(const Jet& a, const Jet& b) {
  const double p = std::pow(a.v, b.v);
  // d(a^b) = b a^(b−1) da + a^b log(a) db; the second term only where b varies (a^2 at a < 0).
  Jet r = a.chain(p, b.v == 0.0 ? 0.0 : b.v * std::pow(a.v, b.v - 1.0));
  if (has_gradient(b)) r += b.chain(0.0, p * std::log(a.v));
  r.v = p;
  return r;
}
double apply(const std::string& f, double x) {
  if (f == "sin") return std::sin(x);
  if (f == "cos") return std::cos(x);
  if (f == "tan") return std::tan(x);
  if (f == "asin") return std::asin(x);
  if (f == "acos") return std::acos(x);
  if (f == "atan") return std::atan(x);
  if (f == "sqrt") return std::sqrt(x);
  if (f == "exp") return std::exp(x);
  if (f == "log") return std::log(x);
  if (f == "abs") return std::fabs(x);
  return std::nan("");
}
/// The derivative of the function `f` at x (apply() returns NaN for unknown names too).
double slope(const std::string& f, double x) {
  if (f == "sin") return std::cos(x);
  if (f == "cos") return -std::sin(x);
  if (f == "tan") return 1.0 + std::tan(x) * std::tan(x);
  if (f == "asin") return 1.0 / std::sqrt(1.0 - x * x);
  if (f == "acos") return -1.0 / std::sqrt(1.0 - x * x);
  if (f == "atan") return 1.0 / (1.0 + x * x);
  if (f == "sqrt") return 0.5 / std::sqrt(x);
  if (f == "exp") return std::exp(x);
  if (f == "log") return 1.0 / x;
  if (f == "abs") return x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : 0.0;
  return std::nan("");
}
bool known_function(const std::string& f) {
  static const char* names[] = {"sin", "cos", "tan", "asin", "acos", "atan", "sqrt", "exp", "log", "abs"};
  return std::find(std::begin(names), std::end(names), f) != std::end(names);
}
double apply1(const std::string& f, double x) { return apply(f, x); }
Jet apply1(const std::string& f, const Jet& x) { return x.chain(apply(f, x.v), slope(f, x.v)); }
double atan2_of(double y, double x) { return std::atan2(y, x); }
Jet atan2_of(const Jet& y, const Jet& x) {
  const double r2 = x.v * x.v + y.v * y.v;
  return (y.chain(0.0, x.v / r2) + x.chain(0.0, -y.v / r2)) + Jet(std::atan2(y.v, x.v));
}
double hypot_of(double a, double b) { return std::hypot(a, b); }
Jet hypot_of(const Jet& a, const Jet& b) {
  const double h = std::hypot(a.v, b.v);
  return (a.chain(0.0, a.v / h) + b.chain(0.0, b.v / h)) + Jet(h);
}

/// The end of the name starting at `pos`: letters, digits, _ and inner dots followed by a letter
/// or _ (`arm.angle`; a dot then a digit is not part of a name).
size_t name_end(const std::string& s, size_t pos) {
  auto word = [&](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  while (pos < s.size()) {
    if (word(s[pos])) ++pos;
    else if (s[pos] == '.' && pos + 1 < s.size() && (std::isalpha(static_cast<unsigned char>(s[pos + 1])) || s[pos + 1] == '_')) ++pos;
    else break;
  }
  return pos;
}

// Recursive-descent parser over the grammar
//   expr := term (('+'|'-') term)* ; term := unary (('*'|'/') unary)* ;
//   unary := '-' unary | '+' unary | power ; power := primary ('^' unary)? ;
//   primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'.
template <class T>
class Parser {
 public:
  /// `variables` (names and values, may be null): names that take precedence over `scope`; in a
  /// Jet parse, variable k carries the unit derivative k.
  Parser(const std::string& s, const ExpressionScope& scope, const std::vector<std::string>* variables = nullptr,
         const double* values = nullptr)
      : s_(s), scope_(scope), variables_(variables), values_(values) {}
  /// Collects the names used as values into `names` (each evaluates to 0) instead of looking them up.
  void collect_names(std::vector<std::string>* names) { names_ = names; }

  T parse() {
    T v = expr();
    skip();
    if (pos_ != s_.size()) fail("unexpected '" + std::string(1, s_[pos_]) + "'");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    // A message quotes the expression, not pages of it.
    constexpr size_t kShown = 60;
    const std::string shown = s_.size() <= kShown ? s_ : s_.substr(0, kShown) + "... (" + std::to_string(s_.size()) + " characters)";
    throw std::invalid_argument("in expression '" + shown + "' at character " + std::to_string(pos_ + 1) + ": " + what);
  }
  // Every nesting — parentheses, unary signs, powers, arguments — recurses through unary(): bounded,
  // so that no input overflows the stack (found by tests/fuzz: 10⁵ nested parentheses).
  static constexpr int kMaxDepth = 200;
  struct Nesting {
    explicit Nesting(Parser& p) : p_(p) {
      if (++p_.depth_ > kMaxDepth) p_.fail("nested more than " + std::to_string(kMaxDepth) + " levels deep");
    }
    ~Nesting() { --p_.depth_; }
    Parser& p_;
  };
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool accept(char c) {
    skip();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  T expr() {
    T v = term();
    for (;;) {
      if (accept('+')) v += term();
      else if (accept('-')) v -= term();
      else return v;
    }
  }
  T term() {
    T v = unary();
    for (;;) {
      if (accept('*')) v *= unary();
      else if (accept('/')) v /= unary();
      else return v;
    }
  }
  T unary() {
    const Nesting nesting(*this);
    if (accept('-')) return -unary();
    if (accept('+')) return unary();
    return power();
  }
  T power() {
    T base = primary();
    if (accept('^')) return alphaflex::power(base, unary());
    return base;
  }
  T primary() {
    skip();
    if (pos_ >= s_.size()) fail("unexpected end");
    if (accept('(')) {
      T v = expr();
      if (!accept(')')) fail("expected ')'");
      return v;
    }
    const char c = s_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      const char* begin = s_.c_str() + pos_;
      char* end = nullptr;
      double v = std::strtod(begin, &end);
      if (end == begin) fail("bad number");
      pos_ += static_cast<size_t>(end - begin);
      return T(v);
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      size_t start = pos_;
      pos_ = name_end(s_, pos_);
      std::string name = s_.substr(start, pos_ - start);
      if (names_) {
        skip();
        if (pos_ >= s_.size() || s_[pos_] != '(') {
          if (std::find(names_->begin(), names_->end(), name) == names_->end()) names_->push_back(name);
          return T(0.0);
        }
      }
      if (accept('(')) {
        std::vector<T> args{expr()};
        while (accept(',')) args.push_back(expr());
        if (!accept(')')) fail("expected ')' after arguments of " + name);
        return call(name, args);
      }
      if (variables_)
        for (size_t k = 0; k < variables_->size(); ++k)
          if ((*variables_)[k] == name) return variable(k);
      auto it = scope_.find(name);
      if (it != scope_.end()) return it->second;
      if (name == "pi") return M_PI;
      if (name == "e") return M_E;
      pos_ = start;
      if (variables_ && !variables_->empty()) {
        std::string names;
        for (const std::string& v : *variables_) names += (names.empty() ? "" : ", ") + v;
        fail("unknown name '" + name + "' (the variables here are " + names + "; constants are defined under `parameters:`)");
      }
      fail("unknown name '" + name + "' (define it under `parameters:`)");
    }
    fail("unexpected '" + std::string(1, c) + "'");
  }
  T variable(size_t k) const {
    T x(values_[k]);
    if constexpr (std::is_same_v<T, Jet>) x.d[k] = 1.0;
    return x;
  }
  T call(const std::string& f, const std::vector<T>& a) {
    auto need = [&](size_t n) {
      if (a.size() != n) fail(f + " takes " + std::to_string(n) + " argument(s)");
    };
    if (f == "atan2") { need(2); return atan2_of(a[0], a[1]); }
    if (f == "hypot") { need(2); return hypot_of(a[0], a[1]); }
    // min, max: the derivative of the argument that is taken (one-sided at a tie).
    if (f == "min") { need(2); return value_of(a[0]) <= value_of(a[1]) ? a[0] : a[1]; }
    if (f == "max") { need(2); return value_of(a[0]) >= value_of(a[1]) ? a[0] : a[1]; }
    if (!known_function(f)) fail("unknown function '" + f + "'");
    need(1);
    return apply1(f, a[0]);
  }

  const std::string& s_;
  const ExpressionScope& scope_;
  const std::vector<std::string>* variables_;
  const double* values_;
  std::vector<std::string>* names_ = nullptr;
  size_t pos_ = 0;
  int depth_ = 0;
};

}  // namespace

std::vector<std::string> expression_names(const std::string& text) {
  std::vector<std::string> names;
  Parser<double> p(text, ExpressionScope{});
  p.collect_names(&names);
  p.parse();
  return names;
}

double evaluate_expression(const std::string& text, const ExpressionScope& scope) {
  return Parser<double>(text, scope).parse();
}

ExpressionFunction::ExpressionFunction(std::string text, ExpressionScope scope, std::vector<std::string> variables)
    : text_(std::move(text)), scope_(std::move(scope)), variables_(std::move(variables)) {
  if (variables_.size() > kMaxVariables) throw std::logic_error("ExpressionFunction: more than kMaxVariables variables");
  // Parse once at zero values, so that a misspelt name or a syntax error is an error of the input
  // (the value there may be anything, 1/0 included).
  const std::vector<double> zeros(variables_.size(), 0.0);
  Parser<double>(text_, scope_, &variables_, zeros.data()).parse();
}

double ExpressionFunction::value(const double* x, double* gradient) const {
  if (!gradient) return Parser<double>(text_, scope_, &variables_, x).parse();
  const Jet j = Parser<Jet>(text_, scope_, &variables_, x).parse();
  for (size_t k = 0; k < variables_.size(); ++k) gradient[k] = j.d[k];
  return j.v;
}

}  // namespace alphaflex
