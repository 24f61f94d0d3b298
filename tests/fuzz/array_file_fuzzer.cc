// MATLAB .mat files (v5 and v7.3, through matio) and HDF5 files (through the
// HDF5 C library) as a step's recording of the fuzz campaign
// (signal::OpenArrayFile, signal::RecordingFromArrays). Both libraries read
// from a path: each input is written to a file of this process, once named
// .mat and once .h5. Messages must be valid UTF-8 whatever the file's
// variable names and unit texts hold.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "hb/errors.h"
#include "signal/array_file.h"
#include "signal/array_recording.h"
#include "signal/campaign.h"
#include "signal/internal/text.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const beamid::signal::Campaign campaign =
      beamid::signal::ParseCampaign(beamid::fuzz::kCampaignJson, "fuzz", "fuzz/campaign.json");
  static const std::filesystem::path stem =
      std::filesystem::temp_directory_path() / ("beamid_array_fuzzer_" + std::to_string(getpid()));
  for (const char* extension : {".mat", ".h5"}) {
    const std::filesystem::path path = stem.string() + extension;
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    beamid::fuzz::Accept([&] {
      try {
        const auto file = beamid::signal::OpenArrayFile(path, "fuzz/step" + std::string(extension));
        beamid::signal::RecordingFromArrays(*file, campaign, campaign.steps.front());
      } catch (const beamid::InputError& e) {
        if (!beamid::signal::internal::IsValidUtf8(e.what())) std::abort();
      }
    });
    std::filesystem::remove(path);
  }
  return 0;
}
