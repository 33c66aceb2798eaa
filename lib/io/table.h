#pragma once
// A CSV table written row by row (each row flushed as soon as it is added, so a
// run that stops early keeps every finished row).
#include <fstream>
#include <string>
#include <vector>

namespace anisodwr
{
class CsvTable
{
public:
  CsvTable(const std::string &path, const std::vector<std::string> &columns);
  /// Numbers are written with 8 significant digits; NaN is written as an empty cell.
  void add_row(const std::vector<double> &values);
  const std::string &path() const { return file; }

private:
  std::string file;
  std::size_t n_columns;
  std::ofstream out;
};

/// A number for JSON output: `null` for NaN/Inf, else `digits` significant digits.
std::string json_number(double v, int digits = 12);

/// Peak resident memory of this process in MB (getrusage).
double peak_memory_mb();

/// Creates the directory (and parents); InputError naming it if that fails.
void make_directory(const std::string &dir);
} // namespace anisodwr
