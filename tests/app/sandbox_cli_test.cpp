// The sandbox program itself, run as a user would, where no display is needed.
#include <array>
#include <cstdio>
#include <string>

#include <sys/wait.h>

#include <gtest/gtest.h>

namespace {

struct ProcessResult {
  int exitCode;
  std::string output;  // stdout and stderr together
};

ProcessResult runShell(const std::string& command) {
  ProcessResult r{-1, {}};
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 512> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) r.output += buffer.data();
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

const std::string kSandbox = std::string("'") + SANDBOX_EXE + "'";

TEST(SandboxCli, WithoutADisplaySaysSoInOneLineAndFails) {
  const ProcessResult r = runShell("env -u DISPLAY -u WAYLAND_DISPLAY " + kSandbox);
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(r.output,
            "sandbox: no DISPLAY; use --screenshot under xvfb-run "
            "(e.g. xvfb-run -a sandbox --screenshot out.png)\n");
}

TEST(SandboxCli, UsageErrorsExitTwoAndShowUsage) {
  const ProcessResult r = runShell(kSandbox + " --frames nope");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("--frames: 'nope'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("usage: sandbox"), std::string::npos) << r.output;
}

// The arguments are checked before the display is looked for: a mistyped name is said as that,
// not as a missing display, and no window is opened for a run that cannot work.
TEST(SandboxCli, BadArgumentsAreRefusedBeforeTheDisplayIsLookedFor) {
  const std::string noDisplay = "env -u DISPLAY -u WAYLAND_DISPLAY " + kSandbox;
  ProcessResult r = runShell(noDisplay + " /no-such-folder/x.xml");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.output,
            "sandbox: scene: /no-such-folder/x.xml: cannot open scene file: No such file or directory\n");
  r = runShell(noDisplay + " --screenshot /no-such-folder/a.png");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.output,
            "sandbox: --screenshot '/no-such-folder/a.png': its folder '/no-such-folder': No such file or "
            "directory\n");
  r = runShell(noDisplay + " --data /no-such-folder");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.output, "sandbox: --data '/no-such-folder': No such file or directory\n");
  r = runShell(noDisplay + " --threads 2 --threads 3");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.output.substr(0, r.output.find('\n')), "sandbox: --threads is given twice; give it once");
}

TEST(SandboxCli, HelpExitsZero) {
  const ProcessResult r = runShell(kSandbox + " --help");
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.output.find("--screenshot FILE"), std::string::npos);
}

}  // namespace
