// A model file (hb::ParseModelFile).
#include <string>

#include "hb/model_file.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return beamid::fuzz::Accept(
      [&] { beamid::hb::ParseModelFile(std::string(beamid::fuzz::AsText(data, size)), "fuzz/model.json"); });
}
