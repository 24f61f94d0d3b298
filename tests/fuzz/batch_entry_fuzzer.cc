// batch.json of `beamid batch` (workflow::BatchEntryFromJson), read back by
// `beamid batch --collect` from folders a cluster's job array or someone
// else wrote.
#include <string>

#include "solver/workflow/batch_entry.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return beamid::fuzz::Accept([&] {
    beamid::workflow::BatchEntryFromJson(std::string(beamid::fuzz::AsText(data, size)), "fuzz/batch.json");
  });
}
