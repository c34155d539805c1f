// The lab's command line, parsed in-process: every option's good values and every kind of bad
// argument, whose one-line message must name the argument.
#include <new>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "commands.h"
#include "lab.h"
#include "options.h"
#include "stability_options.h"

namespace {

using Args = std::vector<std::string>;

// The arguments after "run", parsed by lab run's own command line.
lab::RunOptions parsed(const Args& args) {
  lab::RunOptions o;
  lab::CommandLine line("run");
  lab::describeRun(line, o);
  EXPECT_EQ(line.parse(args), "") << (args.empty() ? "" : args.back());
  return o;
}

TEST(LabOptions, RunWithDefaults) {
  const lab::RunOptions o = parsed({"pendulum"});
  EXPECT_EQ(o.scene, "pendulum");
  EXPECT_EQ(o.steps, 600);
  EXPECT_FALSE(o.dt);
  EXPECT_FALSE(o.method);
  EXPECT_FALSE(o.iterations);
  EXPECT_FALSE(o.substeps);
  EXPECT_FALSE(o.json);
  EXPECT_FALSE(o.dump);
  EXPECT_TRUE(o.dataDir.empty());
  EXPECT_EQ(lab::dataDir(o.dataDir), std::filesystem::path(DATA_DIR));
}

TEST(LabOptions, EveryOptionAnyOrder) {
  const lab::RunOptions o =
      parsed({"--steps",   "10000000",   "--dt",    "0.005",  "--methods", "xpbd",    "--iterations", "1000",
              "scene.xml", "--substeps", "1",       "--json", "--dump",    "out.csv", "--data",       "/d",
              "--models",  "rigid",      "--sleep", "on",     "--threads", "2"});
  EXPECT_EQ(o.scene, "scene.xml");
  EXPECT_EQ(o.steps, 10000000);
  EXPECT_EQ(o.dt, 0.005);
  EXPECT_EQ(o.method, phys::SolverMethod::Xpbd);
  EXPECT_EQ(o.iterations, 1000);
  EXPECT_EQ(o.substeps, 1);
  EXPECT_TRUE(o.json);
  EXPECT_EQ(o.dump, std::filesystem::path("out.csv"));
  EXPECT_EQ(o.dataDir, std::filesystem::path("/d"));
  EXPECT_EQ(o.model, phys::BodyModel::Rigid);
  EXPECT_TRUE(o.sleep);
  EXPECT_EQ(o.threads, 2);
  EXPECT_EQ(lab::dataDir(o.dataDir), std::filesystem::path("/d"));
}

// The old spellings stay as aliases, and CLI11's --option=value form works too.
TEST(LabOptions, AliasesAndEqualsForm) {
  const lab::RunOptions o = parsed({"s", "--method", "jacobi", "--model=tetra", "--steps=7"});
  EXPECT_EQ(o.method, phys::SolverMethod::Jacobi);
  EXPECT_EQ(o.model, phys::BodyModel::Tetra);
  EXPECT_EQ(o.steps, 7);
}

// An option given twice: the last one counts.
TEST(LabOptions, LastValueWins) {
  EXPECT_EQ(parsed({"s", "--steps", "5", "--steps", "9"}).steps, 9);
}

TEST(LabOptions, EveryMethodName) {
  for (const char* name : {"gauss-seidel", "jacobi", "xpbd", "shake"}) {
    EXPECT_EQ(phys::toString(*parsed({"s", "--methods", name}).method), name);
  }
}

TEST(LabOptions, DtLimitsAndForms) {
  for (const char* good : {"1", "1e-3", "0.0166666666666667", "1.0", "1e-06"}) parsed({"s", "--dt", good});
}

// A LIST drops the command's defaults at its first value, a second one adds to the first, and
// a value listed twice counts once.
TEST(LabOptions, ListsReplaceTheDefaultsAndAddUp) {
  lab::stability::StabilityOptions o;
  lab::CommandLine line("stability");
  lab::stability::describeOptions(line, o);
  ASSERT_EQ(line.parse({"--iterations", "2", "--iterations", "5,2", "--scene", "a", "b", "--scene", "c,d"}),
            "");
  EXPECT_EQ(o.iterations, (std::vector<int>{2, 5}));
  EXPECT_EQ(o.substeps, (std::vector<int>{1, 4, 16}));  // not given: the defaults
  EXPECT_EQ(o.scenes, (std::vector<std::string>{"a", "b", "c", "d"}));
}

// The word after a "--" is a positional: a second SCENE, named as one.
TEST(LabOptions, AfterTheMarkerAWordIsASecondScene) {
  const lab::CommandOutput o = lab::runCaptured({"run", "a", "--", "b"});
  EXPECT_EQ(o.code, lab::kExitUsage);
  EXPECT_NE(o.err.find("run takes one SCENE; got 'a' and 'b'"), std::string::npos) << o.err;
}

TEST(LabOptions, HelpInEveryForm) {
  for (const Args& args : {Args{"help"}, Args{"--help"}, Args{"-h"}, Args{"run", "s", "--help"},
                           Args{"run", "--steps", "0", "-h"}, Args{"sweep", "--help"}}) {
    const lab::CommandOutput o = lab::runCaptured(args);
    EXPECT_EQ(o.code, lab::kExitOk) << args[0];
    EXPECT_TRUE(o.out.starts_with("usage: lab")) << o.out;
    EXPECT_EQ(o.err, "");
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

// Exit 2, "lab: " and one line naming the argument, then the usage; nothing on stdout.
TEST_P(LabOptionsBad, OneLineNamingTheArgument) {
  const BadCase& c = GetParam();
  const lab::CommandOutput o = lab::runCaptured(c.args);
  EXPECT_EQ(o.code, lab::kExitUsage);
  EXPECT_EQ(o.out, "");
  ASSERT_TRUE(o.err.starts_with("lab: ")) << o.err;
  const std::string line = o.err.substr(0, o.err.find('\n'));
  EXPECT_NE(line.find(c.named), std::string::npos) << line;
  EXPECT_NE(o.err.find("\nusage: lab"), std::string::npos) << o.err;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, LabOptionsBad,
    ::testing::Values(
        BadCase{{}, "command"}, BadCase{{"frobnicate"}, "'frobnicate'"}, BadCase{{"--json"}, "'--json'"},
        BadCase{{"run"}, "SCENE"}, BadCase{{"run", ""}, "SCENE"}, BadCase{{"run", "--json"}, "SCENE"},
        BadCase{{"run", "a", "b"}, "'b'"}, BadCase{{"run", "s", "--bogus"}, "'--bogus'"},
        BadCase{{"run", "s", "-x"}, "'-x'"},
        // a value given to a flag: CLI11's own words were "Could not convert: --json = banana"
        BadCase{{"run", "s", "--json=banana"}, "--json takes no value"},
        BadCase{{"run", "s", "--json=no"}, "--json takes no value"},
        // and an empty one, which CLI11 took as on
        BadCase{{"run", "s", "--json="}, "--json takes no value"},
        BadCase{{"stability", "--no-peers="}, "--no-peers takes no value"},
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
        BadCase{{"run", "s", "--steps", ""}, "--steps is empty: it needs a whole number"},
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
        BadCase{{"run", "s", "--method", "euler"}, "--methods: unknown method 'euler'"},
        BadCase{{"run", "s", "--models", "soft"}, "--models: unknown model 'soft'"},
        BadCase{{"run", "s", "--sleep", "yes"}, "--sleep: 'yes' is not on or off"},
        BadCase{{"run", "s", "--threads", "65"}, "--threads: '65'"},
        BadCase{{"run", "s", "--dump", ""}, "--dump is empty: it needs a file name"},
        BadCase{{"run", "s", "--steps", "--json"}, "--steps needs a whole number"},
        BadCase{{"sweep", "s", "--out", "d", "--iterations", "1,,2"}, "--iterations: '1,,2'"},
        BadCase{{"sweep", "s", "--out", "d", "--methods", "xpbd,euler"}, "--methods: unknown method 'euler'"},
        BadCase{{"sweep", "s"}, "--out DIR"}, BadCase{{"run", "s", "--method", "Jacobi"}, "'Jacobi'"}));

// The options of a command that take a value, as its help lists them ("  --steps N", the first
// spelling of each).
std::vector<std::string> optionsTakingAValue(const std::string& command) {
  std::istringstream help(lab::runCaptured({command, "--help"}).out);
  std::vector<std::string> options;
  for (std::string line; std::getline(help, line);) {
    if (!line.starts_with("  --")) continue;
    std::istringstream words(line);
    std::string name, value;
    words >> name >> value;
    // A flag's help follows its name; an option's value is in capitals or on|off ("N", "DIR").
    const bool takesValue =
        !value.empty() &&
        (value == "on|off" || value.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ=.") == std::string::npos);
    if (takesValue && name != "--help") options.push_back(name);
  }
  return options;
}

// An empty value is said in one wording, whatever the option and the command: `--steps ""` read
// "'' is not a whole number", `--methods ""` "'' is not a comma-separated list", `--out ""` "the
// folder name is empty", `--error ""` "unknown figure ''".
TEST(LabOptions, AnEmptyValueIsSaidAlikeForEveryOptionOfEveryCommand) {
  std::size_t checked = 0;
  for (const char* command :
       {"run", "sweep", "stability", "tune", "compare", "scale", "converge", "report"}) {
    const std::vector<std::string> options = optionsTakingAValue(command);
    EXPECT_FALSE(options.empty()) << command;
    const bool takesScene = lab::runCaptured({command, "--help"})
                                .out.starts_with(std::string("usage: lab ") + command + " SCENE");
    for (const std::string& option : options) {
      for (const Args& given : {Args{option, ""}, Args{option + "="}}) {
        Args args{command};
        if (takesScene) args.push_back("s");
        args.insert(args.end(), given.begin(), given.end());
        const lab::CommandOutput o = lab::runCaptured(args);
        EXPECT_EQ(o.code, lab::kExitUsage) << command << " " << option;
        const std::string line = o.err.substr(0, o.err.find('\n'));
        EXPECT_TRUE(line.starts_with("lab: " + option + " is empty: it needs ")) << command << ": " << line;
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 60u);  // every command's options, each as `--x ""` and `--x=`
}

TEST(LabOptions, HelpListsEveryOption) {
  const std::string u = lab::runCaptured({"run", "--help"}).out;
  for (const char* option : {"usage: lab run SCENE", "--steps N", "--dt S", "--methods M", "--iterations K",
                             "--substeps S", "--models M", "--sleep on|off", "--threads N", "--json",
                             "--dump FILE", "--data DIR", "--help", "--method too", "--model too"}) {
    EXPECT_NE(u.find(option), std::string::npos) << option;
  }
}

// The help writes each range from the option table's numbers, as the errors do: a count's, a
// time's, a time above its least; no "{range}" is left standing.
TEST(LabOptions, HelpWritesTheRangesOutFromTheTable) {
  const std::string run = lab::runCaptured({"run", "--help"}).out;
  for (const char* text :
       {"steps to run, 1 to 10000000", "seconds per step, 1e-06 to 1", "threads the step may use, 1 to 64"}) {
    EXPECT_NE(run.find(text), std::string::npos) << text;
  }
  EXPECT_NE(lab::runCaptured({"converge", "--help"}).out.find("s, above 0 and at most 3600"),
            std::string::npos);
  EXPECT_NE(lab::runCaptured({"scale", "--help"}).out.find("sizes, comma-separated, 1 to 4096: ragdolls"),
            std::string::npos);
  for (const char* command : {"run", "sweep", "stability", "tune", "compare", "scale", "converge", "report"})
    EXPECT_EQ(lab::runCaptured({command, "--help"}).out.find("{range}"), std::string::npos) << command;
}

// `lab help` names every command; the help of each begins with its usage line.
TEST(LabOptions, EveryCommandHasHelp) {
  const std::string overview = lab::usage();
  for (const char* command :
       {"run", "sweep", "stability", "tune", "compare", "scale", "converge", "report"}) {
    EXPECT_NE(overview.find(std::string("  ") + command + " "), std::string::npos) << command;
    const lab::CommandOutput o = lab::runCaptured({command, "--help"});
    EXPECT_EQ(o.code, lab::kExitOk) << command;
    EXPECT_TRUE(o.out.starts_with(std::string("usage: lab ") + command)) << o.out;
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
  const std::string help = lab::runCaptured({"run", "--help"}).out;
  EXPECT_EQ(err2.str(), "lab: --steps: '0' is not a whole number from 1 to 10000000\n" + help);
}

TEST(LabMain, MissingSceneFileExitsOneWithTheOsReason) {
  std::ostringstream out, err;
  EXPECT_EQ(lab::labMain({"run", "/no/such/dir/scene.xml"}, out, err), lab::kExitFailure);
  EXPECT_EQ(out.str(), "");
  EXPECT_EQ(err.str().rfind("/no/such/dir/scene.xml: cannot open: No such file or directory", 0), 0u)
      << err.str();
}

// A run too large for the machine says so in words (it printed "lab: run: std::bad_alloc").
TEST(LabMain, OutOfMemoryIsSaidInWords) {
  lab::CommandLine line("run");
  std::ostringstream out, err;
  EXPECT_EQ(lab::commandMain(line, {}, out, err, []() -> int { throw std::bad_alloc(); }), lab::kExitFailure);
  EXPECT_EQ(err.str(), "lab: run: out of memory (the scene or the run is too large for this machine)\n");
}

}  // namespace
