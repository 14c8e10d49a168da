// Reading untrusted input files (common/input_file.h) and the output folder's lock
// (common/output_lock.h): devices, pipes, link loops, files without line breaks and oversized
// files are refused naming the file; a stop signal ends a long read; a second holder of a lock is
// refused naming the first.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "common/errors.h"
#include "common/input_file.h"
#include "common/output_lock.h"
#include "common/stop_signal.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  TempDir() : path(fs::temp_directory_path() / ("viqu_input_file_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  fs::path path;
};

void WriteText(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// The message of the InputError that `f` throws ("" when it throws none).
template <class F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InputFile, RefusesWhatIsNoRegularFile) {
  TempDir tmp;
  EXPECT_NE(ErrorOf([] { CheckInputFile("/dev/zero", 1 << 20, "trajectory file"); }).find("/dev/zero: not a regular file"),
            std::string::npos);
  const fs::path fifo = tmp.path / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // A pipe would block the open and never end the read: refused before either.
  EXPECT_NE(ErrorOf([&] { InputLines lines(fifo.string(), 1 << 20, "table file"); }).find("not a regular file"),
            std::string::npos);
  fs::create_symlink(tmp.path / "b", tmp.path / "a");
  fs::create_symlink(tmp.path / "a", tmp.path / "b");
  EXPECT_NE(ErrorOf([&] { CheckInputFile((tmp.path / "a").string(), 1 << 20, "mask image"); }).find("loop of links"),
            std::string::npos);
  fs::create_symlink(tmp.path / "nowhere", tmp.path / "dangling");
  EXPECT_NE(ErrorOf([&] { CheckInputFile((tmp.path / "dangling").string(), 1 << 20, "mask image"); }).find("dangling link"),
            std::string::npos);
  EXPECT_EQ(ErrorOf([&] { CheckInputFile((tmp.path / "none").string(), 1 << 20, "x"); }),
            (tmp.path / "none").string() + ": file not found");
  EXPECT_NE(ErrorOf([&] { CheckInputFile(tmp.path.string(), 1 << 20, "trajectory file"); }).find("is a directory"),
            std::string::npos);
}

TEST(InputFile, BoundsTheSizeAndTheLineLength) {
  TempDir tmp;
  const fs::path big = tmp.path / "big.txt";
  WriteText(big, std::string(2000, 'x'));
  EXPECT_NE(ErrorOf([&] { ReadInputFile(big.string(), 1000, "URDF file"); }).find("larger than 1000 bytes"), std::string::npos);
  EXPECT_EQ(ReadInputFile(big.string(), 2000, "URDF file").size(), 2000u);
  // A file without line breaks (zeros) is refused at the line bound, naming its first line.
  const fs::path zeros = tmp.path / "zeros";
  WriteText(zeros, std::string(kMaxInputLineBytes + 10, '\0'));
  const std::string why = ErrorOf([&] {
    InputLines lines(zeros.string(), uintmax_t{1} << 30, "trajectory file");
    std::string line;
    while (lines.Next(&line)) {
    }
  });
  EXPECT_NE(why.find(zeros.string() + ":1: line longer than"), std::string::npos) << why;
  // Lines are handed out whole across read chunks, the last one without its line break too.
  const fs::path text = tmp.path / "lines.txt";
  std::string expected;
  for (int i = 0; i < 20000; ++i) expected += "row " + std::to_string(i) + (i + 1 < 20000 ? "\n" : "");
  WriteText(text, expected);
  InputLines lines(text.string(), uintmax_t{1} << 30, "table file");
  std::string line, got;
  while (lines.Next(&line)) got += line + (lines.line() < 20000 ? "\n" : "");
  EXPECT_EQ(got, expected);
  EXPECT_EQ(lines.line(), 20000);
}

TEST(OutputLock, ASecondHolderIsRefusedNamingTheFirst) {
  TempDir tmp;
  const std::string dir = (tmp.path / "runs" / "x").string();
  {
    OutputLock first(dir, "viqu run a.yaml --out x");
    ASSERT_TRUE(first.held());
    EXPECT_EQ(first.path(), (tmp.path / "runs" / ".x.viqu-lock").string());
    // flock locks belong to the open file: a second open in this process is refused as another
    // process's would be.
    const std::string why = ErrorOf([&] { OutputLock second(dir + "/", "viqu run b.yaml"); });
    EXPECT_NE(why.find("output folder " + dir), std::string::npos) << why;
    EXPECT_NE(why.find("in use by viqu run a.yaml --out x (pid " + std::to_string(::getpid()) + ")"), std::string::npos)
        << why;
    OutputLock other((tmp.path / "runs" / "y").string(), "viqu run c.yaml");  // another folder: no conflict
    EXPECT_TRUE(other.held());
  }
  // Let go: the lock file is gone and the folder can be locked again.
  EXPECT_FALSE(fs::exists(tmp.path / "runs" / ".x.viqu-lock"));
  OutputLock again(dir, "viqu run d.yaml");
  EXPECT_TRUE(again.held());
}

TEST(OutputLock, ALockWhoseHolderDiedBlocksNothing) {
  TempDir tmp;
  const std::string dir = (tmp.path / "x").string();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    OutputLock held(dir, "viqu run killed.yaml");
    ::pause();  // killed below, lock held
    ::_exit(0);
  }
  // Wait for the child's lock to appear, then kill it (no destructor runs: the file stays).
  std::error_code ec;
  for (int i = 0; i < 500 && !(fs::exists(OutputLockPath(dir)) && fs::file_size(OutputLockPath(dir), ec) > 0); ++i) {
    ::usleep(10000);
  }
  EXPECT_NE(ErrorOf([&] { OutputLock blocked(dir, "viqu run b.yaml"); }).find("in use by viqu run killed.yaml"),
            std::string::npos);
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(fs::exists(OutputLockPath(dir)));  // left behind, unlocked
  OutputLock after(dir, "viqu run c.yaml");
  EXPECT_TRUE(after.held());
}

// Last in the file: the stop signal stays recorded for the rest of the process (CTest runs each
// test in a process of its own; a whole-binary run reaches this one last).
TEST(InputFile, AStopSignalEndsARead) {
  TempDir tmp;
  const fs::path text = tmp.path / "long.txt";
  WriteText(text, std::string(1 << 20, 'a') + "\n");
  InstallStopSignalHandlers();
  std::raise(SIGTERM);  // the handler records it (and resets itself: a second one would kill)
  ASSERT_EQ(StopSignal(), SIGTERM);
  try {
    ReadInputFile(text.string(), uintmax_t{1} << 30, "trajectory file");
    FAIL() << "no Stopped";
  } catch (const Stopped& e) {
    EXPECT_EQ(e.signal(), SIGTERM);
    EXPECT_NE(std::string(e.what()).find(text.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace viqu
