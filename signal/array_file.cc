#include "signal/array_file.h"

#include <algorithm>
#include <cctype>

#include "signal/input_error.h"
#include "signal/internal/read_in_child.h"
#include "signal/internal/text.h"

namespace beamid::signal {
namespace {

// A child reading a file: the time it may take (a base, plus the file's size at the slowest reading rate), and
// how many children are forked before a file is called unreadable (read_in_child.h: a child forked from a
// process with threads may deadlock at once; under AddressSanitizer about one fork in a few hundred does, on
// the allocator's lock).
constexpr double kChildBaseTimeoutS = 10.0;
constexpr double kChildSlowestReadBytesPerS = 10e6;
constexpr int kChildAttempts = 3;

std::string LowerExtension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// matio and HDF5 are C libraries that a damaged file can crash (the fuzzer
// finds buffer overflows inside libhdf5 1.10 reading a hostile file's
// attributes): a file is first read in a child process, everything the
// reader may ask of it (the list, the units, every real array), and only
// when the child ends well does this process read it. A child that dies, or
// runs past its time on every attempt, is an InputError, never a crash or a
// hang of beamid. Without a process to spare (fork fails) the file is read
// directly.
void ReadInChildFirst(const std::filesystem::path& path, const std::string& source, bool mat) {
  // Reading runs at tens of MB/s at the least; the time allowed is far beyond that, so that only a child which
  // will never finish reaches it.
  std::error_code error;
  const std::uintmax_t bytes = std::filesystem::file_size(path, error);
  const double timeout_s =
      kChildBaseTimeoutS + (error ? 0.0 : static_cast<double>(bytes) / kChildSlowestReadBytesPerS);
  const internal::ChildRead read = internal::ReadInChild(
      [&] {
        const auto file = mat ? OpenMatFile(path, source) : OpenHdf5File(path, source);
        for (const ArrayInfo& array : file->Arrays())
          if (array.kind == ArrayKind::kReal && array.NumElements() <= kMaxArrayElements) file->ReadReal(array);
      },
      timeout_s, kChildAttempts);
  const char* const library = mat ? "matio (the MATLAB file library)" : "the HDF5 library";
  if (read.outcome == internal::ChildRead::Outcome::kDied)
    throw InputError(source, "",
                     std::string("the file is damaged: reading it crashed ") + library + " in a separate process (" +
                         read.how_it_ended + "), so beamid reads nothing of it",
                     "save or copy the file again from the acquisition system");
  if (read.outcome == internal::ChildRead::Outcome::kTimedOut)
    throw InputError(source, "",
                     std::string("the file is damaged or hostile: reading it with ") + library +
                         " in a separate process did not end within " + internal::FormatNumber(timeout_s) +
                         " s, " + std::to_string(read.attempts) + " times, so beamid reads nothing of it",
                     "save or copy the file again from the acquisition system");
}

}  // namespace

std::uint64_t ArrayInfo::NumElements() const {
  std::uint64_t n = 1;
  for (const std::uint64_t d : dims) {
    if (d != 0 && n > kMaxArrayElements * 1024 / d) return kMaxArrayElements * 1024;  // saturated: only "too many"
    n *= d;
  }
  return n;
}

bool ArrayInfo::IsVector() const {
  return std::count_if(dims.begin(), dims.end(), [](std::uint64_t d) { return d != 1; }) <= 1;
}

std::string ArrayInfo::Shape() const {
  if (dims.empty()) return "scalar";
  std::string shape;
  for (const std::uint64_t d : dims) shape += (shape.empty() ? "" : "×") + std::to_string(d);
  return shape;
}

const ArrayInfo* ArrayFile::Find(std::string_view name) const {
  for (const ArrayInfo& array : arrays_)
    if (array.name == name) return &array;
  return nullptr;
}

bool IsMatFile(const std::filesystem::path& file) { return LowerExtension(file) == ".mat"; }

bool IsHdf5File(const std::filesystem::path& file) {
  const std::string extension = LowerExtension(file);
  return extension == ".h5" || extension == ".hdf5";
}

std::unique_ptr<ArrayFile> OpenArrayFile(const std::filesystem::path& path, const std::string& source) {
  const bool mat = IsMatFile(path);
  ReadInChildFirst(path, source, mat);
  return mat ? OpenMatFile(path, source) : OpenHdf5File(path, source);
}

}  // namespace beamid::signal
