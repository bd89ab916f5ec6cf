#pragma once
// Scalar arithmetic expressions in scene files ("pi/2", "sqrt(l2^2 - l1^2)", "2*m*l^2/12"), so that
// a scene states a derived value by its formula instead of a rounded number.
#include <map>
#include <string>
#include <vector>

namespace alphaflex {

/// Named constants an expression may use (scene `parameters:` plus pi and e).
using ExpressionScope = std::map<std::string, double>;

/// Evaluates `text`: numbers, + - * / ^ (right-associative), unary minus, parentheses, constants
/// `pi` and `e`, names from `scope`, and the functions sin cos tan asin acos atan atan2 sqrt exp
/// log abs min max hypot. Throws std::invalid_argument with the position of the first error.
double evaluate_expression(const std::string& text, const ExpressionScope& scope);

/// An expression of named variables (a spring's force as a function of its elongation and rate, a
/// motor's torque of time, angle and speed), with its exact gradient by forward differentiation of
/// the same grammar (chain rule on every operation; min and max take the derivative of the
/// argument they return, abs has slope 0 at 0). Variables shadow `scope`'s constants of the same
/// name. The text is parsed at every evaluation (a few µs for a scene formula).
class ExpressionFunction {
 public:
  static constexpr size_t kMaxVariables = 4;
  /// Checks the text once (syntax, names, functions): throws std::invalid_argument as
  /// evaluate_expression does, naming the variables when a name is unknown.
  ExpressionFunction(std::string text, ExpressionScope scope, std::vector<std::string> variables);
  /// The value at x (one value per variable, in the constructor's order) and, if `gradient` is not
  /// null, ∂f/∂x_k into gradient[k].
  double value(const double* x, double* gradient = nullptr) const;
  const std::string& text() const { return text_; }
  const std::vector<std::string>& variables() const { return variables_; }

 private:
  std::string text_;
  ExpressionScope scope_;
  std::vector<std::string> variables_;
};

}  // namespace alphaflex
