// phasors.json of `beamid extract` (signal::PhasorSetFromJson), read by
// identify --phasors and diagnose --phasors.
#include "signal/phasor_set_io.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return beamid::fuzz::Accept(
      [&] { beamid::signal::PhasorSetFromJson(beamid::fuzz::AsText(data, size), "fuzz/phasors.json"); });
}
