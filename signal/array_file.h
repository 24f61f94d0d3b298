// The named numeric arrays of a MATLAB .mat file (v5 and v7.3, read by
// matio) or an HDF5 file (.h5, .hdf5, read by the HDF5 C library): what a
// step's recording (signal/array_recording.h) is made of. A .mat file's
// arrays are its variables; an HDF5 file's are its datasets, named by their
// path without the leading '/' ("acc1", "data/acc1"), and the numeric
// attributes of its root group ("sample_rate_Hz"). Only the list of arrays
// is read on opening; values are read when asked for, one array at a time,
// so a file's spare channels take no memory.
// A unit travels with an array: an HDF5 dataset's "units" (or "unit")
// attribute, or in a .mat file the char variable <name>_units ("acc1_units"
// holding 'g'), as MATLAB has no attributes. docs/campaign-format.md has the
// layout. matio and HDF5 are not thread-safe: every call into them holds one
// lock (calls of two files are serialised, never interleaved).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace beamid::signal {

// What an array holds, as far as a recording is concerned: real numbers
// (double or single precision) are read, anything else is refused by name.
// kElsewhere: an HDF5 dataset whose values lie in other files (external
// storage, a virtual dataset), which beamid does not follow.
enum class ArrayKind { kReal, kComplex, kInteger, kLogical, kText, kOther, kElsewhere };

struct ArrayInfo {
  std::string name;   // the variable's name, the dataset's path or the root attribute's name
  ArrayKind kind = ArrayKind::kOther;
  std::string type;   // for messages: "double", "single", "int16", "complex double", "struct", "char", ...
  std::vector<std::uint64_t> dims;  // as the file gives them (MATLAB: rows, columns, ...); {} for an HDF5 scalar
  std::string unit;   // the unit the file gives (see above), "" when none; raw bytes, not checked
  bool root_attribute = false;      // an attribute of an HDF5 file's root group

  std::uint64_t NumElements() const;
  // A vector: every dimension but one is 1 (a column, a row or a 1-D dataset), or a scalar.
  bool IsVector() const;
  // "5000×1", "1×5000", "5000" (a 1-D dataset), "scalar".
  std::string Shape() const;
};

class ArrayFile {
 public:
  virtual ~ArrayFile() = default;

  // The file as messages name it.
  const std::string& Source() const { return source_; }
  // "MATLAB .mat file (v5)", "MATLAB .mat file (v7.3)" or "HDF5 file".
  const std::string& FormatName() const { return format_name_; }
  // "variable" (a .mat file) or "dataset" (HDF5), for messages.
  virtual std::string_view ArrayWord() const = 0;
  // Every array, in the order the file lists them.
  const std::vector<ArrayInfo>& Arrays() const { return arrays_; }
  // The array of that name, or nullptr.
  const ArrayInfo* Find(std::string_view name) const;

  // The values of a real array (kind kReal), converted to double (a single
  // precision value exactly), in storage order. Throws InputError when the
  // file's data cannot be read (a damaged file) or the array holds more than
  // kMaxArrayElements values.
  virtual std::vector<double> ReadReal(const ArrayInfo& array) = 0;

 protected:
  ArrayFile(std::string source, std::string format_name)
      : source_(std::move(source)), format_name_(std::move(format_name)) {}
  void SetFormatName(std::string format_name) { format_name_ = std::move(format_name); }
  std::vector<ArrayInfo> arrays_;

 private:
  std::string source_;
  std::string format_name_;
};

// More values than any step's channel holds (2^27: 7 h at 5120 Hz), so a
// damaged or hostile file's sizes never decide what is allocated.
inline constexpr std::uint64_t kMaxArrayElements = std::uint64_t{1} << 27;

// By extension, any case: .mat; .h5, .hdf5.
bool IsMatFile(const std::filesystem::path& file);
bool IsHdf5File(const std::filesystem::path& file);
inline bool IsArrayFile(const std::filesystem::path& file) { return IsMatFile(file) || IsHdf5File(file); }

// Opens a .mat file (v5 or v7.3; a v4 file is refused) or an HDF5 file and
// lists its arrays. Throws InputError naming `source` when the file is not
// one (a CSV saved as .mat, a damaged file) or cannot be read.
std::unique_ptr<ArrayFile> OpenMatFile(const std::filesystem::path& path, const std::string& source);
std::unique_ptr<ArrayFile> OpenHdf5File(const std::filesystem::path& path, const std::string& source);
// By extension, after the whole file has been read once in a child process
// (fork): a file that crashes matio or HDF5 there (a hostile or damaged file
// can), or keeps it busy past 10 s plus 1 s per 10 MB three times, is an
// InputError, and this process never reads it. What beamid's readers use.
std::unique_ptr<ArrayFile> OpenArrayFile(const std::filesystem::path& path, const std::string& source);

}  // namespace beamid::signal
