// Core utilities: scene expressions and time functions (values and the derivatives that
// prescribed motions will need).
#include <gtest/gtest.h>

#include <cmath>

#include "alphaflex/core/expression.hpp"
#include "alphaflex/core/time_function.hpp"

namespace alphaflex {
namespace {

TEST(Expression, ArithmeticPrecedenceAndFunctions) {
  const ExpressionScope s{{"l1", 0.3}, {"l2", 0.6}};
  EXPECT_DOUBLE_EQ(evaluate_expression("1 + 2*3", s), 7.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("2^3^2", s), 512.0);  // right-associative
  EXPECT_DOUBLE_EQ(evaluate_expression("-2^2", s), -4.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("pi/2", s), M_PI / 2);
  EXPECT_DOUBLE_EQ(evaluate_expression("sqrt(l2^2 - l1^2)", s), std::sqrt(0.36 - 0.09));
  EXPECT_DOUBLE_EQ(evaluate_expression("atan2(-1, 1)", s), -M_PI / 4);
  EXPECT_DOUBLE_EQ(evaluate_expression("1.5e-3", s), 1.5e-3);
}

TEST(Expression, ErrorsNameTheProblem) {
  const ExpressionScope s;
  EXPECT_THROW(evaluate_expression("2 * lx", s), std::invalid_argument);
  EXPECT_THROW(evaluate_expression("sin(1, 2)", s), std::invalid_argument);
  EXPECT_THROW(evaluate_expression("(1 + 2", s), std::invalid_argument);
  EXPECT_THROW(evaluate_expression("abc", s), std::invalid_argument);
  try {
    evaluate_expression("2 * lx", s);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lx"), std::string::npos);
  }
}

// Nesting is bounded (a deep one overflowed the stack: tests/fuzz), and a message quotes a long
// expression shortened.
TEST(Expression, DeepNestingIsRefusedNotAStackOverflow) {
  const ExpressionScope s;
  const auto nested = [](size_t depth) { return std::string(depth, '(') + "1" + std::string(depth, ')'); };
  EXPECT_DOUBLE_EQ(evaluate_expression(nested(150), s), 1.0);
  EXPECT_DOUBLE_EQ(evaluate_expression(std::string(150, '-') + "1", s), 1.0);
  for (const std::string& deep : {nested(50000), std::string(100000, '-') + "1"}) {
    try {
      evaluate_expression(deep, s);
      ADD_FAILURE() << "a 100000-deep expression was accepted";
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("nested more than 200 levels deep"), std::string::npos) << m;
      EXPECT_NE(m.find("... (100001 characters)"), std::string::npos) << m;
      EXPECT_LT(m.size(), 200u) << m;
    }
  }
}

// f' and f'' against central differences, for every function kind.
TEST(TimeFunction, DerivativesMatchFiniteDifferences) {
  const std::vector<TimeFunctionPtr> fs{make_constant(2.0), make_ramp(0.1, 0.5, 1.0, 3.0),
                                        make_smooth_step(0.1, 0.5, 1.0, 3.0), make_sine(2.0, 3.0, 0.4, 1.0),
                                        make_table({0.0, 0.2, 0.6}, {1.0, 2.0, -1.0})};
  const double d = 1e-5;
  for (const auto& f : fs)
    for (double t : {0.13, 0.27, 0.44}) {
      EXPECT_NEAR(f->derivative(t), (f->value(t + d) - f->value(t - d)) / (2 * d), 1e-6 * (1 + std::fabs(f->derivative(t))));
      EXPECT_NEAR(f->second_derivative(t), (f->derivative(t + d) - f->derivative(t - d)) / (2 * d),
                  1e-4 * (1 + std::fabs(f->second_derivative(t))));
    }
}

TEST(TimeFunction, ValuesAtKnownPoints) {
  EXPECT_DOUBLE_EQ(make_ramp(0.0, 2.0, 1.0, 3.0)->value(1.0), 2.0);
  EXPECT_DOUBLE_EQ(make_ramp(0.0, 2.0, 1.0, 3.0)->value(5.0), 3.0);
  EXPECT_DOUBLE_EQ(make_smooth_step(0.0, 1.0, 0.0, 1.0)->value(0.5), 0.5);
  EXPECT_DOUBLE_EQ(make_smooth_step(0.0, 1.0, 0.0, 1.0)->derivative(0.0), 0.0);
  EXPECT_NEAR(make_sine(2.0, 0.25, 0.0, 1.0)->value(1.0), 3.0, 1e-15);
  EXPECT_DOUBLE_EQ(make_table({0.0, 1.0}, {0.0, 4.0})->value(0.25), 1.0);
  EXPECT_THROW(make_table({0.0, 0.0}, {1.0, 2.0}), std::invalid_argument);
}

}  // namespace
}  // namespace alphaflex
