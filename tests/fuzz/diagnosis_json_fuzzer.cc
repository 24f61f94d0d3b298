// diagnosis.json of `beamid diagnose` (solver::DiagnosisFileFromJson), read
// by report, with the result it may embed.
#include <string>

#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/result_io.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return beamid::fuzz::Accept([&] {
    const auto file =
        beamid::solver::DiagnosisFileFromJson(std::string(beamid::fuzz::AsText(data, size)), "fuzz/diagnosis.json");
    // As report does: the embedded result is read as a result.json.
    if (!file.embedded_result_json.empty())
      beamid::solver::ResultFileFromJson(file.embedded_result_json, "fuzz/diagnosis.json (its embedded result)");
  });
}
