#pragma once
// Escaping for the inside of JSON strings: every JSON text the program writes (the
// defaults, the config echo, summary.json) goes through it.
#include <string>

namespace anisodwr
{
/// s as the inside of a JSON string (quotes, backslashes, control characters escaped).
std::string json_escape(const std::string &s);
} // namespace anisodwr
