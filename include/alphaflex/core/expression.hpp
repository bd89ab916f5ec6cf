#pragma once
// Scalar arithmetic expressions in scene files ("pi/2", "sqrt(l2^2 - l1^2)", "2*m*l^2/12"), so that
// a scene states a derived value by its formula instead of a rounded number.
#include <map>
#include <string>

namespace alphaflex {

/// Named constants an expression may use (scene `parameters:` plus pi and e).
using ExpressionScope = std::map<std::string, double>;

/// Evaluates `text`: numbers, + - * / ^ (right-associative), unary minus, parentheses, constants
/// `pi` and `e`, names from `scope`, and the functions sin cos tan asin acos atan atan2 sqrt exp
/// log abs min max hypot. Throws std::invalid_argument with the position of the first error.
double evaluate_expression(const std::string& text, const ExpressionScope& scope);

}  // namespace alphaflex
