// MATLAB .mat (v5, v7.3) and HDF5 files as step recordings and as
// first-harmonic tables (beamid backbone --measured LEVEL.mat): the test writes
// each file itself (matio's Mat_CreateVer, the HDF5 C library) from the same
// numbers as a CSV campaign, and the phasors of the two campaigns agree
// (columns and rows, double and single precision, a time vector or a sample
// rate); each malformed file gives an InputError naming the file, the
// channel (or the time variable) and what to fix.
#include <hdf5.h>
#include <matio.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>

#include <gtest/gtest.h>

#include "signal/array_file.h"
#include "signal/campaign_extractor.h"
#include "signal/input_error.h"
#include "signal/phasor_table.h"
#include "signal/recording.h"
#include "tests/signal/synthetic_signal.h"
#include "tests/support/temp_path.h"

namespace beamid::signal {
namespace {

namespace fs = std::filesystem;

constexpr double kRateHz = 5000.0;
constexpr int kSamples = 5000;
constexpr int kSteps = 2;
constexpr double kGravity = 9.80665;
// The .mat and HDF5 campaigns must give the CSV campaign's phasors to this
// relative precision (of the channel's first harmonic); they are read as the
// same doubles, so they agree exactly.
constexpr double kPhasorTolerance = 1e-12;
const char* const kChannels[] = {"force", "acc1", "vel2"};
const char* const kUnits[] = {"N", "g", "mm/s"};

std::string CampaignJson(const std::string& extension, bool with_sample_rate) {
  std::string steps;
  for (int s = 0; s < kSteps; ++s)
    steps += std::string(s ? "," : "") + R"({"file": "s)" + std::to_string(s) + extension +
             R"(", "frequency_Hz": )" + std::to_string(40 + s) + R"(, "level": "low"})";
  return R"({
  "format": "stepped-sine-campaign/1", "name": "array test",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": {"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "quantity": "acceleration", "unit": "g"},
              {"channel": "vel2", "position_m": 0.3, "quantity": "velocity", "unit": "mm/s"}],
  "steps": [)" + steps + "]" + (with_sample_rate ? R"(, "sample_rate_Hz": 5000)" : "") + "}";
}

// A step's channels in the campaign's units (N, g, mm/s), and its times.
struct StepData {
  std::vector<double> time_s;
  std::vector<std::vector<double>> columns;  // force, acc1, vel2
};

std::vector<StepData> MakeSteps(bool single_precision) {
  std::mt19937 rng(17);
  std::normal_distribution<double> noise;
  std::vector<StepData> steps(kSteps);
  const double to_file[] = {1.0, 1.0 / kGravity, 1e3};
  for (int s = 0; s < kSteps; ++s) {
    for (int n = 0; n < kSamples; ++n) steps[s].time_s.push_back(n / kRateHz);
    for (int c = 0; c < 3; ++c) {
      testing::Tone tone = testing::RandomTone(rng, 5, 40.0 + s + 0.011, 1.0 + c);
      tone.sample_rate_hz = kRateHz;
      const Eigen::VectorXd si = testing::Synthesize(tone, kSamples, 0.0);
      std::vector<double> column(kSamples);
      for (int n = 0; n < kSamples; ++n) {
        column[n] = (si[n] + 1e-3 * (1.0 + c) * noise(rng)) * to_file[c];
        if (single_precision) column[n] = static_cast<float>(column[n]);
      }
      steps[s].columns.push_back(column);
    }
  }
  return steps;
}

void WriteFile(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string CsvOf(const StepData& step, bool with_time) {
  std::string csv = with_time ? "time_s,force,acc1,vel2\n" : "force,acc1,vel2\n";
  char line[200];
  for (int n = 0; n < kSamples; ++n) {
    if (with_time) {
      std::snprintf(line, sizeof line, "%.17g,", step.time_s[n]);
      csv += line;
    }
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g\n", step.columns[0][n], step.columns[1][n],
                  step.columns[2][n]);
    csv += line;
  }
  return csv;
}

// ---- Writers: what MATLAB, scipy or an acquisition system would save ----

enum class Container { kMatV5, kMatV73, kHdf5 };
enum class Precision { kDouble, kSingle };
enum class Orientation { kColumn, kRow, kOneDimensional };
enum class Timing { kTimeVector, kSampleRate };

// One array to write: real values (double or single), or something else for
// the bad-input cases.
struct Array {
  std::string name;
  std::vector<double> values;
  std::vector<std::size_t> dims;  // MATLAB's order: rows, columns
  Precision precision = Precision::kDouble;
  std::string unit;               // HDF5: "units" attribute; .mat: <name>_units
  enum class Special { kNone, kComplex, kInt16, kChar } special = Special::kNone;
};

Array Vector(const std::string& name, const std::vector<double>& values, Orientation orientation,
             Precision precision = Precision::kDouble) {
  Array array{.name = name, .values = values, .precision = precision};
  const std::size_t n = values.size();
  array.dims = orientation == Orientation::kColumn ? std::vector<std::size_t>{n, 1}
               : orientation == Orientation::kRow  ? std::vector<std::size_t>{1, n}
                                                    : std::vector<std::size_t>{n};
  return array;
}

void WriteMatVariable(mat_t* mat, const std::string& name, matio_classes class_type, matio_types data_type,
                      std::vector<std::size_t> dims, void* data, int options = 0) {
  matvar_t* var = Mat_VarCreate(name.c_str(), class_type, data_type, static_cast<int>(dims.size()), dims.data(),
                                data, options);
  ASSERT_NE(var, nullptr) << name;
  ASSERT_EQ(Mat_VarWrite(mat, var, MAT_COMPRESSION_ZLIB), 0) << name;
  Mat_VarFree(var);
}

void WriteMat(const fs::path& path, Container container, const std::vector<Array>& arrays) {
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, container == Container::kMatV5 ? MAT_FT_MAT5 : MAT_FT_MAT73);
  ASSERT_NE(mat, nullptr) << path;
  for (const Array& array : arrays) {
    std::vector<std::size_t> dims = array.dims;
    if (dims.size() == 1) dims.push_back(1);  // MATLAB has no 1-D arrays
    if (array.special == Array::Special::kComplex) {
      std::vector<double> re = array.values, im(array.values.size(), 0.5);
      mat_complex_split_t split{re.data(), im.data()};
      WriteMatVariable(mat, array.name, MAT_C_DOUBLE, MAT_T_DOUBLE, dims, &split, MAT_F_COMPLEX);
    } else if (array.special == Array::Special::kInt16) {
      std::vector<std::int16_t> counts(array.values.begin(), array.values.end());
      WriteMatVariable(mat, array.name, MAT_C_INT16, MAT_T_INT16, dims, counts.data());
    } else if (array.special == Array::Special::kChar) {
      std::string text = "not a number";
      WriteMatVariable(mat, array.name, MAT_C_CHAR, MAT_T_UTF8, {1, text.size()}, text.data());
    } else if (array.precision == Precision::kSingle) {
      std::vector<float> values(array.values.begin(), array.values.end());
      WriteMatVariable(mat, array.name, MAT_C_SINGLE, MAT_T_SINGLE, dims, values.data());
    } else {
      std::vector<double> values = array.values;
      WriteMatVariable(mat, array.name, MAT_C_DOUBLE, MAT_T_DOUBLE, dims, values.data());
    }
    if (!array.unit.empty()) {
      std::string unit = array.unit;
      WriteMatVariable(mat, array.name + "_units", MAT_C_CHAR, MAT_T_UTF8, {1, unit.size()}, unit.data());
    }
  }
  Mat_Close(mat);
}

void WriteHdf5StringAttribute(hid_t object, const char* name, const std::string& value) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, value.size());
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attribute, type, value.data());
  H5Aclose(attribute);
  H5Sclose(space);
  H5Tclose(type);
}

// HDF5 keeps C's row-major order: a MATLAB n×1 column is written as dims {n, 1}.
void WriteHdf5(const fs::path& path, const std::vector<Array>& arrays, std::optional<double> root_rate_hz = {}) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0) << path;
  for (const Array& array : arrays) {
    std::vector<hsize_t> dims(array.dims.begin(), array.dims.end());
    const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
    hid_t dataset = -1;
    if (array.special == Array::Special::kComplex) {
      // h5py's complex: a compound of two doubles named r and i.
      const hid_t type = H5Tcreate(H5T_COMPOUND, 16);
      H5Tinsert(type, "r", 0, H5T_NATIVE_DOUBLE);
      H5Tinsert(type, "i", 8, H5T_NATIVE_DOUBLE);
      std::vector<std::complex<double>> values(array.values.begin(), array.values.end());
      dataset = H5Dcreate2(file, array.name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Dwrite(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
      H5Tclose(type);
    } else if (array.special == Array::Special::kInt16) {
      std::vector<std::int16_t> counts(array.values.begin(), array.values.end());
      dataset = H5Dcreate2(file, array.name.c_str(), H5T_STD_I16LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Dwrite(dataset, H5T_NATIVE_INT16, H5S_ALL, H5S_ALL, H5P_DEFAULT, counts.data());
    } else if (array.precision == Precision::kSingle) {
      std::vector<float> values(array.values.begin(), array.values.end());
      dataset = H5Dcreate2(file, array.name.c_str(), H5T_IEEE_F32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Dwrite(dataset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    } else {
      dataset = H5Dcreate2(file, array.name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, array.values.data());
    }
    ASSERT_GE(dataset, 0) << array.name;
    if (!array.unit.empty()) WriteHdf5StringAttribute(dataset, "units", array.unit);
    H5Dclose(dataset);
    H5Sclose(space);
  }
  if (root_rate_hz) {
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attribute = H5Acreate2(file, "sample_rate_Hz", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, H5T_NATIVE_DOUBLE, &*root_rate_hz);
    H5Aclose(attribute);
    H5Sclose(space);
  }
  H5Fclose(file);
}

void WriteArrays(const fs::path& path, Container container, const std::vector<Array>& arrays,
                 std::optional<double> hdf5_root_rate_hz = {}) {
  if (container == Container::kHdf5)
    WriteHdf5(path, arrays, hdf5_root_rate_hz);
  else
    WriteMat(path, container, arrays);
}

std::string Extension(Container container) { return container == Container::kHdf5 ? ".h5" : ".mat"; }

// ---- The same numbers as CSV and as .mat / HDF5 give the same phasors ----

struct Layout {
  const char* name;
  Container container;
  Precision precision;
  Orientation orientation;
  Timing timing;
  bool units;  // the file states each channel's unit (and the time's)
};

// GoogleTest prints a parameter by its name, not its bytes (its padding is uninitialised).
void PrintTo(const Layout& layout, std::ostream* os) { *os << layout.name; }

class ArrayRecordingTest : public ::testing::TestWithParam<Layout> {
 protected:
  void SetUp() override {
    folder_ = beamid::testing::UniqueTempPath("beamid_array");
    fs::remove_all(folder_);
    fs::create_directories(folder_ / "csv");
    fs::create_directories(folder_ / "array");
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path folder_;
};

TEST_P(ArrayRecordingTest, GivesThePhasorsOfTheSameSamplesAsCsv) {
  const Layout layout = GetParam();
  const bool with_time = layout.timing == Timing::kTimeVector;
  const std::vector<StepData> steps = MakeSteps(layout.precision == Precision::kSingle);
  // Without a time vector the CSV twin has no time column and campaign.json
  // gives the rate; the array file gives its own (sample_rate_Hz).
  WriteFile(folder_ / "csv/campaign.json", CampaignJson(".csv", !with_time));
  WriteFile(folder_ / "array/campaign.json", CampaignJson(Extension(layout.container), false));
  for (int s = 0; s < kSteps; ++s) {
    WriteFile(folder_ / ("csv/s" + std::to_string(s) + ".csv"), CsvOf(steps[s], with_time));
    std::vector<Array> arrays;
    // Channels in another order than campaign.json.
    for (int c : {2, 0, 1}) {
      arrays.push_back(Vector(kChannels[c], steps[s].columns[c], layout.orientation, layout.precision));
      if (layout.units) arrays.back().unit = kUnits[c];
    }
    if (with_time) {
      arrays.push_back(Vector(layout.units ? "time" : "time_s", steps[s].time_s, layout.orientation));
      if (layout.units) arrays.back().unit = "s";
    }
    std::optional<double> root_rate_hz;
    if (!with_time && layout.container == Container::kHdf5)
      root_rate_hz = kRateHz;  // an attribute of the root group
    else if (!with_time)
      arrays.push_back(Vector("sample_rate_Hz", {kRateHz}, Orientation::kColumn));
    WriteArrays(folder_ / ("array/s" + std::to_string(s) + Extension(layout.container)), layout.container, arrays,
                root_rate_hz);
  }
  const Campaign array_campaign = ReadCampaign(folder_ / "array");
  const Recording recording = ReadRecording(array_campaign, array_campaign.steps[0]);
  EXPECT_EQ(recording.sample_rate_hz, kRateHz);
  ASSERT_EQ(recording.NumSamples(), kSamples);
  EXPECT_EQ(recording.channels, (std::vector<std::string>{"force", "acc1", "vel2"}));
  EXPECT_EQ(recording.samples(7, 1), steps[0].columns[1][7] * kGravity);  // g → m/s²
  EXPECT_EQ(recording.samples(7, 2), steps[0].columns[2][7] * 1e-3);      // mm/s → m/s
  EXPECT_TRUE(recording.ignored_columns.empty());

  const PhasorSet from_csv = ExtractCampaign(ReadCampaign(folder_ / "csv"));
  const PhasorSet from_array = ExtractCampaign(array_campaign);
  ASSERT_EQ(from_array.steps.size(), static_cast<std::size_t>(kSteps));
  double worst_relative = 0.0, worst_frequency_hz = 0.0;
  for (int s = 0; s < kSteps; ++s) {
    worst_frequency_hz = std::max(worst_frequency_hz,
                                  std::abs(from_array.steps[s].frequency_hz - from_csv.steps[s].frequency_hz));
    for (const char* name : kChannels) {
      const ChannelPhasors& a = *from_array.steps[s].Find(name);
      const ChannelPhasors& b = *from_csv.steps[s].Find(name);
      const double scale = b.Harmonic(1).Amplitude();
      for (int k = 1; k <= 5; ++k)
        worst_relative = std::max(worst_relative, std::abs(a.Harmonic(k).value - b.Harmonic(k).value) / scale);
    }
  }
  std::cout << layout.name << ": largest phasor difference from CSV " << worst_relative
            << " of the first harmonic, frequency difference " << worst_frequency_hz << " Hz\n";
  RecordProperty("worst_relative_phasor_difference", std::to_string(worst_relative));
  EXPECT_LE(worst_relative, kPhasorTolerance);
  EXPECT_LE(worst_frequency_hz, 1e-12 * 40.0);
}

std::string LayoutName(const ::testing::TestParamInfo<Layout>& param) { return param.param.name; }

INSTANTIATE_TEST_SUITE_P(
    Layouts, ArrayRecordingTest,
    ::testing::Values(
        Layout{"MatV5DoubleColumns", Container::kMatV5, Precision::kDouble, Orientation::kColumn,
               Timing::kTimeVector, false},
        Layout{"MatV5SingleRowsSampleRate", Container::kMatV5, Precision::kSingle, Orientation::kRow,
               Timing::kSampleRate, false},
        Layout{"MatV73DoubleRowsUnits", Container::kMatV73, Precision::kDouble, Orientation::kRow,
               Timing::kTimeVector, true},
        Layout{"MatV73SingleColumnsSampleRate", Container::kMatV73, Precision::kSingle, Orientation::kColumn,
               Timing::kSampleRate, false},
        Layout{"Hdf5DoubleOneDimensionalUnits", Container::kHdf5, Precision::kDouble, Orientation::kOneDimensional,
               Timing::kTimeVector, true},
        Layout{"Hdf5SingleColumnsRootSampleRate", Container::kHdf5, Precision::kSingle, Orientation::kColumn,
               Timing::kSampleRate, false}),
    LayoutName);

// ---- One malformed file per case: the error names the file, the channel and what is wrong ----

class ArrayMalformedTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = beamid::testing::UniqueTempPath("beamid_array_bad");
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    const StepData step = MakeSteps(false)[0];
    for (int c = 0; c < 3; ++c) arrays_.push_back(Vector(kChannels[c], step.columns[c], Orientation::kColumn));
    arrays_.push_back(Vector("time_s", step.time_s, Orientation::kColumn));
  }
  void TearDown() override { fs::remove_all(folder_); }

  Array& Named(const std::string& name) {
    for (Array& array : arrays_)
      if (array.name == name) return array;
    throw std::logic_error("no array " + name);
  }

  // Writes both steps' files with `write`, reads step 0 and checks the error.
  void ExpectError(Container container, const std::string& channel, const std::string& problem,
                   const std::function<void(const fs::path&)>& write = {}) {
    const std::string extension = Extension(container);
    WriteFile(folder_ / "campaign.json", CampaignJson(extension, false));
    for (int s = 0; s < kSteps; ++s) {
      const fs::path path = folder_ / ("s" + std::to_string(s) + extension);
      if (write)
        write(path);
      else
        WriteArrays(path, container, arrays_);
    }
    const Campaign campaign = ReadCampaign(folder_);
    try {
      ReadRecording(campaign, campaign.steps[0]);
      ADD_FAILURE() << "no error for " << problem;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), (folder_ / ("s0" + extension)).string());
      EXPECT_EQ(e.channel(), channel) << e.what();
      EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("Fix: "), std::string::npos) << e.what();
      std::cout << "  " << e.what() << "\n";
    }
  }

  fs::path folder_;
  std::vector<Array> arrays_;
};

TEST_F(ArrayMalformedTest, WellFormedFilesRead) {
  for (const Container container : {Container::kMatV5, Container::kMatV73, Container::kHdf5}) {
    const std::string extension = Extension(container);
    WriteFile(folder_ / "campaign.json", CampaignJson(extension, false));
    for (int s = 0; s < kSteps; ++s) WriteArrays(folder_ / ("s" + std::to_string(s) + extension), container, arrays_);
    const Campaign campaign = ReadCampaign(folder_);
    EXPECT_EQ(ReadRecording(campaign, campaign.steps[0]).NumSamples(), kSamples) << extension;
  }
}

TEST_F(ArrayMalformedTest, MissingVariable) {
  arrays_.erase(arrays_.begin() + 2);  // vel2
  ExpectError(Container::kMatV5, "vel2", "has no variable named 'vel2' (it holds 'force' (5000×1 double)");
}

TEST_F(ArrayMalformedTest, MissingDataset) {
  Named("vel2").name = "Vel2";
  ExpectError(Container::kHdf5, "vel2", "has no dataset named 'vel2'");
}

TEST_F(ArrayMalformedTest, WrongLength) {
  Named("acc1").values.pop_back();
  Named("acc1").dims = {kSamples - 1, 1};
  ExpectError(Container::kMatV73, "acc1",
              "variable 'acc1' holds 4999 samples, but the excitation's variable 'force' holds 5000");
}

TEST_F(ArrayMalformedTest, TimeOfAnotherLength) {
  Named("time_s").values.pop_back();
  Named("time_s").dims = {kSamples - 1, 1};
  ExpectError(Container::kHdf5, "time_s", "dataset 'time_s' holds 4999 times");
}

TEST_F(ArrayMalformedTest, NaN) {
  Named("acc1").values[100] = std::nan("");
  ExpectError(Container::kMatV5, "acc1", "variable 'acc1' holds NaN or an infinite value at sample 100 (t = 0.02 s)");
}

TEST_F(ArrayMalformedTest, NaNInHdf5) {
  Named("vel2").values[7] = -std::numeric_limits<double>::infinity();
  ExpectError(Container::kHdf5, "vel2", "dataset 'vel2' holds NaN or an infinite value at sample 7");
}

TEST_F(ArrayMalformedTest, NonUniformTime) {
  Named("time_s").values[2000] += 0.5 / kRateHz;
  ExpectError(Container::kMatV5, "time_s", "non-uniform sampling at sample 2000");
}

TEST_F(ArrayMalformedTest, TimeThatDoesNotIncrease) {
  Named("time_s").values[10] = Named("time_s").values[9];
  ExpectError(Container::kHdf5, "time_s", "time does not increase at sample 10");
}

TEST_F(ArrayMalformedTest, ComplexMat) {
  Named("acc1").special = Array::Special::kComplex;
  ExpectError(Container::kMatV5, "acc1", "variable 'acc1' holds complex double values; a time history is real");
}

TEST_F(ArrayMalformedTest, ComplexHdf5) {
  Named("acc1").special = Array::Special::kComplex;
  ExpectError(Container::kHdf5, "acc1", "dataset 'acc1' holds complex double values");
}

TEST_F(ArrayMalformedTest, IntegerMat) {
  Named("acc1").special = Array::Special::kInt16;
  ExpectError(Container::kMatV73, "acc1", "variable 'acc1' holds int16 integers (raw converter counts?)");
}

TEST_F(ArrayMalformedTest, IntegerHdf5) {
  Named("force").special = Array::Special::kInt16;
  ExpectError(Container::kHdf5, "force", "dataset 'force' holds int16 integers");
}

TEST_F(ArrayMalformedTest, TextInsteadOfNumbers) {
  Named("vel2").special = Array::Special::kChar;
  ExpectError(Container::kMatV5, "vel2", "variable 'vel2' is a char variable, not numbers");
}

TEST_F(ArrayMalformedTest, MatrixInsteadOfVector) {
  Array& acc1 = Named("acc1");
  acc1.values.resize(3 * 1000);
  acc1.dims = {1000, 3};
  ExpectError(Container::kMatV5, "acc1", "variable 'acc1' is a 1000×3 array, not a vector of samples");
}

TEST_F(ArrayMalformedTest, NotAMatFile) {
  ExpectError(Container::kMatV5, "", "not a MATLAB .mat file",
              [](const fs::path& path) { WriteFile(path, "time_s,force,acc1,vel2\n0,1,2,3\n"); });
}

TEST_F(ArrayMalformedTest, EmptyMatFile) {
  ExpectError(Container::kMatV5, "", "not a MATLAB .mat file", [](const fs::path& path) { WriteFile(path, ""); });
}

TEST_F(ArrayMalformedTest, NotAnHdf5File) {
  ExpectError(Container::kHdf5, "", "not an HDF5 file",
              [](const fs::path& path) { WriteFile(path, std::string(4096, '\0')); });
}

TEST_F(ArrayMalformedTest, TruncatedMatFile) {
  // The v5 file cut in the middle of its data: an error naming the file, never a crash.
  const std::string extension = ".mat";
  WriteFile(folder_ / "campaign.json", CampaignJson(extension, false));
  const fs::path whole = folder_ / "whole.mat";
  WriteArrays(whole, Container::kMatV5, arrays_);
  std::ifstream in(whole, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  bytes.resize(bytes.size() / 2);
  for (int s = 0; s < kSteps; ++s) WriteFile(folder_ / ("s" + std::to_string(s) + extension), bytes);
  const Campaign campaign = ReadCampaign(folder_);
  try {
    ReadRecording(campaign, campaign.steps[0]);
    ADD_FAILURE() << "no error for a truncated file";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (folder_ / "s0.mat").string());
    EXPECT_NE(std::string(e.what()).find("Fix: "), std::string::npos) << e.what();
    std::cout << "  " << e.what() << "\n";
  }
}

TEST_F(ArrayMalformedTest, UnknownUnit) {
  Named("acc1").unit = "furlong/s^2";
  ExpectError(Container::kHdf5, "acc1",
              "dataset 'acc1' gives the unit 'furlong/s^2' (its \"units\" attribute), which is not a unit of "
              "acceleration (campaign.json declares 'g')");
}

TEST_F(ArrayMalformedTest, UnitDisagreesWithCampaign) {
  Named("acc1").unit = "m/s^2";
  ExpectError(Container::kMatV5, "acc1",
              "variable 'acc1' gives the unit 'm/s^2' (the variable acc1_units) but campaign.json declares 'g'");
}

TEST_F(ArrayMalformedTest, UnitSuffixDisagreesWithCampaign) {
  Named("vel2").name = "vel2_m_s";
  ExpectError(Container::kMatV73, "vel2", "gives the unit 'm_s' (its name) but campaign.json declares 'mm/s'");
}

TEST_F(ArrayMalformedTest, TimeWithoutUnit) {
  Named("time_s").name = "time";
  ExpectError(Container::kMatV5, "time", "the time variable 'time' has no unit");
}

TEST_F(ArrayMalformedTest, NoTimeAndNoSampleRate) {
  arrays_.pop_back();  // time_s
  ExpectError(Container::kHdf5, "", "has no time dataset and no sample rate");
}

TEST_F(ArrayMalformedTest, SampleRateThatIsNoNumber) {
  arrays_.pop_back();
  arrays_.push_back(Vector("sample_rate_Hz", {5000.0, 5000.0}, Orientation::kColumn));
  ExpectError(Container::kMatV5, "sample_rate_Hz", "variable 'sample_rate_Hz' is a 2×1 double, not one number");
}

// A dataset whose values lie in another file (HDF5 external storage) could
// read any file of the disk: it is refused, not followed.
TEST_F(ArrayMalformedTest, ExternalStorageIsNotFollowed) {
  const fs::path outside = folder_ / "outside.bin";
  ExpectError(Container::kHdf5, "acc1", "dataset 'acc1' keeps its values in other files", [&](const fs::path& path) {
    std::vector<Array> arrays = arrays_;
    arrays.erase(arrays.begin() + 1);  // acc1, written below
    WriteHdf5(path, arrays);
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hsize_t dims[] = {kSamples};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t creation = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_external(creation, outside.c_str(), 0, kSamples * sizeof(double));
    const hid_t dataset = H5Dcreate2(file, "acc1", H5T_IEEE_F64LE, space, H5P_DEFAULT, creation, H5P_DEFAULT);
    ASSERT_GE(dataset, 0);
    H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, Named("acc1").values.data());
    H5Dclose(dataset);
    H5Pclose(creation);
    H5Sclose(space);
    H5Fclose(file);
  });
}

// A unit suffix that is campaign.json's unit reads, and so does a channel
// whose "column" names an HDF5 dataset in a group.
TEST_F(ArrayMalformedTest, UnitSuffixAndColumnInAGroupRead) {
  Named("acc1").name = "acc1_g";
  Named("vel2").name = "channels/Ch2 vel";
  std::string json = CampaignJson(".h5", false);
  const std::string vel2 = R"("channel": "vel2",)";
  json.replace(json.find(vel2), vel2.size(), R"("channel": "vel2", "column": "/channels/Ch2 vel",)");
  WriteFile(folder_ / "campaign.json", json);
  for (int s = 0; s < kSteps; ++s) {
    const fs::path path = folder_ / ("s" + std::to_string(s) + ".h5");
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    H5Gclose(H5Gcreate2(file, "channels", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    H5Fclose(file);
    // WriteHdf5 truncates: write into the group through a second file handle.
    const hid_t again = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    for (const Array& array : arrays_) {
      const hsize_t dims[] = {array.values.size()};
      const hid_t space = H5Screate_simple(1, dims, nullptr);
      const hid_t dataset =
          H5Dcreate2(again, array.name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, array.values.data());
      H5Dclose(dataset);
      H5Sclose(space);
    }
    H5Fclose(again);
  }
  const Campaign campaign = ReadCampaign(folder_);
  const Recording recording = ReadRecording(campaign, campaign.steps[0]);
  EXPECT_EQ(recording.channels, (std::vector<std::string>{"force", "acc1", "vel2"}));
  EXPECT_EQ(recording.samples(3, 1), Named("acc1_g").values[3] * kGravity);
  EXPECT_EQ(recording.samples(3, 2), Named("channels/Ch2 vel").values[3] * 1e-3);
}

// A spare channel's problem is no error: a channel campaign.json ignores is
// left out with a note, and extra variables are listed, not read.
TEST_F(ArrayMalformedTest, ProblemsOfAnIgnoredChannelAreNotes) {
  Named("vel2").special = Array::Special::kComplex;
  arrays_.push_back(Vector("temperature", std::vector<double>(10, 21.0), Orientation::kColumn));
  std::string json = CampaignJson(".mat", false);
  json.insert(json.rfind('}'), R"(, "ignore_channels": ["vel2"])");
  WriteFile(folder_ / "campaign.json", json);
  for (int s = 0; s < kSteps; ++s)
    WriteArrays(folder_ / ("s" + std::to_string(s) + ".mat"), Container::kMatV5, arrays_);
  const Campaign campaign = ReadCampaign(folder_);
  const Recording recording = ReadRecording(campaign, campaign.steps[0]);
  EXPECT_EQ(recording.channels, (std::vector<std::string>{"force", "acc1"}));
  EXPECT_EQ(recording.ignored_columns, std::vector<std::string>{"temperature"});
  ASSERT_FALSE(recording.findings.empty());
  EXPECT_EQ(recording.findings.front().severity, Severity::kNote);
  EXPECT_NE(recording.findings.front().problem.find("holds complex double values"), std::string::npos);
}

// ---- A first-harmonic table as vectors (beamid backbone --measured LEVEL.mat, docs/phasor-table.md) ----

class ArrayPhasorTableTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = beamid::testing::UniqueTempPath("beamid_array_table");
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    for (int i = 0; i < 9; ++i) {
      frequency_hz_.push_back(53.0 + 0.25 * i);
      force_n_.push_back(1.0 + 0.01 * std::sin(i));
      acceleration_g_.push_back(0.2 + 0.05 * std::sin(0.7 * i));
      phase_deg_.push_back(20.0 + 15.0 * i);
      acceleration_std_g_.push_back(1e-3 * (1.0 + 0.1 * i));
    }
  }
  void TearDown() override { fs::remove_all(folder_); }

  // The columns, named as a CSV header would name them or given their units by the file.
  std::vector<Array> Columns(Orientation orientation, bool units_in_file) const {
    std::vector<Array> arrays = {Vector(units_in_file ? "frequency" : "frequency_Hz", frequency_hz_, orientation),
                                 Vector(units_in_file ? "force" : "force_N", force_n_, orientation),
                                 Vector(units_in_file ? "acceleration" : "acceleration_g", acceleration_g_,
                                        orientation),
                                 Vector(units_in_file ? "phase" : "phase_deg", phase_deg_, orientation),
                                 Vector("acceleration_std_g", acceleration_std_g_, orientation)};
    if (units_in_file)
      for (auto [a, unit] : {std::pair{0, "Hz"}, {1, "N"}, {2, "g"}, {3, "deg"}}) arrays[a].unit = unit;
    return arrays;
  }

  std::string Csv() const {
    std::string csv = "frequency_Hz,force_N,acceleration_g,phase_deg,acceleration_std_g\n";
    char line[200];
    for (std::size_t i = 0; i < frequency_hz_.size(); ++i) {
      std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g\n", frequency_hz_[i], force_n_[i],
                    acceleration_g_[i], phase_deg_[i], acceleration_std_g_[i]);
      csv += line;
    }
    return csv;
  }

  fs::path folder_;
  std::vector<double> frequency_hz_, force_n_, acceleration_g_, phase_deg_, acceleration_std_g_;
};

TEST_F(ArrayPhasorTableTest, GivesTheLevelOfTheSameNumbersAsCsv) {
  const FirstHarmonicLevel from_csv = ParsePhasorTable(Csv(), "high.csv", "high");
  const struct {
    Container container;
    Orientation orientation;
    bool units_in_file;
  } layouts[] = {{Container::kMatV5, Orientation::kRow, false},
                 {Container::kMatV73, Orientation::kColumn, true},
                 {Container::kHdf5, Orientation::kOneDimensional, true}};
  for (const auto& layout : layouts) {
    const fs::path path = folder_ / ("high" + Extension(layout.container));
    WriteArrays(path, layout.container, Columns(layout.orientation, layout.units_in_file));
    const FirstHarmonicLevel level = ReadPhasorTable(path);
    EXPECT_EQ(level.label, "high");
    EXPECT_EQ(level.response_quantity, Quantity::kAcceleration);
    ASSERT_EQ(level.points.size(), from_csv.points.size()) << path;
    double worst = 0.0;
    for (std::size_t i = 0; i < level.points.size(); ++i) {
      const FirstHarmonicPoint& a = level.points[i];
      const FirstHarmonicPoint& b = from_csv.points[i];
      worst = std::max({worst, std::abs(a.frequency_hz - b.frequency_hz), std::abs(a.force.value - b.force.value),
                        std::abs(a.response.value - b.response.value),
                        (a.response.Covariance() - b.response.Covariance()).cwiseAbs().maxCoeff()});
    }
    std::cout << path.filename().string() << ": largest difference from the CSV table " << worst << "\n";
    EXPECT_EQ(worst, 0.0) << path;
  }
}

TEST_F(ArrayPhasorTableTest, ComplexResponseIsRefused) {
  std::vector<Array> arrays = Columns(Orientation::kColumn, false);
  arrays[2].special = Array::Special::kComplex;
  const fs::path path = folder_ / "high.mat";
  WriteArrays(path, Container::kMatV5, arrays);
  try {
    ReadPhasorTable(path);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_NE(std::string(e.what()).find("column 'acceleration_g': holds complex double values, not real numbers"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("Fix: "), std::string::npos) << e.what();
  }
}

TEST_F(ArrayPhasorTableTest, ColumnsOfDifferentLengthsAreRefused) {
  std::vector<Array> arrays = Columns(Orientation::kColumn, true);
  arrays[3].values.pop_back();
  arrays[3].dims = {arrays[3].values.size(), 1};
  const fs::path path = folder_ / "high.h5";
  WriteArrays(path, Container::kHdf5, arrays);
  try {
    ReadPhasorTable(path);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    // HDF5 lists datasets by name: 'acceleration' is the first column read.
    EXPECT_NE(std::string(e.what()).find("column 'phase': holds 8 values but 'acceleration' holds 9"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace beamid::signal
