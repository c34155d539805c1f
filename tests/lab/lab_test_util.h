#pragma once
// Helpers shared by the lab tests: the scene texts (in one place, so a change of the scene
// format, docs/scene-format.md, is one edit), temporary files, the check of a usage error,
// running the real program, and reading its one-line JSON back. (Commands run in-process
// through lab::runCaptured, and their CSVs are read with csv.h: what `lab report` itself uses.)
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "commands.h"
#include "json.h"
#include "lab.h"

namespace lab_testing {

/// The keys of `lab run --json`, in the order the lab writes them (docs/lab.md, "lab run").
inline const std::vector<std::string> kRunJsonKeys = {"scene",
                                                      "method",
                                                      "iterations",
                                                      "substeps",
                                                      "dt",
                                                      "joint_projection",
                                                      "threads",
                                                      "sleep",
                                                      "steps",
                                                      "particles",
                                                      "constraints",
                                                      "bodies",
                                                      "contacts",
                                                      "ms_per_step",
                                                      "max_constraint_error",
                                                      "rms_constraint_error",
                                                      "max_joint_error",
                                                      "max_penetration",
                                                      "max_speed",
                                                      "max_stick_error_over_run",
                                                      "max_joint_error_over_run",
                                                      "max_penetration_over_run",
                                                      "max_angular_speed_over_run",
                                                      "rms_tracking_error_over_run",
                                                      "energy_initial",
                                                      "energy_final",
                                                      "frozen",
                                                      "islands",
                                                      "largest_island",
                                                      "awake_bodies",
                                                      "sleeping_bodies",
                                                      "hash"};

/// Standard gravity, as the scenes below state it. unit: m/s^2
inline constexpr double kGravity = 9.81;
/// Where the free-falling particle starts. unit: m
inline constexpr double kDropHeight = 5.0;

/// One particle "p" at kDropHeight, and no ground under it (a scene without <ground> has
/// none), so it falls freely however long the run.
inline std::string freeFallScene() {
  return "<scene name=\"t\">\n"
         "  <world gravity=\"0 -9.81 0\"/>\n"
         "  <solver/>\n"
         "  <particle name=\"p\" pos=\"0 5 0\" mass=\"1\"/>\n"
         "</scene>\n";
}

/// Named bodies of both kinds for the dump, an unnamed particle that must not be dumped, and
/// a stick; the box rests on the ground.
inline std::string namedBodiesScene() {
  return "<scene name=\"named\">\n"
         "  <world/>\n"
         "  <ground/>\n"
         "  <box name=\"crate\" pos=\"0 0.5 0\" size=\"1 1 1\"/>\n"
         "  <particle name=\"a\" pos=\"2 3 0\" mass=\"1\"/>\n"
         "  <particle name=\"b,&quot;odd&quot;\" pos=\"3 3 0\" mass=\"1\"/>\n"
         "  <particle pos=\"4 3 0\" mass=\"1\"/>\n"
         "  <stick a=\"a\" b=\"b,&quot;odd&quot;\" length=\"auto\"/>\n"
         "</scene>\n";
}

/// A particle shot out of a world bounded at 10 m, for the guard to freeze.
inline std::string escapingScene() {
  return "<scene name=\"escape\">\n"
         "  <world bound=\"10\"/>\n"
         "  <particle name=\"runaway\" pos=\"0 5 0\" velocity=\"100 0 0\" mass=\"1\"/>\n"
         "</scene>\n";
}

/// A scene whose line 3 is wrong (a position that is not three numbers).
inline std::string badSceneLine3() {
  return "<scene name=\"bad\">\n"
         "  <world/>\n"
         "  <particle name=\"p\" pos=\"0 five 0\" mass=\"1\"/>\n"
         "</scene>\n";
}

/// A fresh folder for this test's files, removed at the end of the test. CTest may run the
/// cases in parallel processes, so the name carries the process id and the test's name.
class TempDir {
 public:
  TempDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("lab_tests_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  /// A path inside the folder.
  std::filesystem::path file(const std::string& name) const { return path_ / name; }
  /// Writes text to a file in the folder and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
    return path_ / name;
  }

 private:
  std::filesystem::path path_;
};

/// A whole file as a string ("" when it cannot be read).
inline std::string readFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A command-line mistake as every lab command reports it (commands.h): exit 2, an error line
/// "lab: ..." that names the bad argument, the command's usage, and nothing on stdout.
inline void expectUsageError(const lab::CommandOutput& o, const std::string& command,
                             const std::string& named) {
  EXPECT_EQ(o.code, lab::kExitUsage) << o.err;
  EXPECT_TRUE(o.err.starts_with("lab: ")) << o.err;
  EXPECT_NE(o.err.find(named), std::string::npos) << named << " in " << o.err;
  EXPECT_NE(o.err.find("usage: lab " + command), std::string::npos) << o.err;
  EXPECT_TRUE(o.out.empty()) << o.out;
}

/// What the real program did.
struct ProcessResult {
  int exitCode = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// Runs `lab ARGS` through the shell (ARGS already quoted), stdout and stderr apart.
inline ProcessResult runLab(const std::string& args, const TempDir& dir) {
  ProcessResult r;
  const std::filesystem::path errFile = dir.file("stderr.txt");
  const std::string command = std::string("'") + LAB_EXE + "' " + args + " 2>'" + errFile.string() + "'";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 512> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) r.out += buffer.data();
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = readFile(errFile);
  return r;
}

/// A path quoted for the shell.
inline std::string quoted(const std::filesystem::path& p) {
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) about "'" + std::string.
  std::string s = "'";
  s += p.string();
  s += '\'';
  return s;
}

/// One flat JSON object: each key's value as JSON text (strings keep their quotes), in file
/// order in `keys`; nullopt when the text is not one such object (nlohmann/json reads it, so
/// NaN, a trailing comma or a second object fail as they should).
struct FlatJson {
  std::vector<std::string> keys;
  std::map<std::string, std::string> values;
};

inline std::optional<FlatJson> parseFlatJson(const std::string& text) {
  const lab::Json j = lab::Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return std::nullopt;  // a parse error is "discarded", not an object
  FlatJson flat;
  for (const auto& [key, value] : j.items()) {
    if (value.is_structured()) return std::nullopt;
    flat.keys.push_back(key);
    flat.values[key] = value.dump();
  }
  return flat;
}

/// A JSON number value as a double (NaN for null or a string).
inline double number(const FlatJson& j, const std::string& key) {
  const auto it = j.values.find(key);
  if (it == j.values.end() || it->second == "null" || it->second.starts_with("\"")) return std::nan("");
  return std::strtod(it->second.c_str(), nullptr);
}

/// A JSON string value without its quotes ("" when missing or not a string).
inline std::string text(const FlatJson& j, const std::string& key) {
  const auto it = j.values.find(key);
  if (it == j.values.end() || !it->second.starts_with("\"")) return "";
  return it->second.substr(1, it->second.size() - 2);
}

}  // namespace lab_testing
