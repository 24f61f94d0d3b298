#include "solver/report/external_program.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include <fmt/core.h>

#include "hb/errors.h"

extern char** environ;

namespace beamid::solver {
namespace {

// A file descriptor closed when it goes out of scope.
class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

[[noreturn]] void Fail(const std::string& what) { throw EnvironmentError(what + ": " + std::strerror(errno)); }

// Above 2, so that dup2 onto 0, 1 and 2 in the child never overwrites one of
// them when the parent runs with a standard stream closed; close-on-exec, so
// that a program started by another thread meanwhile does not inherit it.
int Above2(int fd, const std::string& what) {
  if (fd < 0) Fail(what);
  if (fd > 2) return fd;
  const int moved = ::fcntl(fd, F_DUPFD_CLOEXEC, 3);
  const int saved = errno;
  ::close(fd);
  errno = saved;
  if (moved < 0) Fail(what);
  return moved;
}

int OpenNull(int flags) { return Above2(::open("/dev/null", flags | O_CLOEXEC), "cannot open /dev/null"); }

int OpenOutput(const std::optional<std::filesystem::path>& file) {
  if (!file) return OpenNull(O_WRONLY);
  return Above2(::open(file->c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644), "cannot write " + file->string());
}

// The text in an anonymous in-memory file, read from its start: unlike a
// pipe, it never blocks beamid when the program reads its input late or not
// at all.
int StdinFile(const std::optional<std::string>& text) {
  if (!text) return OpenNull(O_RDONLY);
  Fd fd(Above2(::memfd_create("beamid_stdin", MFD_CLOEXEC), "cannot create the program's input"));
  std::size_t written = 0;
  while (written < text->size()) {
    const ssize_t n = ::write(fd.get(), text->data() + written, text->size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) Fail("cannot write the program's input");
    written += static_cast<std::size_t>(n);
  }
  if (::lseek(fd.get(), 0, SEEK_SET) != 0) Fail("cannot rewind the program's input");
  return fd.release();
}

int DecodeStatus(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 255;
}

// Waits for the child, through EINTR, so that it never stays a zombie.
int Wait(pid_t pid, int options, bool& done) {
  int status = 0;
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, options);
    if (r == pid) {
      done = true;
      return status;
    }
    if (r == 0) {
      done = false;
      return 0;
    }
    if (errno != EINTR) Fail("cannot wait for a started program");
  }
}

// posix_spawn's settings: the child's own signal mask empty and every signal
// at its default (beamid's ignored SIGPIPE must not reach gnuplot).
class SpawnAttributes {
 public:
  SpawnAttributes() {
    if (int e = ::posix_spawnattr_init(&attr_)) errno = e, Fail("cannot prepare a program's start");
    sigset_t none, all;
    sigemptyset(&none);
    sigfillset(&all);
    ::posix_spawnattr_setsigmask(&attr_, &none);
    ::posix_spawnattr_setsigdefault(&attr_, &all);
    ::posix_spawnattr_setflags(&attr_, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  }
  ~SpawnAttributes() { ::posix_spawnattr_destroy(&attr_); }
  SpawnAttributes(const SpawnAttributes&) = delete;
  SpawnAttributes& operator=(const SpawnAttributes&) = delete;
  const posix_spawnattr_t* get() const { return &attr_; }

 private:
  posix_spawnattr_t attr_;
};

// The child's descriptors: 0, 1, 2 from the given ones, all others closed.
class SpawnFileActions {
 public:
  SpawnFileActions(int in, int out, int err) {
    if (int e = ::posix_spawn_file_actions_init(&actions_)) errno = e, Fail("cannot prepare a program's start");
    int e = ::posix_spawn_file_actions_adddup2(&actions_, in, 0);
    if (!e) e = ::posix_spawn_file_actions_adddup2(&actions_, out, 1);
    if (!e) e = ::posix_spawn_file_actions_adddup2(&actions_, err, 2);
    if (!e) e = ::posix_spawn_file_actions_addclosefrom_np(&actions_, 3);
    if (e) {
      ::posix_spawn_file_actions_destroy(&actions_);
      errno = e;
      Fail("cannot prepare a program's start");
    }
  }
  ~SpawnFileActions() { ::posix_spawn_file_actions_destroy(&actions_); }
  SpawnFileActions(const SpawnFileActions&) = delete;
  SpawnFileActions& operator=(const SpawnFileActions&) = delete;
  const posix_spawn_file_actions_t* get() const { return &actions_; }

 private:
  posix_spawn_file_actions_t actions_;
};

}  // namespace

int RunExternalProgram(const ExternalProgram& run) {
  const Fd in(StdinFile(run.stdin_text));
  const Fd out(OpenOutput(run.stdout_file));
  const Fd err(OpenOutput(run.stderr_file));
  const SpawnFileActions actions(in.get(), out.get(), err.get());
  const SpawnAttributes attributes;

  std::vector<std::string> strings{run.program};
  strings.insert(strings.end(), run.arguments.begin(), run.arguments.end());
  std::vector<char*> argv;
  for (auto& s : strings) argv.push_back(s.data());
  argv.push_back(nullptr);

  pid_t pid = 0;
  // posix_spawnp reports a program it cannot execute as its own error, so a
  // missing program never runs as a half-started child.
  const int e = ::posix_spawnp(&pid, run.program.c_str(), actions.get(), attributes.get(), argv.data(), environ);
  if (e == ENOENT || e == ENOTDIR)
    throw EnvironmentError(fmt::format("{} is not installed (or not on PATH): install the Debian package {} "
                                       "(scripts/install-deps.sh)",
                                       run.program, run.debian_package));
  if (e != 0) {
    errno = e;
    Fail(fmt::format("cannot start {} (Debian package {})", run.program, run.debian_package));
  }

  bool done = false;
  int status = 0;
  if (run.timeout_s <= 0.0) {
    status = Wait(pid, 0, done);
  } else {
    // Polled, with a growing pause: a wait on SIGCHLD would take the signal
    // from the rest of the program.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(run.timeout_s);
    auto pause = std::chrono::milliseconds(1);
    while (!done) {
      status = Wait(pid, WNOHANG, done);
      if (done) break;
      if (std::chrono::steady_clock::now() > deadline) {
        ::kill(pid, SIGKILL);
        Wait(pid, 0, done);
        throw EnvironmentError(
            fmt::format("{} did not finish within {:g} s and was stopped", run.program, run.timeout_s));
      }
      std::this_thread::sleep_for(pause);
      pause = std::min(2 * pause, std::chrono::milliseconds(50));
    }
  }
  return DecodeStatus(status);
}

}  // namespace beamid::solver
