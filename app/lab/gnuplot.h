#pragma once
// Charts through gnuplot (Debian's gnuplot-nox, which scripts/install-deps installs): the lab
// writes a gnuplot script and its data files, then runs gnuplot once per chart. Without
// gnuplot the data and the script are still written and the caller says how to draw them.
#include <filesystem>
#include <string>

namespace lab {

/// The gnuplot program found on PATH, or empty when there is none.
std::filesystem::path findGnuplot();

/// `text` in single quotes, each quote inside it written as `quoteInside`: two quotes for
/// gnuplot's strings, a closing, escaped and reopening one ('\'') for the shell.
std::string singleQuoted(const std::string& text, const std::string& quoteInside);

/// The lab's scripts write their charts into the folder `outdir` names: the script's own folder
/// unless set (`gnuplot -e "outdir='charts'" sweep.gp` draws elsewhere).
/// How runGnuplot's answer starts when gnuplot is not found: `lab report` says it once for all.
inline constexpr const char* kGnuplotMissing =
    "gnuplot is not installed (Debian: apt-get install gnuplot-nox)";
inline constexpr const char* kOutdirDefault = "if (!exists('outdir')) outdir = '.'\n";

/// Runs `gnuplot SCRIPT` in `folder` (so the script names its data files relative to it, and its
/// charts land there). OutputFolder runs it in a scratch folder and writes the charts with the
/// rest of a command's files, so a chart is replaced whole or not at all. Returns "" on success,
/// else one line saying why: gnuplot missing (with the package to install), or its exit status and
/// the end of what it printed. The messages name the script as `shownAs` when given (a script run
/// where the user will not find it).
std::string runGnuplot(const std::filesystem::path& script, const std::filesystem::path& folder,
                       const std::filesystem::path& shownAs = {});

}  // namespace lab
