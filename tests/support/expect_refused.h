// The checks the tests of bad input share: ExpectRefused — the call must
// throw beamid::InputError whose message names `field` and says what the
// field must be; InputErrorOf — the message of the InputError the call
// throws (a test failure when it throws none).
#pragma once

#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "hb/errors.h"

namespace beamid::testing {

inline void ExpectRefused(const std::function<void()>& call, const std::string& field) {
  try {
    call();
    ADD_FAILURE() << "accepted an invalid " << field;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("must be"), std::string::npos) << e.what();
  }
}

inline std::string InputErrorOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

}  // namespace beamid::testing
