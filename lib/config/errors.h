#pragma once
// Error classes of anisodwr and the exit codes the program maps them to.
#include <stdexcept>
#include <string>

namespace anisodwr
{
/// Bad input from the user (file, key, value). The program exits with code 2.
class InputError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Numerical failure (solver failure, NaN/Inf). The program exits with code 3.
/// The message names the DWR loop / study level and the slab.
class NumericalError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

constexpr int exit_ok = 0;
constexpr int exit_input_error = 2;
constexpr int exit_numerical_error = 3;
} // namespace anisodwr
