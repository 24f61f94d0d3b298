// Writes the seed corpus of the fuzz targets whose inputs no example ships
// (a campaign, a CSV recording, universal files, .mat and HDF5 recordings, a
// phasor table) into
// DIR/<target>/: valid inputs, so that mutation starts from what readers
// accept. scripts/fuzz.sh adds the examples' model and scenario files.
// Usage: write_seeds DIR
#include <hdf5.h>
#include <matio.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_input.h"
#include "tests/signal/uff58_writer.h"

namespace {

void Write(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
}

std::string RecordingCsv() {
  std::string csv = "time_s,force,acc1,vel2\n";
  char line[160];
  for (int n = 0; n < 200; ++n) {
    const double t = n / 1000.0, phase = 2 * std::numbers::pi * 50.0 * t;
    std::snprintf(line, sizeof line, "%.7f,%.6f,%.6f,%.6f\n", t, std::sin(phase), 2 * std::cos(phase),
                  300 * std::sin(2 * phase));
    csv += line;
  }
  return csv;
}

// The same samples as an acquisition system's export: ';' separator,
// decimal comma, a BOM, a comment line, units in the header, time in ms,
// an extra column no channel uses, CRLF line ends.
std::string AcquisitionExportCsv() {
  std::string csv = "\xEF\xBB\xBF# exported by a DAQ\r\n\"t [ms]\";\"force [N]\";acc1_g;\"vel2 (mm/s)\";temp [degC]\r\n";
  char line[160];
  for (int n = 0; n < 200; ++n) {
    const double t = n / 1000.0, phase = 2 * std::numbers::pi * 50.0 * t;
    std::snprintf(line, sizeof line, "%.4f;%.6f;%.6f;%.6f;21.5\r\n", 1e3 * t, std::sin(phase), 2 * std::cos(phase),
                  300 * std::sin(2 * phase));
    std::string row = line;
    for (char& c : row)
      if (c == '.') c = ',';
    csv += row;
  }
  return csv;
}

std::string UffFile(beamid::testing::UffEncoding encoding) {
  using beamid::testing::UffChannel;
  std::string text = beamid::testing::Uff151Header();
  int type = 13;
  for (const char* name : {"force", "acc1", "vel2"}) {
    UffChannel channel{.id_line1 = name, .ordinate_data_type = type, .dx = 1e-3};
    type = type == 13 ? 12 : 11;
    for (int n = 0; n < 64; ++n) channel.values.push_back(std::sin(2 * std::numbers::pi * 50.0 * n * 1e-3));
    text += beamid::testing::UffDataset58(channel, encoding);
  }
  return text;
}

// The fuzz campaign's channels, 200 samples at 1 kHz, as MATLAB saves them
// (column vectors, time_s) in a .mat file of version `version`.
void WriteMatSeed(const std::filesystem::path& file, mat_ft version) {
  std::filesystem::create_directories(file.parent_path());
  mat_t* mat = Mat_CreateVer(file.c_str(), nullptr, version);
  if (mat == nullptr) return;
  for (const char* name : {"time_s", "force", "acc1", "vel2"}) {
    std::vector<double> values;
    for (int n = 0; n < 200; ++n)
      values.push_back(name[0] == 't' ? n / 1000.0 : std::sin(2 * std::numbers::pi * 50.0 * n / 1000.0));
    std::size_t dims[] = {values.size(), 1};
    matvar_t* var = Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, values.data(), 0);
    Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE);
    Mat_VarFree(var);
  }
  char unit[] = "g";
  std::size_t unit_dims[] = {1, 1};
  matvar_t* var = Mat_VarCreate("acc1_units", MAT_C_CHAR, MAT_T_UTF8, 2, unit_dims, unit, 0);
  Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE);
  Mat_VarFree(var);
  Mat_Close(mat);
}

// The same channels as 1-D single-precision HDF5 datasets with "units"
// attributes, and the sample rate as an attribute of the root group.
void WriteHdf5Seed(const std::filesystem::path& file) {
  std::filesystem::create_directories(file.parent_path());
  const hid_t h5 = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (h5 < 0) return;
  const char* units[] = {"N", "g", "mm/s"};
  int c = 0;
  for (const char* name : {"force", "acc1", "vel2"}) {
    std::vector<float> values;
    for (int n = 0; n < 200; ++n) values.push_back(static_cast<float>(std::sin(2 * std::numbers::pi * 0.05 * n)));
    const hsize_t dims[] = {values.size()};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t dataset = H5Dcreate2(h5, name, H5T_IEEE_F32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(dataset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    const hid_t text = H5Tcopy(H5T_C_S1);
    H5Tset_size(text, std::string(units[c]).size());
    const hid_t scalar = H5Screate(H5S_SCALAR);
    const hid_t attribute = H5Acreate2(dataset, "units", text, scalar, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, text, units[c++]);
    H5Aclose(attribute);
    H5Sclose(scalar);
    H5Tclose(text);
    H5Dclose(dataset);
    H5Sclose(space);
  }
  const double rate_hz = 1000.0;
  const hid_t scalar = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(h5, "sample_rate_Hz", H5T_IEEE_F64LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attribute, H5T_NATIVE_DOUBLE, &rate_hz);
  H5Aclose(attribute);
  H5Sclose(scalar);
  H5Fclose(h5);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: write_seeds DIR\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  Write(dir / "campaign_json_fuzzer" / "campaign.json", beamid::fuzz::kCampaignJson);
  std::string voltage_campaign = beamid::fuzz::kCampaignJson;
  const std::string force = R"("quantity": "force", "unit": "N"})";
  voltage_campaign.replace(voltage_campaign.find(force), force.size(),
                           R"("quantity": "voltage", "unit": "mV", "sensitivity_N_per_V": 12.5}, "ignore_channels": ["vel2"])");
  Write(dir / "campaign_json_fuzzer" / "voltage_campaign.json", voltage_campaign);
  Write(dir / "batch_entry_fuzzer" / "batch.json",
        R"({"format": "beamid-batch-entry/1", "beamid_version": "0.1.0", "campaign": "/data/specimen_01",
            "campaign_name": "specimen 1", "status": "misfit", "exit_code": 5, "message": "", "seconds": 12.5,
            "result_file": "result.json", "report_file": "report.html", "report_problem": "",
            "errors_file": "errors.txt"})");
  Write(dir / "recording_csv_fuzzer" / "step.csv", RecordingCsv());
  Write(dir / "recording_csv_fuzzer" / "acquisition_export.csv", AcquisitionExportCsv());
  Write(dir / "uff58_fuzzer" / "ascii.uff", UffFile(beamid::testing::UffEncoding::kAsciiDouble));
  Write(dir / "uff58_fuzzer" / "binary.uff", UffFile(beamid::testing::UffEncoding::kBinaryLittleFloat));
  WriteMatSeed(dir / "array_file_fuzzer" / "v5.mat", MAT_FT_MAT5);
  WriteMatSeed(dir / "array_file_fuzzer" / "v73.mat", MAT_FT_MAT73);
  WriteHdf5Seed(dir / "array_file_fuzzer" / "step.h5");
  Write(dir / "phasor_table_fuzzer" / "comma.csv",
        "frequency_Hz,force_N,acceleration_m_s2,phase_deg\n53.50,1.000,2.31,32.4\n54.00,1.000,3.10,60.1\n");
  Write(dir / "phasor_table_fuzzer" / "semicolon.csv",
        "Frequency [Hz];Force [N];Velocity [mm/s];Phase [rad];Phase_std [rad]\n53,50;1,000;6,87;0,565;0,002\n");
  return 0;
}
