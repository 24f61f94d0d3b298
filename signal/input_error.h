// signal/'s readers throw beamid::InputError (hb/errors.h) with the file and
// channel at fault; the name is kept in this namespace for their code.
#pragma once

#include "hb/errors.h"

namespace beamid::signal {

using InputError = beamid::InputError;

}  // namespace beamid::signal
