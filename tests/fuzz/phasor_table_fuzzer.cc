// A first-harmonic phasor table (signal::ParsePhasorTable).
#include "signal/phasor_table.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return beamid::fuzz::Accept(
      [&] { beamid::signal::ParsePhasorTable(beamid::fuzz::AsText(data, size), "fuzz/level.csv", "level"); });
}
