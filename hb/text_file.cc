#include "hb/text_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "hb/errors.h"

namespace beamid {
namespace {

std::string KindOfMode(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Closes a descriptor whatever happens.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// Writes all of text to fd; false with errno set when a write fails.
bool WriteAll(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t written = ::write(fd, text.data(), text.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    text.remove_prefix(static_cast<std::size_t>(written));
  }
  return true;
}

[[noreturn]] void WriteFailed(const std::filesystem::path& path, int error) {
  if (error == ENOSPC || error == EDQUOT)
    throw EnvironmentError(path.string() + ": writing failed (" + std::strerror(error) + "): free some space");
  throw EnvironmentError(path.string() + ": writing failed (" + std::strerror(error) + ")");
}

}  // namespace

std::string FileKind(const std::filesystem::path& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) return "missing";
    return std::string("unreadable (") + std::strerror(errno) + ")";
  }
  return KindOfMode(status.st_mode);
}

void WriteTextFileAtomically(const std::filesystem::path& path, std::string_view text) {
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode)) {
    if (!S_ISCHR(status.st_mode))
      throw InputError(path.string() + ": is " + KindOfMode(status.st_mode) +
                       ", not a file: give the name of a file to write");
    // A device is written in place, never renamed over.
    Descriptor out{::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY)};
    if (out.fd < 0)
      throw InputError(path.string() + ": cannot open this device for writing (" + std::strerror(errno) + ")");
    if (!WriteAll(out.fd, text)) WriteFailed(path, errno);
    return;
  }
  std::filesystem::path temporary = path;
  temporary += ".partial-" + std::to_string(::getpid());
  // O_EXCL: a leftover of that name (or a link planted there) is not followed.
  ::unlink(temporary.c_str());
  Descriptor out{::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOCTTY, 0666)};
  if (out.fd < 0) {
    if (errno == EMFILE || errno == ENFILE || errno == ENOMEM)
      throw EnvironmentError(path.string() + ": cannot write this file (" + std::strerror(errno) + ")");
    throw InputError(path.string() + ": cannot write this file (" + std::strerror(errno) +
                     "): check the folder and permissions");
  }
  const bool written = WriteAll(out.fd, text);
  const int write_error = errno;
  const bool closed = ::close(out.fd) == 0;
  const int close_error = errno;
  out.fd = -1;
  if (!written || !closed) {
    ::unlink(temporary.c_str());
    WriteFailed(path, !written ? write_error : close_error);
  }
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    throw InputError(path.string() + ": cannot replace this file (" + std::strerror(error) + ")");
  }
}

std::string ReadTextFile(const std::filesystem::path& path, std::string_view what, std::string_view fix) {
  const auto fail = [&](const std::string& reason) {
    throw InputError(path.string(), "", "cannot read the " + std::string(what) + " (" + reason + ")", std::string(fix));
  };
  const auto machine_failed = [&](int error) {
    throw EnvironmentError(path.string() + ": cannot read the " + std::string(what) + " (" + std::strerror(error) +
                           (error == EIO ? ": the disk or the network file system failed" : "") + ")");
  };
  const auto open_failed = [&](int error) {
    if (error == ENOENT || error == ENOTDIR) fail("no such file");
    if (error == EACCES || error == EPERM) fail("no read permission");
    if (error == EMFILE || error == ENFILE || error == ENOMEM || error == EIO) machine_failed(error);
    fail(std::strerror(error));
  };
  // The kind first, so that a FIFO or a device is never opened at all.
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) open_failed(errno);
  if (!S_ISREG(status.st_mode)) fail("it is " + KindOfMode(status.st_mode) + ", not a file");
  Descriptor in{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (in.fd < 0) open_failed(errno);
  // The descriptor's own kind: the path may have been replaced since stat.
  if (::fstat(in.fd, &status) != 0) machine_failed(errno);
  if (!S_ISREG(status.st_mode)) fail("it is " + KindOfMode(status.st_mode) + ", not a file");
  if (static_cast<std::uintmax_t>(status.st_size) > kMaxInputFileBytes) fail("larger than 1 GiB");
  std::string text;
  text.reserve(static_cast<std::size_t>(status.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(in.fd, buffer, sizeof buffer);
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR) continue;
      if (errno == EISDIR) fail("it is a folder, not a file");
      machine_failed(errno);
    }
    // A file that grows while it is read is bounded all the same.
    if (text.size() + static_cast<std::size_t>(got) > kMaxInputFileBytes) fail("larger than 1 GiB");
    text.append(buffer, static_cast<std::size_t>(got));
  }
  return text;
}

}  // namespace beamid
