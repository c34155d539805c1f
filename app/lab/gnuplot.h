#pragma once
// Charts through gnuplot (Debian's gnuplot-nox, which scripts/install-deps installs): the lab
// writes a gnuplot script and its data files, then runs gnuplot once per chart. Without
// gnuplot the data and the script are still written and the caller says how to draw them.
#include <filesystem>
#include <string>

namespace lab {

/// A new hidden folder PREFIXxxxxxx inside `parent` (the same file system, so its files rename
/// into `parent`), removed with whatever is left in it when this goes.
class PrivateFolder {
 public:
  PrivateFolder(const std::filesystem::path& parent, const char* prefix);
  PrivateFolder(const PrivateFolder&) = delete;
  PrivateFolder& operator=(const PrivateFolder&) = delete;
  ~PrivateFolder();
  const std::filesystem::path& path() const { return path_; }  ///< empty if it could not be made
  int error() const { return error_; }                         ///< errno when it could not

 private:
  std::filesystem::path path_;
  int error_ = 0;
};

/// The gnuplot program found on PATH, or empty when there is none.
std::filesystem::path findGnuplot();

/// The lab's scripts write their charts into the folder `outdir` names: runGnuplot sets it to a
/// private folder, and a person running `gnuplot SCRIPT` by hand gets the script's own folder.
inline constexpr const char* kOutdirDefault = "if (!exists('outdir')) outdir = '.'\n";

/// Runs `gnuplot SCRIPT` in `folder` (so the script names its data files relative to it), with
/// its charts drawn into a new hidden folder there and then each renamed into `folder`, so a
/// chart is replaced whole or not at all and a failed run leaves the old charts. Returns "" on
/// success, else one line saying why: gnuplot missing (with the package to install), its exit
/// status and the end of what it printed, or which chart could not be moved into place. The
/// messages name the script as `shownAs` when given (a script run where the user will not find it).
std::string runGnuplot(const std::filesystem::path& script, const std::filesystem::path& folder,
                       const std::filesystem::path& shownAs = {});

}  // namespace lab
