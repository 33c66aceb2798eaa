#include "base/json_escape.h"

#include <cstdio>

namespace anisodwr
{
std::string json_escape(const std::string &s)
{
  std::string o;
  for (const char c : s)
    switch (c)
    {
    case '"':
      o += "\\\"";
      break;
    case '\\':
      o += "\\\\";
      break;
    case '\n':
      o += "\\n";
      break;
    case '\t':
      o += "\\t";
      break;
    case '\r':
      o += "\\r";
      break;
    default:
      if (static_cast<unsigned char>(c) < 0x20)
      {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned int>(c));
        o += buf;
      }
      else
        o += c;
    }
  return o;
}
} // namespace anisodwr
