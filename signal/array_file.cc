#include "signal/array_file.h"

#include <algorithm>
#include <cctype>

namespace beamid::signal {
namespace {

std::string LowerExtension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
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
  return IsMatFile(path) ? OpenMatFile(path, source) : OpenHdf5File(path, source);
}

}  // namespace beamid::signal
