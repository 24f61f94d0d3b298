// Reading and writing the files a user names.
//
// Writing: a whole text file or nothing. A regular file (or a new name) gets
// the text at a temporary name in the same folder, renamed to the final path
// once complete (rename is atomic within one file system): a run killed
// halfway, or a disk that fills, leaves the previous file or none, never a
// truncated one that a reader would take for complete. A character device
// (/dev/null, /dev/stdout, a terminal) is opened and written in place: a
// rename over it would replace the device node by a regular file. Any other
// kind of existing path (a folder, a FIFO, a socket, a block device) is
// refused. Every writer of beamid uses it.
// Throws InputError when the path cannot be written (missing folder, no
// permission, a folder of that name) and EnvironmentError when writing fails
// (disk full, an I/O error).
//
// Reading: regular files only. A FIFO would block the run forever and a
// device (/dev/zero) would be read until memory runs out, so the path is
// checked before it is opened and the opened descriptor again (fstat: a file
// swapped in between is caught too); the open does not block (O_NONBLOCK).
#pragma once

#include <filesystem>
#include <cstdint>
#include <string>
#include <string_view>

namespace beamid {

void WriteTextFileAtomically(const std::filesystem::path& path, std::string_view text);

// The most a file beamid reads may hold: no file of a stepped-sine test
// does; a bigger one would exhaust memory before any check could speak.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{1} << 30;  // 1 GiB

// Reads a whole regular file that a user named. Throws InputError
// "<path>: cannot read the <what> (<reason>). Fix: <fix>" when it is missing,
// not a regular file ("it is a FIFO, not a file"), not readable, or larger
// than kMaxInputFileBytes; EnvironmentError naming the file when the machine
// fails (an I/O error of the disk, too many open files, no memory).
std::string ReadTextFile(const std::filesystem::path& path, std::string_view what, std::string_view fix);

// What kind of thing a path names, for messages: "" for a regular file
// (links followed), "missing", "a folder", "a FIFO", "a character device",
// "a block device", "a socket", or "unreadable (<reason>)" when stat fails
// otherwise (no permission on a folder of the path).
std::string FileKind(const std::filesystem::path& path);

}  // namespace beamid
