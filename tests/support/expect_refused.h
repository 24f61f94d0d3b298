// The check the options tests share: the call must throw beamid::InputError
// whose message names `field` and says what the field must be.
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

}  // namespace beamid::testing
