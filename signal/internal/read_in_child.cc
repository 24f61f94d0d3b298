#include "signal/internal/read_in_child.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstring>
#include <mutex>

#include "signal/internal/array_library_lock.h"

namespace beamid::signal::internal {
namespace {

using Clock = std::chrono::steady_clock;

std::string HowItEnded(int status) {
  if (WIFSIGNALED(status))
    return "signal " + std::to_string(WTERMSIG(status)) + ", " + std::string(strsignal(WTERMSIG(status)));
  return "exit code " + std::to_string(WEXITSTATUS(status));
}

void Reap(pid_t pid, int& status) {
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
}

// Waits until the pipe has the child's byte or is closed (the child ended),
// or the deadline passes: true when the child answered or ended in time.
bool WaitForAnswer(int read_end, Clock::time_point deadline, char& byte, ssize_t& got) {
  for (;;) {
    const auto left_ms = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left_ms <= 0) return false;
    pollfd fd{.fd = read_end, .events = POLLIN, .revents = 0};
    const int ready = poll(&fd, 1, static_cast<int>(std::min<long long>(left_ms, INT_MAX)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;  // the deadline is checked above
    while ((got = read(read_end, &byte, 1)) < 0 && errno == EINTR) {
    }
    return true;
  }
}

}  // namespace

ChildRead ReadInChild(const std::function<void()>& read_all, double timeout_s, int max_attempts) {
  ChildRead result;
  for (int attempt = 0; attempt < max_attempts; ++attempt) {
    int done[2];
    pid_t pid;
    {
      std::unique_lock lock(ArrayLibraryLock());  // no thread of ours inside matio or HDF5 at the fork
      // O_CLOEXEC: a program another thread starts does not keep the pipe open.
      if (pipe2(done, O_CLOEXEC) != 0) return result;
      pid = fork();
      if (pid < 0) {
        close(done[0]);
        close(done[1]);
        return result;
      }
      if (pid == 0) {
        close(done[0]);
        lock.unlock();  // the child's copy of the lock, held by its one thread
        try {
          read_all();
        } catch (...) {
        }
        const char byte = 1;
        [[maybe_unused]] const ssize_t written = write(done[1], &byte, 1);
        _exit(0);
      }
      // Closed before another thread may fork: a later child must not hold this child's write end, or the
      // pipe would stay open after this child ended.
      close(done[1]);
    }
    result.attempts = attempt + 1;
    char byte = 0;
    ssize_t got = 0;
    const Clock::time_point deadline =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
    const bool answered = WaitForAnswer(done[0], deadline, byte, got);
    close(done[0]);
    int status = 0;
    if (!answered) {
      kill(pid, SIGKILL);
      Reap(pid, status);
      result.outcome = ChildRead::Outcome::kTimedOut;
      continue;
    }
    Reap(pid, status);
    if (got == 1) {
      result.outcome = ChildRead::Outcome::kFinished;
    } else {
      result.outcome = ChildRead::Outcome::kDied;
      result.how_it_ended = HowItEnded(status);
    }
    return result;
  }
  return result;
}

}  // namespace beamid::signal::internal
