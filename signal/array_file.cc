#include "signal/array_file.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <mutex>

#include "signal/input_error.h"
#include "signal/internal/array_library_lock.h"

namespace beamid::signal {
namespace {

std::string LowerExtension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// matio and HDF5 are C libraries that a damaged file can crash (the fuzzer
// finds buffer overflows inside libhdf5 1.10 reading a hostile file's
// attributes): a file is first read in a child process, everything the
// reader may ask of it (the list, the units, every real array), and only
// when the child ends well does this process read it. A child that dies is
// an InputError, never a crash of beamid. Without a process to spare (fork
// fails) the file is read directly.
void ReadInChildFirst(const std::filesystem::path& path, const std::string& source, bool mat) {
  // The child says it read the whole file by one byte through a pipe, before it exits: its exit status may
  // be a leak checker's (valgrind, LeakSanitizer), which a file has no part in.
  std::unique_lock lock(internal::ArrayLibraryLock());  // no thread of ours inside matio or HDF5 at the fork
  int done[2];
  if (pipe2(done, O_CLOEXEC) != 0) return;  // a program another thread starts does not keep it open
  const pid_t pid = fork();
  if (pid < 0) {
    close(done[0]);
    close(done[1]);
    return;
  }
  if (pid == 0) {
    close(done[0]);
    lock.unlock();  // the child's copy of the lock, held by its one thread
    try {
      const auto file = mat ? OpenMatFile(path, source) : OpenHdf5File(path, source);
      for (const ArrayInfo& array : file->Arrays())
        if (array.kind == ArrayKind::kReal && array.NumElements() <= kMaxArrayElements) file->ReadReal(array);
    } catch (...) {
    }
    const char byte = 1;
    [[maybe_unused]] const ssize_t written = write(done[1], &byte, 1);
    _exit(0);
  }
  lock.unlock();
  close(done[1]);
  char byte = 0;
  ssize_t got;
  while ((got = read(done[0], &byte, 1)) < 0 && errno == EINTR) {
  }
  close(done[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (got == 1) return;
  const std::string how = WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status)) + ", " +
                                                    std::string(strsignal(WTERMSIG(status)))
                                              : "exit code " + std::to_string(WEXITSTATUS(status));
  throw InputError(source, "",
                   std::string("the file is damaged: reading it crashed ") +
                       (mat ? "matio (the MATLAB file library)" : "the HDF5 library") + " in a separate process (" +
                       how + "), so beamid reads nothing of it",
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
