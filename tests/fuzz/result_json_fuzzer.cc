// result.json of `beamid identify` (solver::ResultFileFromJson), read by
// predict, backbone --result, diagnose --result and report.
#include <string>

#include "solver/estimation/result_io.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return beamid::fuzz::Accept(
      [&] { beamid::solver::ResultFileFromJson(std::string(beamid::fuzz::AsText(data, size)), "fuzz/result.json"); });
}
