#pragma once
// Charts through gnuplot (Debian's gnuplot-nox, which scripts/install-deps installs): the lab
// writes a gnuplot script and its data files, then runs gnuplot once per chart. Without
// gnuplot the data and the script are still written and the caller says how to draw them.
#include <filesystem>
#include <string>

namespace lab {

/// The gnuplot program found on PATH, or empty when there is none.
std::filesystem::path findGnuplot();

/// Runs `gnuplot SCRIPT` in `folder` (so the script names its data and output files relative
/// to it). Returns "" on success, else one line saying why: gnuplot missing (with the package
/// to install), or its exit status and the end of what it printed.
std::string runGnuplot(const std::filesystem::path& script, const std::filesystem::path& folder);

}  // namespace lab
