// A simulation scenario (hb::ParseScenario).
#include <string>

#include "hb/scenario.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return beamid::fuzz::Accept(
      [&] { beamid::hb::ParseScenario(std::string(beamid::fuzz::AsText(data, size)), "fuzz/scenario.json"); });
}
