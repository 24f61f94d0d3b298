// Universal files, datasets 58 and 58b, ASCII and binary (signal::ParseUff58).
#include "signal/uff58.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return beamid::fuzz::Accept([&] { beamid::signal::ParseUff58(beamid::fuzz::AsText(data, size), "fuzz/step.uff"); });
}
