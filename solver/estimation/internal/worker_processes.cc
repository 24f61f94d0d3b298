#include "solver/estimation/internal/worker_processes.h"

#include "hb/errors.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace beamid::solver::internal {
namespace {

bool WriteAll(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool ReadAll(int fd, void* data, std::size_t size) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::read(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// Message: job index, status (0 ok, 1 error), payload length, payload
// (the result's bytes, or the error text's).
void SendResult(int fd, std::int64_t index, const std::string& result, const std::string& error) {
  const std::int64_t status = error.empty() ? 0 : 1;
  const std::string& payload = error.empty() ? result : error;
  const std::int64_t length = static_cast<std::int64_t>(payload.size());
  WriteAll(fd, &index, sizeof index);
  WriteAll(fd, &status, sizeof status);
  WriteAll(fd, &length, sizeof length);
  WriteAll(fd, payload.data(), payload.size());
}

}  // namespace

void RunTextJobsInWorkers(int num_jobs, int num_workers, const std::function<std::string(int)>& job,
                          const std::function<void(int, const std::string&, const std::string&, int)>& collect) {
  if (num_workers <= 1 || num_jobs <= 1) {
    for (int i = 0; i < num_jobs; ++i) {
      try {
        collect(i, job(i), "", i + 1);
      } catch (const std::exception& e) {
        collect(i, {}, e.what(), i + 1);
      }
    }
    return;
  }
  struct Worker {
    pid_t pid = -1;
    int fd = -1;
    std::vector<int> jobs;
  };
  std::vector<Worker> workers(num_workers);
  for (int i = 0; i < num_jobs; ++i) workers[i % num_workers].jobs.push_back(i);
  // When a fork fails or collect throws (a caller that abandons the run:
  // Ctrl-C in the Python module), no worker may be left blocked on a pipe
  // nobody reads, or unreaped: each is killed and waited for.
  struct StopWorkers {
    std::vector<Worker>& workers;
    bool finished = false;
    ~StopWorkers() {
      if (finished) return;
      for (Worker& w : workers) {
        if (w.fd >= 0) ::close(w.fd);
        if (w.pid <= 0) continue;
        ::kill(w.pid, SIGKILL);
        ::waitpid(w.pid, nullptr, 0);
      }
    }
  } stop{workers};
  // A child inherits the parent's unflushed stdio buffers, and whatever it
  // prints flushes them again: the parent's pending output appeared once per
  // worker.
  std::fflush(nullptr);
  for (Worker& w : workers) {
    int fds[2];
    if (::pipe(fds) != 0) throw EnvironmentError(std::string("cannot create a pipe: ") + std::strerror(errno));
    const pid_t pid = ::fork();
    if (pid < 0) throw EnvironmentError(std::string("cannot start a worker process: ") + std::strerror(errno));
    if (pid == 0) {
      ::close(fds[0]);
      for (int i : w.jobs) {
        try {
          SendResult(fds[1], i, job(i), "");
        } catch (const std::exception& e) {
          SendResult(fds[1], i, {}, e.what()[0] ? e.what() : "unknown error");
        } catch (...) {
          SendResult(fds[1], i, {}, "unknown error");
        }
      }
      ::close(fds[1]);
      ::_exit(0);  // no destructors, no atexit handlers of the parent's state
    }
    ::close(fds[1]);
    w.pid = pid;
    w.fd = fds[0];
  }
  int done = 0;
  std::vector<bool> received(num_jobs, false);
  std::vector<pollfd> polls;
  for (const Worker& w : workers) polls.push_back({w.fd, POLLIN, 0});
  int open = num_workers;
  while (open > 0) {
    if (::poll(polls.data(), polls.size(), -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (pollfd& p : polls) {
      if (p.fd < 0 || !(p.revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const auto close_pipe = [&] {
        ::close(p.fd);
        workers[static_cast<std::size_t>(&p - polls.data())].fd = -1;
        p.fd = -1;
        --open;
      };
      std::int64_t index = 0, status = 0, length = 0;
      if (!ReadAll(p.fd, &index, sizeof index) || !ReadAll(p.fd, &status, sizeof status) ||
          !ReadAll(p.fd, &length, sizeof length) || index < 0 || index >= num_jobs || length < 0) {
        close_pipe();
        continue;
      }
      std::vector<char> payload(static_cast<std::size_t>(length));
      if (!ReadAll(p.fd, payload.data(), payload.size())) {
        close_pipe();
        continue;
      }
      received[index] = true;
      ++done;
      if (status == 0) collect(static_cast<int>(index), std::string(payload.begin(), payload.end()), "", done);
      else collect(static_cast<int>(index), {}, std::string(payload.begin(), payload.end()), done);
    }
  }
  for (const Worker& w : workers) {
    int status = 0;
    ::waitpid(w.pid, &status, 0);
  }
  stop.finished = true;
  for (int i = 0; i < num_jobs; ++i)
    if (!received[i]) collect(i, {}, "the worker process died", ++done);
}

}  // namespace beamid::solver::internal
