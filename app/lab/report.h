#pragma once
// The three ways `lab run` reports: a summary for people, one JSON object for scripts, and a
// CSV of the named bodies' final poses.
#include <cstdint>
#include <span>
#include <string>

#include "run.h"
#include "scenes/scene.h"

namespace lab {

/// The human summary: settings, timings with the per-phase split, metrics, freezes, hash.
std::string summaryText(const RunResult& result);

/// One JSON object on one line, ending in a newline, with the keys docs/lab.md lists.
std::string jsonText(const RunResult& result);

/// The hash as JSON wants it: 16 lower-case hex digits (a JSON number would lose bits).
std::string hexHash(std::uint64_t hash);

/// What each character part's drive needed over a run (the `drives` of `runJson`, a line of
/// `lab run SCENE --json`) as the Markdown table `lab report` shows; a figure the JSON holds as null
/// (not finite) reads "blew up", with no unit after it.
std::string drivesTable(const std::string& scene, const std::string& runJson);

/// The CSV text of a dump: header name,x,y,z,qw,qx,qy,qz and one row per named body.
std::string dumpCsv(const phys::World& world, std::span<const scenes::NamedBody> bodies);

}  // namespace lab
