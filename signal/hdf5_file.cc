// HDF5 files through the HDF5 C library (signal/array_file.h): every dataset
// reached by hard links from the root group (soft and external links are not
// followed, nor are a dataset's external storage and a virtual dataset's
// sources: they would read files outside the campaign), and
// the numeric attributes of the root group. HDF5's own error printing is off;
// a failed call is an InputError naming the file and the dataset.
#include <hdf5.h>

#include <cstring>
#include <mutex>

#include "signal/array_file.h"
#include "signal/input_error.h"
#include "signal/internal/array_library_lock.h"
#include "signal/internal/text.h"

namespace beamid::signal {
namespace {

using internal::ArrayLibraryLock;
using internal::Excerpt;

// More datasets than any recording holds: a damaged file's list stops here.
constexpr std::size_t kMaxHdf5Arrays = 10000;
// The longest unit text read from a "units" attribute.
constexpr std::size_t kMaxHdf5UnitBytes = 64;

// An HDF5 identifier closed by its own function when it goes out of scope.
class Hdf5Handle {
 public:
  Hdf5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Hdf5Handle() {
    if (id_ >= 0) close_(id_);
  }
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

std::vector<std::uint64_t> Hdf5Dims(hid_t space) {
  std::vector<std::uint64_t> dims;
  if (space < 0) return {0};
  const H5S_class_t kind = H5Sget_simple_extent_type(space);
  if (kind == H5S_SCALAR) return dims;
  if (kind != H5S_SIMPLE) return {0};
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank <= 0 || rank > H5S_MAX_RANK) return {0};
  std::vector<hsize_t> extent(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space, extent.data(), nullptr);
  for (const hsize_t d : extent) dims.push_back(d);
  return dims;
}

// The kind and the type's name of an HDF5 datatype.
void DescribeHdf5Type(hid_t type, ArrayInfo& info) {
  const std::size_t bytes = H5Tget_size(type);
  switch (H5Tget_class(type)) {
    case H5T_FLOAT:
      info.kind = ArrayKind::kReal;
      info.type = bytes == 8 ? "double" : bytes == 4 ? "single" : std::to_string(8 * bytes) + "-bit float";
      return;
    case H5T_INTEGER:
      info.kind = ArrayKind::kInteger;
      info.type = std::string(H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(8 * bytes);
      return;
    case H5T_COMPOUND: {
      // h5py, MATLAB and Octave write a complex number as a compound of two floats.
      const bool two_floats = H5Tget_nmembers(type) == 2 && H5Tget_member_class(type, 0) == H5T_FLOAT &&
                              H5Tget_member_class(type, 1) == H5T_FLOAT;
      info.kind = two_floats ? ArrayKind::kComplex : ArrayKind::kOther;
      info.type = two_floats ? (bytes == 16 ? "complex double" : "complex single") : "compound";
      return;
    }
    case H5T_STRING: info.kind = ArrayKind::kText; info.type = "string"; return;
    case H5T_ENUM: info.kind = ArrayKind::kLogical; info.type = "enumeration (h5py's bool)"; return;
    case H5T_BITFIELD: info.kind = ArrayKind::kOther; info.type = "bitfield"; return;
    case H5T_OPAQUE: info.kind = ArrayKind::kOther; info.type = "opaque"; return;
    case H5T_REFERENCE: info.kind = ArrayKind::kOther; info.type = "reference"; return;
    case H5T_VLEN: info.kind = ArrayKind::kOther; info.type = "variable-length"; return;
    case H5T_ARRAY: info.kind = ArrayKind::kOther; info.type = "array type"; return;
    default: info.kind = ArrayKind::kOther; info.type = "unknown type"; return;
  }
}

// A string attribute (fixed or variable length, one value), or "".
std::string Hdf5StringAttribute(hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return "";
  const Hdf5Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  if (!attribute.ok()) return "";
  const Hdf5Handle type(H5Aget_type(attribute.get()), H5Tclose);
  const Hdf5Handle space(H5Aget_space(attribute.get()), H5Sclose);
  if (!type.ok() || H5Tget_class(type.get()) != H5T_STRING || H5Sget_simple_extent_npoints(space.get()) != 1)
    return "";
  if (H5Tis_variable_str(type.get()) > 0) {
    const Hdf5Handle memory(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(memory.get(), H5T_VARIABLE);
    H5Tset_cset(memory.get(), H5Tget_cset(type.get()));
    char* text = nullptr;
    if (H5Aread(attribute.get(), memory.get(), &text) < 0 || text == nullptr) return "";
    std::string value(text, strnlen(text, kMaxHdf5UnitBytes));
    H5free_memory(text);
    return value;
  }
  const std::size_t bytes = H5Tget_size(type.get());
  if (bytes == 0 || bytes > kMaxHdf5UnitBytes) return "";
  std::string value(bytes, '\0');
  const Hdf5Handle memory(H5Tcopy(type.get()), H5Tclose);
  if (H5Aread(attribute.get(), memory.get(), value.data()) < 0) return "";
  value.resize(strnlen(value.c_str(), bytes));
  while (!value.empty() && value.back() == ' ') value.pop_back();  // Fortran-style padding
  return value;
}

struct Hdf5Listing {
  std::vector<ArrayInfo>* arrays;
  bool too_many = false;
};

herr_t ListHdf5Link(hid_t group, const char* name, const H5L_info_t* link, void* data) {
  auto& listing = *static_cast<Hdf5Listing*>(data);
  if (link->type != H5L_TYPE_HARD) return 0;
  const Hdf5Handle dataset(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose);
  if (!dataset.ok()) return 0;  // a group, or a named datatype
  if (listing.arrays->size() >= kMaxHdf5Arrays) {
    listing.too_many = true;
    return 1;
  }
  ArrayInfo info;
  info.name = name;
  const Hdf5Handle type(H5Dget_type(dataset.get()), H5Tclose);
  const Hdf5Handle space(H5Dget_space(dataset.get()), H5Sclose);
  DescribeHdf5Type(type.get(), info);
  // Values kept in other files (named by the file, so anywhere on the disk) are not read.
  const Hdf5Handle creation(H5Dget_create_plist(dataset.get()), H5Pclose);
  if (!creation.ok() || H5Pget_external_count(creation.get()) != 0 || H5Pget_layout(creation.get()) == H5D_VIRTUAL)
    info.kind = ArrayKind::kElsewhere;
  info.dims = Hdf5Dims(space.get());
  info.unit = Hdf5StringAttribute(dataset.get(), "units");
  if (info.unit.empty()) info.unit = Hdf5StringAttribute(dataset.get(), "unit");
  listing.arrays->push_back(std::move(info));
  return 0;
}

herr_t ListHdf5RootAttribute(hid_t object, const char* name, const H5A_info_t* /*info*/, void* data) {
  auto& listing = *static_cast<Hdf5Listing*>(data);
  if (listing.arrays->size() >= kMaxHdf5Arrays) {
    listing.too_many = true;
    return 1;
  }
  const Hdf5Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  if (!attribute.ok()) return 0;
  ArrayInfo info;
  info.name = name;
  info.root_attribute = true;
  const Hdf5Handle type(H5Aget_type(attribute.get()), H5Tclose);
  const Hdf5Handle space(H5Aget_space(attribute.get()), H5Sclose);
  DescribeHdf5Type(type.get(), info);
  info.dims = Hdf5Dims(space.get());
  listing.arrays->push_back(std::move(info));
  return 0;
}

class Hdf5File final : public ArrayFile {
 public:
  Hdf5File(const std::filesystem::path& path, const std::string& source) : ArrayFile(source, "HDF5 file") {
    std::lock_guard lock(ArrayLibraryLock());
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    if (H5Fis_hdf5(path.c_str()) <= 0)
      throw InputError(Source(), "", "not an HDF5 file (no HDF5 signature)",
                       "save the recording as HDF5 (h5py, MATLAB's h5write, the acquisition system's HDF5 export), "
                       "or name a CSV recording .csv");
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file_ < 0)
      throw InputError(Source(), "", "the HDF5 file cannot be opened (damaged or cut short)",
                       "save or copy the file again");
    Hdf5Listing listing{&arrays_};
    const herr_t links = H5Lvisit(file_, H5_INDEX_NAME, H5_ITER_INC, ListHdf5Link, &listing);
    if (!listing.too_many && links >= 0)
      H5Aiterate2(file_, H5_INDEX_NAME, H5_ITER_INC, nullptr, ListHdf5RootAttribute, &listing);
    if (listing.too_many || links < 0) {
      H5Fclose(file_);
      file_ = -1;
      throw InputError(Source(), "",
                       listing.too_many ? "the file holds more than " + std::to_string(kMaxHdf5Arrays) + " datasets"
                                        : std::string("the HDF5 file's groups cannot be read (damaged file)"),
                       "save one step per file, with one dataset per channel");
    }
  }
  ~Hdf5File() override {
    std::lock_guard lock(ArrayLibraryLock());
    if (file_ >= 0) H5Fclose(file_);
  }
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  std::string_view ArrayWord() const override { return "dataset"; }

  std::vector<double> ReadReal(const ArrayInfo& array) override {
    if (array.NumElements() > kMaxArrayElements)
      throw InputError(Source(), Excerpt(array.name),
                       "dataset '" + Excerpt(array.name) + "' is a " + array.Shape() + " array, more than the " +
                           std::to_string(kMaxArrayElements) + " values beamid reads of one array",
                       "split the step's recording, or save only the step's samples");
    std::lock_guard lock(ArrayLibraryLock());
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    std::vector<double> values(static_cast<std::size_t>(array.NumElements()));
    herr_t status = -1;
    if (array.root_attribute) {
      const Hdf5Handle attribute(H5Aopen(file_, array.name.c_str(), H5P_DEFAULT), H5Aclose);
      const Hdf5Handle space(attribute.ok() ? H5Aget_space(attribute.get()) : -1, H5Sclose);
      if (attribute.ok() && Hdf5Dims(space.get()) == array.dims)
        status = H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, values.data());
    } else if (array.kind != ArrayKind::kElsewhere) {
      const Hdf5Handle dataset(H5Dopen2(file_, array.name.c_str(), H5P_DEFAULT), H5Dclose);
      const Hdf5Handle space(dataset.ok() ? H5Dget_space(dataset.get()) : -1, H5Sclose);
      if (dataset.ok() && Hdf5Dims(space.get()) == array.dims)
        status = H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    }
    if (status < 0)
      throw InputError(Source(), Excerpt(array.name),
                       std::string(array.root_attribute ? "the root attribute '" : "dataset '") + Excerpt(array.name) +
                           "' cannot be read (a damaged file, or a compression filter this HDF5 library lacks)",
                       "save the file again, without compression or with gzip (deflate)");
    return values;
  }

 private:
  hid_t file_ = -1;
};

}  // namespace

std::unique_ptr<ArrayFile> OpenHdf5File(const std::filesystem::path& path, const std::string& source) {
  return std::make_unique<Hdf5File>(path, source);
}

}  // namespace beamid::signal
