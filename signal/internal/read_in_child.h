// Runs a read in a forked child process and tells how the child ended, so
// that a file which crashes a C library (matio, HDF5) takes only the child
// down. The child says it finished by one byte through a pipe, written before
// it exits: its exit status may be a leak checker's, which the file has no
// part in.
// A child forked from a process with other threads may deadlock at once, on
// a lock another thread held at the fork (an allocator's, a sanitizer's stack
// store): such a child never answers. So the parent waits at most timeout_s;
// a child that has not answered by then is killed and the read forked again,
// up to max_attempts times. A second deadlock of the same file is as unlikely
// as the first, while a file that makes the library loop for ever times out
// on every attempt.
#pragma once

#include <functional>
#include <string>

namespace beamid::signal::internal {

struct ChildRead {
  enum class Outcome {
    kFinished,  // the child read everything and said so
    kDied,      // the child ended without saying so (a signal or an exit code)
    kTimedOut,  // every attempt's child was still running after timeout_s, and was killed
    kNoChild,   // no process to spare (fork or pipe failed): nothing was checked
  };
  Outcome outcome = Outcome::kNoChild;
  int attempts = 0;
  std::string how_it_ended;  // kDied: "signal 11, Segmentation fault" or "exit code 3"
};

// `read` runs in the child; whatever it throws is caught there. The fork holds the array libraries' lock
// (array_library_lock.h), so no other thread of this process is inside
// matio or HDF5 at that moment.
ChildRead ReadInChild(const std::function<void()>& read, double timeout_s, int max_attempts);

}  // namespace beamid::signal::internal
