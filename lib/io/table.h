#pragma once
// A CSV table written row by row (each row written as soon as it is added, so a
// run that stops early keeps every finished row), and the other output files: written
// whole (atomically) or not at all. A write that fails throws OutputError naming the
// file and the system's reason.
#include "base/json_escape.h"

#include <fstream>
#include <string>
#include <vector>

namespace anisodwr
{
class CsvTable
{
public:
  CsvTable(const std::string &path, const std::vector<std::string> &columns);
  ~CsvTable();
  CsvTable(const CsvTable &) = delete;
  CsvTable &operator=(const CsvTable &) = delete;
  /// Numbers are written with 8 significant digits; NaN is written as an empty cell.
  /// A row that cannot be written is removed again (the file keeps the rows before it).
  void add_row(const std::vector<double> &values);
  const std::string &path() const { return file; }

private:
  std::string file;
  std::size_t n_columns;
  int fd = -1; ///< the file, on the output rank
  /// Appends `text`; on failure cuts the file back to its size before (OutputError).
  void append(const std::string &text);
};

/// A number for JSON output: `null` for NaN/Inf, else `digits` significant digits.
std::string json_number(double v, int digits = 12);

/// Peak resident memory of this process in MB (getrusage).
double peak_memory_mb();

/// Creates the directory (and parents); InputError naming it if that fails.
void make_directory(const std::string &dir);

/// Writes `content` to path + ".tmp" and renames it to `path` (readers see the old or
/// the new file, never a partial one); SIGINT/SIGTERM are held back meanwhile. If that
/// fails the .tmp file is removed, `path` keeps its last complete version (or stays
/// absent), and OutputError names the file and the reason. Collective (MPI): rank 0
/// writes.
void write_file_atomically(const std::string &path, const std::string &content);
/// The same on this rank alone (for code that runs only on the output rank).
void write_file_atomically_here(const std::string &path, const std::string &content);

/// Creates `dir`, takes an exclusive lock on dir/.anisodwr.lock for the lifetime of the
/// process (InputError naming the directory if another process holds it) and removes
/// the files a previous run wrote there (only names anisodwr writes: summary.json,
/// *.csv tables, loop-/solution- VTU, PVD and cells.csv files, cut_*.csv).
void lock_output_directory(const std::string &dir);

/// On SIGINT/SIGTERM the program writes `content` (a summary with status
/// "interrupted") to `path` atomically and exits with 128 + the signal number.
/// Installs the handlers on the first call; later calls replace path and content.
void set_interrupt_summary(const std::string &path, const std::string &content);
} // namespace anisodwr
