// The kinds of failure beamid tells apart, each with its own exit code
// (mapped once, in solver/cli/main.cc):
//   InputError        something the user can fix in a file or an option:
//                     the message names the file, channel or option and
//                     the fix (exit 2);
//   NumericalError    a computation on valid input did not converge or
//                     has no solution there (exit 3);
//   EnvironmentError  the machine refused: a missing program, a full disk,
//                     a failed fork, too little memory (exit 4).
// Anything else that escapes is a bug in beamid (exit 1). Expected numerical
// outcomes (a start that did not converge, a fit that misses the data) are
// not errors: they travel in result structs.
// The lowest library (hb) holds them, so that every folder throws the same
// types; std::invalid_argument, which the readers have thrown for bad input
// since the first version, counts as an input error too.
#pragma once

#include <stdexcept>
#include <string>

namespace beamid {

class InputError : public std::invalid_argument {
 public:
  explicit InputError(const std::string& message) : std::invalid_argument(message) {}
  // "<file>: channel '<channel>': <problem>. Fix: <fix>" (channel and fix
  // left out when empty); file() and channel() let a caller act on them.
  InputError(std::string file, std::string channel, const std::string& problem, const std::string& fix);

  const std::string& file() const { return file_; }
  const std::string& channel() const { return channel_; }

 private:
  std::string file_;
  std::string channel_;
};

class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Not a failure of the computation: the model was fitted and its result
// written, but it misses the data by more than their noise
// (solver/estimation/fit_verdict.h). Its own exit code lets a script tell
// "fitted, go on" from "fitted, but diagnose first".
class ModelMissesData : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class EnvironmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr int kExitInternalError = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitNoConvergence = 3;
inline constexpr int kExitEnvironment = 4;
inline constexpr int kExitModelMissesData = 5;

}  // namespace beamid
