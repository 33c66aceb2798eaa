#pragma once
// Error classes of anisodwr and the exit codes the program maps them to.
#include <new>
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

/// A run or DWR loop not started because its memory estimate exceeds the limit
/// (adaptivity.max_memory_mb or the physical memory). Exit code 2, like bad input:
/// the configuration asks for more than the budget.
class ResourceLimitError : public InputError
{
public:
  using InputError::InputError;
};

/// An output file that cannot be written (disk full, I/O error) after the output
/// directory was taken: the input was fine. The message names the file and the
/// system's reason (strerror). The program exits with code 4.
class OutputError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Numerical failure (solver failure, NaN/Inf). The program exits with code 3.
/// The message names the DWR loop / study level and the slab.
/// what() is one line; details() holds the full text of a library error (written to
/// summary.json), if any.
class NumericalError : public std::runtime_error
{
public:
  explicit NumericalError(const std::string &message, std::string details = "")
      : std::runtime_error(message), full(std::move(details))
  {
  }
  const std::string &details() const { return full; }

private:
  std::string full;
};

/// The message of a failure for summary.json's status ("out of memory" for bad_alloc).
inline std::string failure_message(const std::exception &e)
{
  if (dynamic_cast<const std::bad_alloc *>(&e))
    return "out of memory (std::bad_alloc)";
  return e.what();
}

/// The details of a failure (empty unless it is a NumericalError with details).
inline std::string failure_details(const std::exception &e)
{
  const auto *n = dynamic_cast<const NumericalError *>(&e);
  return n ? n->details() : std::string();
}

constexpr int exit_ok = 0;
constexpr int exit_input_error = 2;
constexpr int exit_numerical_error = 3;
constexpr int exit_output_error = 4;
} // namespace anisodwr
