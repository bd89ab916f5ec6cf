#include "alphaflex/core/expression.hpp"

#include <cctype>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace alphaflex {
namespace {

// Recursive-descent parser over the grammar
//   expr := term (('+'|'-') term)* ; term := unary (('*'|'/') unary)* ;
//   unary := '-' unary | '+' unary | power ; power := primary ('^' unary)? ;
//   primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'.
class Parser {
 public:
  Parser(const std::string& s, const ExpressionScope& scope) : s_(s), scope_(scope) {}

  double parse() {
    double v = expr();
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
  double expr() {
    double v = term();
    for (;;) {
      if (accept('+')) v += term();
      else if (accept('-')) v -= term();
      else return v;
    }
  }
  double term() {
    double v = unary();
    for (;;) {
      if (accept('*')) v *= unary();
      else if (accept('/')) v /= unary();
      else return v;
    }
  }
  double unary() {
    const Nesting nesting(*this);
    if (accept('-')) return -unary();
    if (accept('+')) return unary();
    return power();
  }
  double power() {
    double base = primary();
    if (accept('^')) return std::pow(base, unary());
    return base;
  }
  double primary() {
    skip();
    if (pos_ >= s_.size()) fail("unexpected end");
    if (accept('(')) {
      double v = expr();
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
      return v;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      size_t start = pos_;
      while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
      std::string name = s_.substr(start, pos_ - start);
      if (accept('(')) {
        std::vector<double> args{expr()};
        while (accept(',')) args.push_back(expr());
        if (!accept(')')) fail("expected ')' after arguments of " + name);
        return call(name, args);
      }
      auto it = scope_.find(name);
      if (it != scope_.end()) return it->second;
      if (name == "pi") return M_PI;
      if (name == "e") return M_E;
      pos_ = start;
      fail("unknown name '" + name + "' (define it under `parameters:`)");
    }
    fail("unexpected '" + std::string(1, c) + "'");
  }
  double call(const std::string& f, const std::vector<double>& a) {
    auto need = [&](size_t n) {
      if (a.size() != n) fail(f + " takes " + std::to_string(n) + " argument(s)");
    };
    if (f == "atan2") { need(2); return std::atan2(a[0], a[1]); }
    if (f == "hypot") { need(2); return std::hypot(a[0], a[1]); }
    if (f == "min") { need(2); return std::min(a[0], a[1]); }
    if (f == "max") { need(2); return std::max(a[0], a[1]); }
    need(1);
    const double x = a[0];
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
    fail("unknown function '" + f + "'");
  }

  const std::string& s_;
  const ExpressionScope& scope_;
  size_t pos_ = 0;
  int depth_ = 0;
};

}  // namespace

double evaluate_expression(const std::string& text, const ExpressionScope& scope) {
  return Parser(text, scope).parse();
}

}  // namespace alphaflex
