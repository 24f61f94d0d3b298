#include "solver/workflow/output_paths.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "hb/errors.h"
#include "hb/text_file.h"

namespace beamid::workflow {
namespace {

namespace fs = std::filesystem;

// Absolute, links resolved as far as the path exists, no trailing separator.
fs::path Resolve(const fs::path& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  if (error) absolute = path;
  fs::path resolved = fs::weakly_canonical(absolute, error);
  if (error) resolved = absolute.lexically_normal();
  if (!resolved.has_filename() && resolved.has_parent_path() && resolved != resolved.root_path())
    resolved = resolved.parent_path();
  return resolved;
}

// Whether path is folder or lies below it.
bool IsWithin(const fs::path& path, const fs::path& folder) {
  const auto [end_of_folder, unused] = std::mismatch(folder.begin(), folder.end(), path.begin(), path.end());
  return end_of_folder == folder.end();
}

// The same file under two names (a hard link, a bind mount).
bool SameFile(const fs::path& a, const fs::path& b) {
  std::error_code error;
  return fs::equivalent(a, b, error) && !error;
}

std::string Quoted(const std::string& option, const fs::path& path) { return option + " " + path.string(); }

// Proves that a file can be created in folder (created first when missing).
void RequireWritableFolder(const std::string& option, const fs::path& output, const fs::path& folder) {
  std::error_code error;
  if (!folder.empty()) fs::create_directories(folder, error);
  const fs::path probe = (folder.empty() ? fs::path(".") : folder) / (".beamid-probe-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOCTTY, 0600);
  if (fd < 0)
    throw InputError(Quoted(option, output) + ": cannot write there (" + std::strerror(errno) +
                     "): check the folder and its permissions");
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace

OutputPaths& OutputPaths::Input(const fs::path& file) {
  if (!file.empty()) input_files_.push_back(file);
  return *this;
}

OutputPaths& OutputPaths::InputFolder(const fs::path& folder) {
  if (!folder.empty()) input_folders_.push_back(folder);
  return *this;
}

OutputPaths& OutputPaths::Output(const std::string& option, const fs::path& file) {
  outputs_.push_back({option, file, false});
  return *this;
}

OutputPaths& OutputPaths::OutputPrefix(const std::string& option, const std::string& prefix,
                                       std::initializer_list<std::string_view> suffixes) {
  if (prefix.empty()) {
    outputs_.push_back({.option = option, .prefix = true});
    return *this;
  }
  for (std::string_view suffix : suffixes)
    outputs_.push_back({option + " (PREFIX" + std::string(suffix) + ")", prefix + std::string(suffix), false});
  return *this;
}

OutputPaths& OutputPaths::OutputFolder(const std::string& option, const fs::path& folder) {
  outputs_.push_back({option, folder, true});
  return *this;
}

void OutputPaths::Check() const {
  std::vector<fs::path> resolved_outputs;
  for (const Named& output : outputs_) {
    if (output.path.empty())
      throw InputError(output.option + " is empty: give the " +
                       (output.prefix ? "prefix of the files" : output.folder ? "name of a folder" : "name of a file") +
                       " to write");
    const fs::path target = Resolve(output.path);
    for (const fs::path& input : input_files_)
      if (Resolve(input) == target || SameFile(input, output.path))
        throw InputError(Quoted(output.option, output.path) + " is also an input of this command (" + input.string() +
                         "): choose another name (beamid never overwrites what it reads)");
    for (const fs::path& folder : input_folders_) {
      if (IsWithin(target, Resolve(folder)) || SameFile(folder, output.path))
        throw InputError(Quoted(output.option, output.path) + " lies inside " + folder.string() +
                         ", which is also an input of this command (every file there is read): write elsewhere");
    }
    if (output.folder) {
      for (const auto* inputs : {&input_files_, &input_folders_})
        for (const fs::path& input : *inputs)
          if (IsWithin(Resolve(input), target))
            throw InputError(Quoted(output.option, output.path) + " holds " + input.string() +
                             ", which this command reads: give another folder");
    }
    for (std::size_t i = 0; i < resolved_outputs.size(); ++i)
      if (resolved_outputs[i] == target || SameFile(outputs_[i].path, output.path))
        throw InputError(Quoted(output.option, output.path) + " is also " + Quoted(outputs_[i].option, outputs_[i].path) +
                         ": give each output its own name");
    resolved_outputs.push_back(target);
    const std::string kind = FileKind(output.path);
    if (output.folder) {
      if (kind != "missing" && kind != "a folder")
        throw InputError(Quoted(output.option, output.path) + " is " + (kind.empty() ? "a file" : kind) +
                         ", not a folder: give the folder to write into");
    } else if (kind == "a folder") {
      throw InputError(Quoted(output.option, output.path) + " is a folder: give a file name");
    } else if (kind != "missing" && !kind.empty() && kind != "a character device" && !kind.starts_with("unreadable")) {
      throw InputError(Quoted(output.option, output.path) + " is " + kind +
                       ", not a file: give the name of a file to write");
    }
  }
  // Only once every output passed: the checks above create nothing.
  for (const Named& output : outputs_) {
    if (output.folder)
      RequireWritableFolder(output.option, output.path, output.path);
    else if (FileKind(output.path) != "a character device")
      RequireWritableFolder(output.option, output.path, output.path.parent_path());
  }
}

}  // namespace beamid::workflow
