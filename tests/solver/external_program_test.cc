// The runner of other programs (solver/report/external_program.h): every
// argument reaches the program as written, whatever a shell would make of
// it; standard input, output and error go where they are asked to; a
// missing program is an EnvironmentError naming its Debian package; the
// child inherits no other file descriptor, is waited for through signals and
// never stays a zombie, and a program that hangs is stopped.
#include "solver/report/external_program.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hb/errors.h"
#include "tests/support/temp_path.h"

namespace {

namespace fs = std::filesystem;
using beamid::solver::ExternalProgram;
using beamid::solver::RunExternalProgram;
using ::testing::HasSubstr;
using ::testing::Not;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// No child of this process is left, running or as a zombie.
void ExpectNoChildLeft() {
  errno = 0;
  EXPECT_EQ(::waitpid(-1, nullptr, WNOHANG), -1);
  EXPECT_EQ(errno, ECHILD);
}

class ExternalProgramTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = beamid::testing::UniqueTempPath("beamid_external_program");
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path folder_;
};

TEST_F(ExternalProgramTest, PassesEveryArgumentLiterallyWithoutAShell) {
  const fs::path sentinel = folder_ / "SENTINEL";
  const std::string touch = "touch " + sentinel.string();
  const std::vector<std::string> arguments = {
      "it's",        "\"double\"",  "$(" + touch + ")", "`" + touch + "`", "; " + touch, "a b  c", "",
      "*",           "$HOME",       "'.system('" + touch + "').'",         "line\nbreak", "-n", "back\\slash"};
  std::vector<std::string> argv = {"[%s]\n"};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  const fs::path out = folder_ / "out.txt";
  const int status = RunExternalProgram(
      {.program = "printf", .arguments = argv, .debian_package = "coreutils", .stdout_file = out});
  EXPECT_EQ(status, 0);
  std::string expected;
  for (const auto& a : arguments) expected += "[" + a + "]\n";
  EXPECT_EQ(ReadFile(out), expected);
  EXPECT_FALSE(fs::exists(sentinel));
  ExpectNoChildLeft();
}

TEST_F(ExternalProgramTest, GivesTheTextOnStandardInput) {
  std::string text;
  for (int i = 0; i < 200000; ++i) text += "line " + std::to_string(i) + " 'quoted' $(not run)\n";  // ~6 MB
  const fs::path out = folder_ / "copy.txt";
  EXPECT_EQ(RunExternalProgram({.program = "cat", .debian_package = "coreutils", .stdin_text = text, .stdout_file = out}),
            0);
  EXPECT_EQ(ReadFile(out), text);
}

TEST_F(ExternalProgramTest, WithoutTextStandardInputIsEmpty) {
  const fs::path out = folder_ / "copy.txt";
  EXPECT_EQ(RunExternalProgram({.program = "cat", .debian_package = "coreutils", .stdout_file = out}), 0);
  EXPECT_EQ(ReadFile(out), "");
}

TEST_F(ExternalProgramTest, CapturesStandardErrorApart) {
  const fs::path out = folder_ / "out.txt", err = folder_ / "err.txt";
  const int status = RunExternalProgram({.program = "ls",
                                         .arguments = {(folder_ / "no such file").string()},
                                         .debian_package = "coreutils",
                                         .stdout_file = out,
                                         .stderr_file = err});
  EXPECT_NE(status, 0);
  EXPECT_EQ(ReadFile(out), "");
  EXPECT_THAT(ReadFile(err), HasSubstr("no such file"));
}

TEST_F(ExternalProgramTest, ReturnsTheExitStatusOrTheSignal) {
  EXPECT_EQ(RunExternalProgram({.program = "true", .debian_package = "coreutils"}), 0);
  EXPECT_EQ(RunExternalProgram({.program = "false", .debian_package = "coreutils"}), 1);
  EXPECT_EQ(RunExternalProgram({.program = "sh", .arguments = {"-c", "exit 7"}, .debian_package = "dash"}), 7);
  EXPECT_EQ(RunExternalProgram({.program = "sh", .arguments = {"-c", "kill -TERM $$"}, .debian_package = "dash"}),
            128 + SIGTERM);
  ExpectNoChildLeft();
}

TEST_F(ExternalProgramTest, AMissingProgramNamesItsDebianPackage) {
  try {
    RunExternalProgram({.program = "beamid-no-such-program", .debian_package = "beamid-test-package"});
    FAIL() << "no EnvironmentError";
  } catch (const beamid::EnvironmentError& e) {
    EXPECT_THAT(e.what(), HasSubstr("beamid-no-such-program"));
    EXPECT_THAT(e.what(), HasSubstr("Debian package beamid-test-package"));
  }
  EXPECT_THROW(RunExternalProgram({.program = (folder_ / "nothing").string(), .debian_package = "x"}),
               beamid::EnvironmentError);
  ExpectNoChildLeft();
}

TEST_F(ExternalProgramTest, AnUnwritableOutputIsAnEnvironmentError) {
  EXPECT_THROW(RunExternalProgram({.program = "true",
                                   .debian_package = "coreutils",
                                   .stdout_file = folder_ / "no folder" / "out.txt"}),
               beamid::EnvironmentError);
}

TEST_F(ExternalProgramTest, TheChildInheritsNoOtherFileDescriptor) {
  // Opened without close-on-exec, as a library might, and moved to 100 (the
  // shell's own listing may take 3).
  const int fd = ::open((folder_ / "secret").c_str(), O_WRONLY | O_CREAT, 0600);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::dup2(fd, 100), 100);
  const fs::path out = folder_ / "fds.txt";
  // The shell lists the descriptors it was started with.
  EXPECT_EQ(RunExternalProgram({.program = "sh",
                                .arguments = {"-c", "for f in /proc/$$/fd/*; do echo \"${f##*/}\"; done"},
                                .debian_package = "dash",
                                .stdout_file = out}),
            0);
  ::close(100);
  ::close(fd);
  std::istringstream lines(ReadFile(out));
  std::vector<std::string> fds;
  for (std::string line; std::getline(lines, line);) fds.push_back(line);
  for (const char* standard : {"0", "1", "2"}) EXPECT_THAT(fds, ::testing::Contains(standard));
  EXPECT_THAT(fds, Not(::testing::Contains("100")));
}

volatile sig_atomic_t alarms = 0;
void CountAlarm(int) { alarms = alarms + 1; }

TEST_F(ExternalProgramTest, WaitsThroughInterruptingSignals) {
  struct sigaction action {};
  action.sa_handler = CountAlarm;
  action.sa_flags = 0;  // no SA_RESTART: waitpid returns EINTR
  struct sigaction previous {};
  ASSERT_EQ(::sigaction(SIGALRM, &action, &previous), 0);
  itimerval every_ms{{0, 1000}, {0, 1000}};
  ASSERT_EQ(::setitimer(ITIMER_REAL, &every_ms, nullptr), 0);
  const fs::path out = folder_ / "out.txt";
  const int status = RunExternalProgram({.program = "sh",
                                         .arguments = {"-c", "sleep 0.3; echo done"},
                                         .debian_package = "dash",
                                         .stdout_file = out});
  itimerval off{};
  ::setitimer(ITIMER_REAL, &off, nullptr);
  ::sigaction(SIGALRM, &previous, nullptr);
  EXPECT_GT(alarms, 10);
  EXPECT_EQ(status, 0);
  EXPECT_EQ(ReadFile(out), "done\n");
  ExpectNoChildLeft();
}

TEST_F(ExternalProgramTest, AProgramPastItsTimeoutIsStoppedAndReaped) {
  const auto start = std::chrono::steady_clock::now();
  try {
    RunExternalProgram({.program = "sleep", .arguments = {"30"}, .debian_package = "coreutils", .timeout_s = 0.3});
    FAIL() << "no EnvironmentError";
  } catch (const beamid::EnvironmentError& e) {
    EXPECT_THAT(e.what(), HasSubstr("did not finish within 0.3 s"));
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  ExpectNoChildLeft();
}

}  // namespace
