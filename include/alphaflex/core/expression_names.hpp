#pragma once
// The names an expression uses (core/expression.hpp's grammar), for readers that decide what a
// name is — a variable, a parameter or a sensor (io/types/sensor_feedback_3d.cpp).
#include <string>
#include <vector>

namespace alphaflex {

/// The names `text` uses as values (not as functions), each once, in order of appearance. Names
/// are letters, digits and _ (not first), with inner dots (`shoulder.angle`). Throws
/// std::invalid_argument on a syntax error, as evaluate_expression does.
std::vector<std::string> expression_names(const std::string& text);

}  // namespace alphaflex
