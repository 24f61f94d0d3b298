// No command replaces what it reads, or a device node, and no command waits
// forever on what it is given: run through the real program, every output
// option of every command pointed at each of its inputs (a recording,
// campaign.json, the model, result, phasors or scenario it reads) is refused
// with exit 2 before any work and leaves every input byte for byte as it
// was; an output that is a character device (made here with mknod: the null
// device) is written in place and stays a device; two outputs of one run on
// one path, a FIFO as an output and a FIFO or a device as any input are
// refused at once (each run has a time limit, so a run that blocks fails
// instead of hanging the suite).
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/file_bytes.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/temp_path.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using beamid::testing::ProgramRun;
using beamid::testing::ReadFile;
using beamid::testing::WriteFile;

bool IsCharacterDevice(const fs::path& path) {
  struct stat status {};
  return ::lstat(path.c_str(), &status) == 0 && S_ISCHR(status.st_mode);
}

class DataSafety : public ::testing::Test {
 protected:
  // `timeout` ends a run that blocks (exit 124): a FIFO read must fail fast.
  static ProgramRun Beamid(const std::string& arguments, int seconds = 60) {
    const fs::path log = root_ / "run.log";
    const std::string command = "timeout " + std::to_string(seconds) + " " + std::string(BEAMID_EXECUTABLE) + " " +
                                arguments + " > " + log.string() + " 2>&1 < /dev/null";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ReadFile(log)};
  }

  static void SetUpTestSuite() {
    root_ = beamid::testing::UniqueTempPath("beamid_data_safety");
    fs::remove_all(root_);
    fs::create_directories(root_);
    WriteFile(root_ / "scenario.json", beamid::testing::PaperScenarioJson("data safety", R"([
      {"label": "low", "force_amplitude_N": 0.5, "frequencies_Hz": {"start": 53.6, "stop": 54.6, "step": 0.5}}])", 3));
    fs::copy_file("examples/paper_setup/model.json", root_ / "model.json");
    const std::string r = root_.string();
    for (const std::string& step :
         {"-q simulate " + r + "/scenario.json -o " + r + "/C", "-q extract " + r + "/C -o " + r + "/phasors.json",
          "-q identify " + r + "/C --phasors " + r + "/phasors.json --fit acc1,acc2 --no-damping-laws --no-robust -o " +
              r + "/result.json"}) {
      setup_ = Beamid(step, 300);
      if (setup_.exit_code != 0) {
        setup_.output = step + "\n" + setup_.output;
        return;
      }
    }
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  void SetUp() override { ASSERT_EQ(setup_.exit_code, 0) << setup_.output; }

  // Every input's bytes, to be compared after each run.
  static std::map<fs::path, std::string> Inputs() {
    std::map<fs::path, std::string> bytes;
    for (const auto& entry : fs::recursive_directory_iterator(root_ / "C"))
      if (entry.is_regular_file()) bytes[entry.path()] = ReadFile(entry.path());
    for (const char* name : {"scenario.json", "model.json", "phasors.json", "result.json"})
      bytes[root_ / name] = ReadFile(root_ / name);
    return bytes;
  }

  // {r}: the suite's folder, {C}: its campaign.
  static std::string Expand(std::string text) {
    for (const auto& [key, value] : {std::pair{"{r}", root_.string()}, {"{C}", (root_ / "C").string()}})
      for (std::size_t at; (at = text.find(key)) != std::string::npos;) text.replace(at, 3, value);
    return text;
  }

  static inline fs::path root_;
  static inline ProgramRun setup_;
};

TEST_F(DataSafety, EveryOutputOptionPointedAtAnInputIsRefusedAndTheInputsStayByteIdentical) {
  struct Row {
    std::string arguments;
    std::string key_word;  // the option named in the message
  };
  const std::vector<Row> rows = {
      {"extract {C} -o {C}/low/step_001.csv", "-o"},
      {"extract {C} -o {C}/campaign.json", "-o"},
      {"extract {C} -o {r}/p.json --csv {C}/campaign.json", "--csv"},
      {"extract {C} -o {C}/new_file.json", "-o"},  // a new file inside the campaign folder
      {"extract {C} -o {C}", "-o"},
      {"extract {C} -o {C}/low/../low/step_000.csv", "-o"},
      {"identify {C} -o {C}/low/step_002.csv", "-o"},
      {"identify {C} --phasors {r}/phasors.json -o {r}/phasors.json", "-o"},
      {"diagnose {C} -o {C}/campaign.json", "-o"},
      {"diagnose {C} --curves {C}/low/step_001 -o {r}/d.json", "--curves"},
      {"diagnose {C} --result {r}/result.json -o {r}/result.json", "-o"},
      {"diagnose {C} --phasors {r}/phasors.json -o {r}/phasors.json", "-o"},
      {"predict {r}/result.json --x 0.3 -o {r}/result.json", "-o"},
      {"predict {r}/result.json --campaign {C} --x 0.3 -o {C}/campaign.json", "-o"},
      {"report {r}/result.json -o {r}/result.json", "-o"},
      {"report {r}/result.json -o {C}/campaign.json", "-o"},
      {"report {r}/result.json -o {r}/report.html --screenshot {r}/result.json", "--screenshot"},
      // The campaign is the one result.json names: known after reading it.
      {"report {r}/result.json -o {r}/report.html --screenshot {C}/campaign.json", "--screenshot"},
      {"backbone {r}/model.json -o {r}/model", "-o"},
      {"backbone --measured {C} -o {C}/low/step_001", "-o"},
      {"backbone --measured {r}/phasors.json -o {r}/phasors", "-o"},
      {"backbone --measured {C} --result {r}/result.json -o {r}/result", "-o"},
      {"frc {r}/model.json -o {r}/model", "-o"},
      {"simulate {r}/scenario.json -o {r}", "-o"},  // the folder holds the scenario
      {"simulate {r}/scenario.json -o {r}/model.json", "-o"},
  };
  const std::map<fs::path, std::string> before = Inputs();
  for (const Row& row : rows) {
    const std::string arguments = Expand(row.arguments);
    SCOPED_TRACE(arguments);
    const ProgramRun run = Beamid(arguments);
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_THAT(run.output, HasSubstr(row.key_word));
    EXPECT_THAT(run.output, ::testing::Not(HasSubstr("internal error")));
    const std::map<fs::path, std::string> after = Inputs();
    EXPECT_EQ(after.size(), before.size()) << "a file appeared in or vanished from the inputs";
    for (const auto& [path, bytes] : before) {
      const auto it = after.find(path);
      ASSERT_NE(it, after.end()) << path << " vanished";
      EXPECT_TRUE(it->second == bytes) << path << " changed";
    }
  }
}

TEST_F(DataSafety, TwoOutputsOnOnePathAndAFifoOrAFolderAsOutputAreRefused) {
  const fs::path d = root_ / "outputs";
  fs::create_directories(d / "folder");
  ASSERT_EQ(::mkfifo((d / "fifo").c_str(), 0600), 0) << std::strerror(errno);
  for (const char* arguments :
       {"extract {C} -o {r}/outputs/same.json --csv {r}/outputs/same.json",
        "diagnose {C} -o {r}/outputs/frc.csv --curves {r}/outputs/frc", "extract {C} -o {r}/outputs/fifo",
        "extract {C} -o {r}/outputs/p.json --csv {r}/outputs/fifo", "predict {r}/result.json --x 0.3 -o {r}/outputs/folder",
        "frc {r}/model.json -o ''", "extract {C} -o ''", "extract {C} --csv '' -o {r}/outputs/p.json"}) {
    SCOPED_TRACE(arguments);
    const ProgramRun run = Beamid(Expand(arguments), 20);
    EXPECT_EQ(run.exit_code, 2) << run.output;
  }
  // Nothing was written beside them, and the FIFO is still one.
  EXPECT_FALSE(fs::exists(d / "same.json"));
  EXPECT_FALSE(fs::exists(d / "p.json"));
  EXPECT_TRUE(fs::is_fifo(d / "fifo"));
}

TEST_F(DataSafety, AFifoOrADeviceAsAnyInputIsRefusedAtOnceNamingWhatItIs) {
  const fs::path d = root_ / "fifo_inputs";
  fs::create_directories(d);
  ASSERT_EQ(::mkfifo((d / "fifo.json").c_str(), 0600), 0) << std::strerror(errno);
  ASSERT_EQ(::mkfifo((d / "fifo.csv").c_str(), 0600), 0) << std::strerror(errno);
  // A campaign whose campaign.json is a FIFO, one whose description is
  // /dev/zero (read until memory ran out), one whose recording is a FIFO and
  // one whose recording is a folder.
  for (const char* name : {"fifo_campaign", "zero_campaign", "fifo_step", "folder_step"})
    fs::copy(root_ / "C", d / name, fs::copy_options::recursive);
  fs::remove(d / "fifo_campaign" / "campaign.json");
  ASSERT_EQ(::mkfifo((d / "fifo_campaign" / "campaign.json").c_str(), 0600), 0);
  fs::remove(d / "zero_campaign" / "campaign.json");
  fs::create_symlink("/dev/zero", d / "zero_campaign" / "campaign.json");
  fs::remove(d / "fifo_step" / "low" / "step_001.csv");
  ASSERT_EQ(::mkfifo((d / "fifo_step" / "low" / "step_001.csv").c_str(), 0600), 0);
  fs::remove(d / "folder_step" / "low" / "step_001.csv");
  fs::create_directories(d / "folder_step" / "low" / "step_001.csv");
  const std::string f = d.string();
  struct Row {
    std::string arguments;
    std::string kind;
  };
  const std::vector<Row> rows = {
      {"extract " + f + "/fifo_campaign -o " + f + "/p.json", "FIFO"},
      {"identify " + f + "/zero_campaign -o " + f + "/r.json", "character device"},
      {"extract " + f + "/fifo_step -o " + f + "/p.json", "FIFO"},
      {"extract " + f + "/folder_step -o " + f + "/p.json", "folder"},
      {"frc " + f + "/fifo.json -o " + f + "/frc", "FIFO"},
      {"backbone " + f + "/fifo.json -o " + f + "/bb", "FIFO"},
      {"simulate " + f + "/fifo.json -o " + f + "/sim", "FIFO"},
      {Expand("identify {C} --phasors ") + f + "/fifo.json -o " + f + "/r.json", "FIFO"},
      {"predict " + f + "/fifo.json --x 0.3 -o " + f + "/pred.json", "FIFO"},
      {"report " + f + "/fifo.json -o " + f + "/report.html", "FIFO"},
      {Expand("diagnose {C} --result ") + f + "/fifo.json -o " + f + "/d.json", "FIFO"},
      {"backbone --measured " + f + "/fifo.csv -o " + f + "/bb", "FIFO"},
      {"backbone --measured " + f + "/fifo.json -o " + f + "/bb", "FIFO"},
      {"frc /dev/zero -o " + f + "/frc", "character device"},
  };
  for (const Row& row : rows) {
    SCOPED_TRACE(row.arguments);
    const ProgramRun run = Beamid(row.arguments, 20);
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_THAT(run.output, HasSubstr(row.kind));
  }
}

// A character device as an output is written in place: the node stays a
// node (a rename over it would have replaced it by a regular file), and
// the inputs are untouched.
TEST_F(DataSafety, ACharacterDeviceAsOutputIsWrittenInPlaceAndStaysADevice) {
  const fs::path d = root_ / "devices";
  fs::create_directories(d);
  for (const char* name : {"null", "null.csv"})
    if (::mknod((d / name).c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) {
      if (errno == EPERM) GTEST_SKIP() << "mknod needs root (CAP_MKNOD)";
      FAIL() << "mknod " << name << ": " << std::strerror(errno);
    }
  const std::map<fs::path, std::string> before = Inputs();
  const std::string n = (d / "null").string();
  for (const std::string& arguments :
       {Expand("extract {C} -o ") + n, Expand("extract {C} -o {r}/devices/p.json --csv ") + n,
        Expand("identify {C} --phasors {r}/phasors.json --fit acc1,acc2 --no-damping-laws --no-robust -o ") + n,
        Expand("predict {r}/result.json --x 0.3 -o ") + n,
        // PREFIX.csv is the device, PREFIX.json a file.
        Expand("backbone {r}/model.json --points 5 -H 3 -o {r}/devices/null"),
        Expand("backbone --measured {r}/phasors.json -o {r}/devices/null")}) {
    SCOPED_TRACE(arguments);
    const ProgramRun run = Beamid(arguments, 120);
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_TRUE(IsCharacterDevice(d / "null"));
    EXPECT_TRUE(IsCharacterDevice(d / "null.csv"));
  }
  EXPECT_TRUE(Inputs() == before) << "an input changed";
  // A device is no folder to simulate into.
  const ProgramRun simulate = Beamid(Expand("simulate {r}/scenario.json -o ") + n, 20);
  EXPECT_EQ(simulate.exit_code, 2) << simulate.output;
  EXPECT_TRUE(IsCharacterDevice(d / "null"));
}

}  // namespace
