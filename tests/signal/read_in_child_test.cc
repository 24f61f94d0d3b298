// The child process that reads a .mat or HDF5 file first: how it ends is told
// apart (finished, died by a signal or an exit code, never answered), and a
// child that deadlocks on a lock another thread held at the fork (what a
// sanitizer's allocator or any library's lock can do to a forked child) is
// killed after its time and forked again, so the read neither hangs nor fails.
#include "signal/internal/read_in_child.h"

#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <thread>

#include <gtest/gtest.h>

namespace beamid::signal::internal {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

TEST(ReadInChild, AReadThatEndsWellIsFinishedAtTheFirstAttempt) {
  const ChildRead read = ReadInChild([] {}, 30.0, 2);
  EXPECT_EQ(read.outcome, ChildRead::Outcome::kFinished);
  EXPECT_EQ(read.attempts, 1);
}

TEST(ReadInChild, AnExceptionInTheChildIsCaughtThereAndTheReadFinishes) {
  const ChildRead read = ReadInChild([] { throw std::runtime_error("a refused file"); }, 30.0, 2);
  EXPECT_EQ(read.outcome, ChildRead::Outcome::kFinished);
}

TEST(ReadInChild, AChildKilledByASignalOrEndingWithoutAnsweringDiedAndIsNotForkedAgain) {
  const ChildRead aborted = ReadInChild([] { std::abort(); }, 30.0, 2);
  EXPECT_EQ(aborted.outcome, ChildRead::Outcome::kDied);
  EXPECT_EQ(aborted.attempts, 1);
  EXPECT_NE(aborted.how_it_ended.find("signal 6"), std::string::npos) << aborted.how_it_ended;

  const ChildRead exited = ReadInChild([] { _exit(3); }, 30.0, 2);
  EXPECT_EQ(exited.outcome, ChildRead::Outcome::kDied);
  EXPECT_EQ(exited.how_it_ended, "exit code 3");
}

TEST(ReadInChild, AChildThatNeverAnswersIsKilledAfterItsTimeOnEveryAttempt) {
  const Clock::time_point start = Clock::now();
  const ChildRead read = ReadInChild(
      [] {
        for (;;) pause();
      },
      0.3, 2);
  const double elapsed_s = SecondsSince(start);
  EXPECT_EQ(read.outcome, ChildRead::Outcome::kTimedOut);
  EXPECT_EQ(read.attempts, 2);
  EXPECT_GE(elapsed_s, 0.6);  // each attempt waited its whole time
  EXPECT_LT(elapsed_s, 20.0);  // and did not wait for the child to end by itself
}

// The deadlock after a fork, made on purpose: another thread holds a mutex
// at the first fork, and the child's copy of it stays locked for ever. By
// the second fork the thread has let it go.
TEST(ReadInChild, AChildDeadlockedOnALockHeldByAnotherThreadAtTheForkIsForkedAgainAndFinishes) {
  std::mutex shared;
  std::mutex state;
  std::condition_variable changed;
  bool holding = false;
  std::thread holder([&] {
    std::lock_guard held(shared);
    {
      std::lock_guard lock(state);
      holding = true;
    }
    changed.notify_all();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  });
  {
    std::unique_lock lock(state);
    changed.wait(lock, [&] { return holding; });
  }
  const double timeout_s = 1.0;
  const Clock::time_point start = Clock::now();
  const ChildRead read = ReadInChild([&] { std::lock_guard child_copy(shared); }, timeout_s, 2);
  const double elapsed_s = SecondsSince(start);
  holder.join();
  EXPECT_EQ(read.outcome, ChildRead::Outcome::kFinished);
  EXPECT_EQ(read.attempts, 2);
  EXPECT_GE(elapsed_s, timeout_s);  // the first child was waited for its whole time
}

}  // namespace
}  // namespace beamid::signal::internal
