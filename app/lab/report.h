#pragma once
// The three ways `lab run` reports: a summary for people, one JSON object for scripts, and a
// CSV of the named bodies' final poses.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "run.h"
#include "scenes/scene.h"

namespace lab {

/// The human summary: settings, timings with the per-phase split, metrics, freezes, hash.
std::string summaryText(const RunResult& result);

/// One JSON object on one line, ending in a newline, with the keys docs/lab.md lists.
std::string jsonText(const RunResult& result);

/// A double as JSON: %.17g (enough to read back the same double), or null when not finite.
std::string jsonNumber(double value);
/// A JSON string literal, quotes included, with quotes, backslashes and controls escaped.
std::string jsonString(std::string_view text);
/// The hash as JSON wants it: 16 lower-case hex digits (a JSON number would lose bits).
std::string hexHash(std::uint64_t hash);

/// The CSV text of a dump: header name,x,y,z,qw,qx,qy,qz and one row per named body.
std::string dumpCsv(const phys::World& world, std::span<const scenes::NamedBody> bodies);

}  // namespace lab
