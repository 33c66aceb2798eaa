#include "io/table.h"

#include "base/errors.h"
#include "base/mpi.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <sstream>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <stdexcept>

namespace anisodwr
{
namespace
{
/// Writes all of data to fd; false (errno set) if a write fails.
bool write_all(int fd, const char *data, std::size_t size)
{
  while (size > 0)
  {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
    {
      if (n == 0)
        errno = EIO;
      return false;
    }
    data += n;
    size -= std::size_t(n);
  }
  return true;
}

std::string reason(int err)
{
  return std::strerror(err);
}
} // namespace

CsvTable::CsvTable(const std::string &path, const std::vector<std::string> &columns)
    : file(path), n_columns(columns.size())
{
  on_output_rank(
      [&]()
      {
        fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (fd < 0)
          throw OutputError(path + ": cannot open for writing: " + reason(errno));
        std::string header;
        for (std::size_t c = 0; c < columns.size(); ++c)
          header += (c ? "," : "") + columns[c];
        append(header + "\n");
      });
}

CsvTable::~CsvTable()
{
  if (fd >= 0)
    ::close(fd);
}

void CsvTable::append(const std::string &text)
{
  const off_t before = ::lseek(fd, 0, SEEK_END);
  if (before >= 0 && write_all(fd, text.data(), text.size()))
    return;
  const int err = errno;
  if (before >= 0 && ::ftruncate(fd, before) == 0)
    ::lseek(fd, before, SEEK_SET);
  throw OutputError(file + ": cannot write: " + reason(err));
}

void CsvTable::add_row(const std::vector<double> &values)
{
  if (values.size() != n_columns)
    throw std::logic_error(file + ": row has " + std::to_string(values.size()) +
                           " values, table has " + std::to_string(n_columns) +
                           " columns");
  if (!writes_output())
    return;
  std::ostringstream row;
  row << std::setprecision(8);
  for (std::size_t c = 0; c < values.size(); ++c)
  {
    if (c)
      row << ",";
    if (!std::isnan(values[c]))
      row << values[c];
  }
  row << "\n";
  append(row.str());
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

namespace
{
/// SIGINT and SIGTERM blocked while an object lives.
class SignalBlock
{
public:
  SignalBlock()
  {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigprocmask(SIG_BLOCK, &set, &old);
  }
  ~SignalBlock() { sigprocmask(SIG_SETMASK, &old, nullptr); }

private:
  sigset_t old;
};

// What the signal handler writes (only changed while the signals are blocked).
std::string interrupt_path, interrupt_tmp, interrupt_content;

extern "C" void on_interrupt(int sig)
{
  // async-signal-safe calls only: open, write, close, rename, unlink, _exit
  if (!interrupt_path.empty())
  {
    const int fd = ::open(interrupt_tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0)
    {
      const bool written =
          write_all(fd, interrupt_content.data(), interrupt_content.size());
      if (::close(fd) == 0 && written)
        ::rename(interrupt_tmp.c_str(), interrupt_path.c_str());
      else
        ::unlink(interrupt_tmp.c_str()); // summary.json keeps its last version
    }
  }
  const char msg[] = "anisodwr: interrupted; summary.json has status \"interrupted\"\n";
  write_all(2, msg, sizeof msg - 1);
  _exit(128 + sig);
}

void lock_output_directory_on_this_rank(const std::string &dir)
{
  make_directory(dir);
  const std::string lock = dir + "/.anisodwr.lock";
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0)
    throw InputError("output directory '" + dir + "': cannot create the lock file " +
                     lock + ": " + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0)
  {
    const int err = errno;
    ::close(fd);
    if (err == EWOULDBLOCK)
      throw InputError("output directory '" + dir +
                       "' is in use by another anisodwr run (it holds " + lock +
                       "); choose another --output");
    throw InputError("output directory '" + dir + "': cannot lock " + lock + ": " +
                     std::strerror(err));
  }
  // fd stays open (and locked) until the process ends
  namespace fs = std::filesystem;
  auto ends = [](const std::string &s, const std::string &e)
  { return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0; };
  auto starts = [](const std::string &s, const std::string &b)
  { return s.compare(0, b.size(), b) == 0; };
  std::error_code ec;
  for (const auto &entry : fs::directory_iterator(dir, ec))
  {
    if (!entry.is_regular_file(ec))
      continue;
    const std::string name = entry.path().filename().string();
    const bool ours =
        name == "summary.json" || name == "summary.json.tmp" || name == "loops.csv" ||
        name == "loops.tex" || name == "loops.pvd" || name == "probes.csv" ||
        name == "convergence.csv" || name == "solution.pvd" ||
        ((starts(name, "loop-") || starts(name, "solution-")) &&
         (ends(name, ".vtu") || ends(name, ".cells.csv"))) ||
        (starts(name, "cut_") && ends(name, ".csv")) ||
        (starts(name, "slab-") && ends(name, ".mtx"));
    if (ours)
      fs::remove(entry.path(), ec);
  }
}
} // namespace

void write_file_atomically_here(const std::string &path, const std::string &content)
{
  const SignalBlock block;
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
    throw OutputError(path + ": cannot create " + tmp + ": " + reason(errno));
  bool written = write_all(fd, content.data(), content.size());
  int err = errno;
  if (::close(fd) != 0 && written)
    written = false, err = errno;
  if (written && ::rename(tmp.c_str(), path.c_str()) == 0)
    return;
  if (written)
    err = errno;
  ::unlink(tmp.c_str());
  throw OutputError(path + ": cannot write (" + tmp + "): " + reason(err));
}

void write_file_atomically(const std::string &path, const std::string &content)
{
  on_output_rank([&]() { write_file_atomically_here(path, content); });
}

void lock_output_directory(const std::string &dir)
{
  on_output_rank([&]() { lock_output_directory_on_this_rank(dir); });
}

void set_interrupt_summary(const std::string &path, const std::string &content)
{
  if (!writes_output())
    return;
  const SignalBlock block;
  static bool installed = false;
  if (!installed)
  {
    struct sigaction sa = {};
    sa.sa_handler = on_interrupt;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    installed = true;
  }
  interrupt_path = path;
  interrupt_tmp = path + ".tmp";
  interrupt_content = content;
}
} // namespace anisodwr
