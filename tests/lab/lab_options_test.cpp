// The lab's command line, parsed in-process: every option's good values and every kind of bad
// argument, whose one-line message must name the argument.
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lab.h"
#include "options.h"

namespace {

using lab::Command;
using lab::parseCommandLine;
using Args = std::vector<std::string>;

TEST(LabOptions, RunWithDefaults) {
  const lab::ParsedCommand p = parseCommandLine({"run", "pendulum"});
  ASSERT_EQ(p.error, "");
  EXPECT_EQ(p.command, Command::Run);
  EXPECT_EQ(p.run.scene, "pendulum");
  EXPECT_EQ(p.run.steps, 600);
  EXPECT_FALSE(p.run.dt);
  EXPECT_FALSE(p.run.method);
  EXPECT_FALSE(p.run.iterations);
  EXPECT_FALSE(p.run.substeps);
  EXPECT_FALSE(p.run.json);
  EXPECT_FALSE(p.run.dump);
  EXPECT_TRUE(p.run.dataDir.empty());
  EXPECT_EQ(lab::dataDir(p.run), std::filesystem::path(DATA_DIR));
}

TEST(LabOptions, EveryOptionAnyOrder) {
  const lab::ParsedCommand p = parseCommandLine({"run", "--steps", "10000000", "--dt", "0.005", "--method",
                                                 "xpbd", "--iterations", "1000", "scene.xml", "--substeps",
                                                 "1", "--json", "--dump", "out.csv", "--data", "/d"});
  ASSERT_EQ(p.error, "");
  EXPECT_EQ(p.run.scene, "scene.xml");
  EXPECT_EQ(p.run.steps, 10000000);
  EXPECT_EQ(p.run.dt, 0.005);
  EXPECT_EQ(p.run.method, phys::SolverMethod::Xpbd);
  EXPECT_EQ(p.run.iterations, 1000);
  EXPECT_EQ(p.run.substeps, 1);
  EXPECT_TRUE(p.run.json);
  EXPECT_EQ(p.run.dump, std::filesystem::path("out.csv"));
  EXPECT_EQ(p.run.dataDir, std::filesystem::path("/d"));
  EXPECT_EQ(lab::dataDir(p.run), std::filesystem::path("/d"));
}

TEST(LabOptions, EveryMethodName) {
  for (const char* name : {"gauss-seidel", "jacobi", "xpbd", "shake"}) {
    const lab::ParsedCommand p = parseCommandLine({"run", "s", "--method", name});
    ASSERT_EQ(p.error, "") << name;
    EXPECT_EQ(phys::toString(*p.run.method), name);
  }
}

TEST(LabOptions, DtLimitsAndForms) {
  for (const char* good : {"1", "1e-3", "0.0166666666666667", "1.0"}) {
    EXPECT_EQ(parseCommandLine({"run", "s", "--dt", good}).error, "") << good;
  }
}

TEST(LabOptions, HelpInEveryForm) {
  for (const Args& args : {Args{"help"}, Args{"--help"}, Args{"-h"}, Args{"run", "s", "--help"}}) {
    const lab::ParsedCommand p = parseCommandLine(args);
    EXPECT_EQ(p.error, "") << args[0];
    EXPECT_EQ(p.command, Command::Help) << args[0];
  }
}

struct BadCase {
  Args args;
  std::string named;  // what the message must mention
};

// Readable test names in CTest: the arguments, not the struct's bytes.
void PrintTo(const BadCase& c, std::ostream* os) {
  *os << "lab";
  for (const std::string& a : c.args) *os << " '" << a << "'";
}

class LabOptionsBad : public ::testing::TestWithParam<BadCase> {};

TEST_P(LabOptionsBad, OneLineNamingTheArgument) {
  const BadCase& c = GetParam();
  const lab::ParsedCommand p = parseCommandLine(c.args);
  ASSERT_NE(p.error, "");
  EXPECT_NE(p.error.find(c.named), std::string::npos) << p.error;
  EXPECT_EQ(p.error.find('\n'), std::string::npos) << p.error;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, LabOptionsBad,
    ::testing::Values(
        BadCase{{}, "command"}, BadCase{{"frobnicate"}, "'frobnicate'"}, BadCase{{"--json"}, "'--json'"},
        BadCase{{"run"}, "SCENE"}, BadCase{{"run", "--json"}, "SCENE"}, BadCase{{"run", "a", "b"}, "'b'"},
        BadCase{{"run", "s", "--bogus"}, "'--bogus'"}, BadCase{{"run", "s", "-x"}, "'-x'"},
        // missing values, at the end or followed by another option
        BadCase{{"run", "s", "--steps"}, "--steps"}, BadCase{{"run", "s", "--dt"}, "--dt"},
        BadCase{{"run", "s", "--method"}, "--method"}, BadCase{{"run", "s", "--iterations"}, "--iterations"},
        BadCase{{"run", "s", "--substeps"}, "--substeps"}, BadCase{{"run", "s", "--dump"}, "--dump"},
        BadCase{{"run", "s", "--data"}, "--data"}, BadCase{{"run", "s", "--dump", "--json"}, "--dump"},
        // malformed numbers
        BadCase{{"run", "s", "--steps", "ten"}, "--steps: 'ten'"},
        BadCase{{"run", "s", "--steps", "10x"}, "--steps: '10x'"},
        BadCase{{"run", "s", "--steps", "1e3"}, "--steps: '1e3'"},
        BadCase{{"run", "s", "--steps", "+5"}, "--steps: '+5'"},
        BadCase{{"run", "s", "--steps", ""}, "--steps: ''"},
        BadCase{{"run", "s", "--dt", "fast"}, "--dt: 'fast'"},
        BadCase{{"run", "s", "--dt", "0.01s"}, "--dt: '0.01s'"},
        BadCase{{"run", "s", "--iterations", "3.5"}, "--iterations: '3.5'"},
        BadCase{{"run", "s", "--substeps", " 2"}, "--substeps: ' 2'"},
        // out of range
        BadCase{{"run", "s", "--steps", "0"}, "--steps: '0'"},
        BadCase{{"run", "s", "--steps", "-1"}, "--steps: '-1'"},
        BadCase{{"run", "s", "--steps", "10000001"}, "--steps: '10000001'"},
        BadCase{{"run", "s", "--steps", "99999999999999999999"}, "--steps"},
        BadCase{{"run", "s", "--dt", "0"}, "--dt: '0'"},
        BadCase{{"run", "s", "--dt", "-0.01"}, "--dt: '-0.01'"},
        BadCase{{"run", "s", "--dt", "1.5"}, "--dt: '1.5'"},
        BadCase{{"run", "s", "--dt", "inf"}, "--dt: 'inf'"},
        BadCase{{"run", "s", "--dt", "nan"}, "--dt: 'nan'"},
        BadCase{{"run", "s", "--dt", "1e-400"}, "--dt: '1e-400'"},
        BadCase{{"run", "s", "--iterations", "0"}, "--iterations: '0'"},
        BadCase{{"run", "s", "--iterations", "1001"}, "--iterations: '1001'"},
        BadCase{{"run", "s", "--substeps", "0"}, "--substeps: '0'"},
        BadCase{{"run", "s", "--substeps", "1001"}, "--substeps: '1001'"},
        BadCase{{"run", "s", "--method", "euler"}, "--method: unknown method 'euler'"},
        BadCase{{"run", "s", "--method", "Jacobi"}, "'Jacobi'"}));

TEST(LabOptions, UsageListsEveryOption) {
  const std::string u = lab::usage();
  for (const char* option :
       {"run SCENE", "--steps N", "--dt S", "--method M", "--iterations K", "--substeps S", "--model M",
        "--json", "--dump FILE", "--data DIR", "--help", "lab help"}) {
    EXPECT_NE(u.find(option), std::string::npos) << option;
  }
}

// The program as a function: usage on the right stream with the right exit code.
TEST(LabMain, HelpToStdoutUsageErrorsToStderr) {
  std::ostringstream out, err;
  EXPECT_EQ(lab::labMain({"help"}, out, err), lab::kExitOk);
  EXPECT_EQ(out.str(), lab::usage());
  EXPECT_EQ(err.str(), "");

  std::ostringstream out2, err2;
  EXPECT_EQ(lab::labMain({"run", "s", "--steps", "0"}, out2, err2), lab::kExitUsage);
  EXPECT_EQ(out2.str(), "");
  EXPECT_EQ(err2.str(), "lab: --steps: '0' is not a whole number from 1 to 10000000\n" + lab::usage());
}

TEST(LabMain, MissingSceneFileExitsOneWithTheOsReason) {
  std::ostringstream out, err;
  EXPECT_EQ(lab::labMain({"run", "/no/such/dir/scene.xml"}, out, err), lab::kExitFailure);
  EXPECT_EQ(out.str(), "");
  EXPECT_EQ(err.str().rfind("/no/such/dir/scene.xml: cannot open: No such file or directory", 0), 0u)
      << err.str();
}

}  // namespace
