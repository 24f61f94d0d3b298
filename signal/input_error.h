// The one exception signal/ throws for anything a test engineer can fix in a
// campaign (a missing file, an unknown unit, a NaN, a clipped channel...).
// It is a beamid::InputError (hb/errors.h), so the beamid program maps it to
// exit code 2.
// The message always reads
//     <file>: channel '<channel>': <problem>. Fix: <what to do>
// (the channel part is left out when the problem concerns no single channel),
// and file() / channel() give the parts to programs and tests.
#pragma once

#include <string>

#include "hb/errors.h"

namespace beamid::signal {

class InputError : public beamid::InputError {
 public:
  InputError(std::string file, std::string channel, const std::string& problem, const std::string& fix);

  const std::string& file() const { return file_; }
  const std::string& channel() const { return channel_; }

 private:
  std::string file_;
  std::string channel_;
};

}  // namespace beamid::signal
