// MATLAB .mat files through matio (signal/array_file.h): v5 (MATLAB's -v6 and
// -v7, compressed or not) and v7.3 (HDF5 underneath, which matio reads through
// the HDF5 library). matio reports its problems through a log function: it is
// replaced, under the library lock, by one that keeps the last message for
// the error and prints nothing.
#include <hdf5.h>
#include <matio.h>

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

// More variables than any recording holds: a damaged file's list stops here.
constexpr std::size_t kMaxMatVariables = 10000;
// The header of a v5 or v7.3 file (text, subsystem offset, version, byte order).
constexpr std::uintmax_t kMatHeaderBytes = 128;
// The longest unit text read from a <name>_units variable.
constexpr std::uint64_t kMaxMatUnitChars = 64;

std::string& MatLastMessage() {
  static std::string message;
  return message;
}

void KeepMatMessage(int /*log_level*/, char* message) {
  MatLastMessage() = message != nullptr ? Excerpt(message, 120) : std::string();
}

// Called with the lock held, before any matio call.
void QuietMatio() {
  MatLastMessage().clear();
  Mat_LogInitFunc("beamid", KeepMatMessage);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // v7.3: HDF5's own error stack printer
}

std::string MatioSays() {
  return MatLastMessage().empty() ? std::string() : " (matio: " + MatLastMessage() + ")";
}

struct MatVarDeleter {
  void operator()(matvar_t* var) const { Mat_VarFree(var); }
};
using MatVarPtr = std::unique_ptr<matvar_t, MatVarDeleter>;

std::string MatClassName(const matvar_t& var) {
  switch (var.class_type) {
    case MAT_C_EMPTY: return "empty";
    case MAT_C_CELL: return "cell";
    case MAT_C_STRUCT: return "struct";
    case MAT_C_OBJECT: return "object";
    case MAT_C_CHAR: return "char";
    case MAT_C_SPARSE: return "sparse";
    case MAT_C_DOUBLE: return "double";
    case MAT_C_SINGLE: return "single";
    case MAT_C_INT8: return "int8";
    case MAT_C_UINT8: return "uint8";
    case MAT_C_INT16: return "int16";
    case MAT_C_UINT16: return "uint16";
    case MAT_C_INT32: return "int32";
    case MAT_C_UINT32: return "uint32";
    case MAT_C_INT64: return "int64";
    case MAT_C_UINT64: return "uint64";
    case MAT_C_FUNCTION: return "function handle";
    case MAT_C_OPAQUE: return "opaque object";
  }
  return "unknown class";
}

ArrayInfo DescribeMatVariable(const matvar_t& var) {
  ArrayInfo info;
  info.name = var.name != nullptr ? var.name : "";
  info.type = MatClassName(var);
  const bool numeric_class = var.class_type == MAT_C_DOUBLE || var.class_type == MAT_C_SINGLE;
  const bool integer_class = var.class_type >= MAT_C_INT8 && var.class_type <= MAT_C_UINT64;
  if (var.isLogical) {
    info.kind = ArrayKind::kLogical;
    info.type = "logical";
  } else if ((numeric_class || integer_class) && var.isComplex) {
    info.kind = ArrayKind::kComplex;
    info.type = "complex " + info.type;
  } else if (numeric_class) {
    info.kind = ArrayKind::kReal;
  } else if (integer_class) {
    info.kind = ArrayKind::kInteger;
  } else if (var.class_type == MAT_C_CHAR) {
    info.kind = ArrayKind::kText;
  }
  if (var.dims != nullptr)
    for (int d = 0; d < var.rank && d < 32; ++d) info.dims.push_back(var.dims[d]);
  return info;
}

// The text of a char variable: UTF-8 (a UTF-16 unit beyond ASCII encoded as
// UTF-8, so 'm/s²' reads as written).
std::string MatText(const matvar_t& var) {
  std::string text;
  if (var.data == nullptr) return text;
  const std::size_t bytes = var.nbytes;
  if (var.data_type == MAT_T_UINT16 || var.data_type == MAT_T_UTF16) {
    const std::size_t n = bytes / 2;
    for (std::size_t i = 0; i < n; ++i) {
      std::uint16_t unit;
      std::memcpy(&unit, static_cast<const char*>(var.data) + 2 * i, 2);
      if (unit < 0x80) {
        text += static_cast<char>(unit);
      } else if (unit < 0x800) {
        text += static_cast<char>(0xC0 | (unit >> 6));
        text += static_cast<char>(0x80 | (unit & 0x3F));
      } else {
        text += static_cast<char>(0xE0 | (unit >> 12));
        text += static_cast<char>(0x80 | ((unit >> 6) & 0x3F));
        text += static_cast<char>(0x80 | (unit & 0x3F));
      }
    }
  } else if (var.data_type == MAT_T_UINT8 || var.data_type == MAT_T_UTF8 || var.data_type == MAT_T_INT8) {
    text.assign(static_cast<const char*>(var.data), bytes);
  }
  return text;
}

class MatFile final : public ArrayFile {
 public:
  MatFile(const std::filesystem::path& path, const std::string& source) : ArrayFile(source, "MATLAB .mat file") {
    // matio opens a file shorter than the 128-byte header of v5 and v7.3 (an empty one) as a v5 file.
    std::error_code error;
    const std::uintmax_t bytes = std::filesystem::file_size(path, error);
    if (error || bytes < kMatHeaderBytes)
      throw InputError(Source(), "",
                       "not a MATLAB .mat file (" + (error ? error.message() : std::to_string(bytes) + " bytes") +
                           ", shorter than the 128-byte header of a v5 or v7.3 file)",
                       "save the recording again with MATLAB's save (-v7 or -v7.3), scipy.io.savemat or matio");
    std::lock_guard lock(ArrayLibraryLock());
    QuietMatio();
    mat_ = Mat_Open(path.c_str(), MAT_ACC_RDONLY);
    if (mat_ == nullptr)
      throw InputError(Source(), "",
                       "not a MATLAB .mat file (no v5 or v7.3 header can be read" + MatioSays() + ")",
                       "save the recording with MATLAB's save (-v7 or -v7.3), scipy.io.savemat or matio, or name a "
                       "CSV recording .csv");
    const enum mat_ft version = Mat_GetVersion(mat_);
    if (version != MAT_FT_MAT5 && version != MAT_FT_MAT73) {
      Mat_Close(mat_);
      mat_ = nullptr;
      throw InputError(Source(), "", "a MATLAB v4 .mat file, which beamid does not read",
                       "save it again with save(..., '-v7') or '-v7.3'");
    }
    SetFormatName(version == MAT_FT_MAT5 ? "MATLAB .mat file (v5)" : "MATLAB .mat file (v7.3)");
    try {
      List();
    } catch (...) {
      Mat_Close(mat_);
      mat_ = nullptr;
      throw;
    }
  }
  ~MatFile() override {
    std::lock_guard lock(ArrayLibraryLock());
    if (mat_ != nullptr) Mat_Close(mat_);
  }
  MatFile(const MatFile&) = delete;
  MatFile& operator=(const MatFile&) = delete;

  std::string_view ArrayWord() const override { return "variable"; }

  std::vector<double> ReadReal(const ArrayInfo& array) override {
    std::lock_guard lock(ArrayLibraryLock());
    QuietMatio();
    const MatVarPtr var = ReadVariable(array);
    const std::size_t n = static_cast<std::size_t>(array.NumElements());
    std::vector<double> values(n);
    const bool is_double = var->class_type == MAT_C_DOUBLE && var->data_type == MAT_T_DOUBLE;
    const bool is_single = var->class_type == MAT_C_SINGLE && var->data_type == MAT_T_SINGLE;
    const std::size_t size = is_double ? sizeof(double) : sizeof(float);
    if ((!is_double && !is_single) || var->isComplex || var->data == nullptr || var->nbytes < n * size)
      throw Damaged(array, "its values do not read as " + array.type + " numbers");
    if (is_double) {
      std::memcpy(values.data(), var->data, n * sizeof(double));
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        float value;
        std::memcpy(&value, static_cast<const char*>(var->data) + i * sizeof(float), sizeof(float));
        values[i] = value;
      }
    }
    return values;
  }

 private:
  InputError Damaged(const ArrayInfo& array, const std::string& why) const {
    return InputError(Source(), Excerpt(array.name),
                      "the " + FormatName() + "'s variable '" + Excerpt(array.name) + "' cannot be read: " + why +
                          MatioSays(),
                      "save the file again (it may be damaged or cut short)");
  }

  MatVarPtr ReadVariable(const ArrayInfo& array) {
    if (array.NumElements() > kMaxArrayElements)
      throw InputError(Source(), Excerpt(array.name),
                       "variable '" + Excerpt(array.name) + "' is a " + array.Shape() + " array, more than the " +
                           std::to_string(kMaxArrayElements) + " values beamid reads of one array",
                       "split the step's recording, or save only the step's samples");
    MatVarPtr var(Mat_VarRead(mat_, array.name.c_str()));
    if (!var) throw Damaged(array, "matio found no data");
    // The listing's class and size must be what is read: a damaged file may say two things.
    if (DescribeMatVariable(*var).dims != array.dims) throw Damaged(array, "its size differs from its header's");
    return var;
  }

  void List() {
    for (;;) {
      MatVarPtr var(Mat_VarReadNextInfo(mat_));
      if (!var) break;
      if (arrays_.size() >= kMaxMatVariables)
        throw InputError(Source(), "",
                         "the file holds more than " + std::to_string(kMaxMatVariables) + " variables",
                         "save one step per file, with one variable per channel");
      if (var->name == nullptr) continue;
      arrays_.push_back(DescribeMatVariable(*var));
    }
    // A unit as MATLAB can keep one: the char variable <name>_units.
    for (ArrayInfo& array : arrays_) {
      const ArrayInfo* units = Find(array.name + "_units");
      if (units == nullptr || units->kind != ArrayKind::kText || units->NumElements() > kMaxMatUnitChars) continue;
      MatVarPtr var(Mat_VarRead(mat_, units->name.c_str()));
      if (var && var->class_type == MAT_C_CHAR) array.unit = MatText(*var);
    }
  }

  mat_t* mat_ = nullptr;
};

}  // namespace

std::unique_ptr<ArrayFile> OpenMatFile(const std::filesystem::path& path, const std::string& source) {
  return std::make_unique<MatFile>(path, source);
}

}  // namespace beamid::signal
