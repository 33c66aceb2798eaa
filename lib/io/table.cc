#include "io/table.h"

#include "config/errors.h"

#include <sys/resource.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <stdexcept>

namespace anisodwr
{
CsvTable::CsvTable(const std::string &path, const std::vector<std::string> &columns)
    : file(path), n_columns(columns.size()), out(path)
{
  if (!out)
    throw InputError(path + ": cannot open for writing");
  for (std::size_t c = 0; c < columns.size(); ++c)
    out << (c ? "," : "") << columns[c];
  out << "\n" << std::flush;
}

void CsvTable::add_row(const std::vector<double> &values)
{
  if (values.size() != n_columns)
    throw std::logic_error(file + ": row has " + std::to_string(values.size()) +
                           " values, table has " + std::to_string(n_columns) +
                           " columns");
  out << std::setprecision(8);
  for (std::size_t c = 0; c < values.size(); ++c)
  {
    if (c)
      out << ",";
    if (!std::isnan(values[c]))
      out << values[c];
  }
  out << "\n" << std::flush;
}

std::string json_number(double v, int digits)
{
  if (!std::isfinite(v))
    return "null";
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

double peak_memory_mb()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

void make_directory(const std::string &dir)
{
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw InputError("output directory '" + dir + "': cannot create it: " + ec.message());
}
} // namespace anisodwr
