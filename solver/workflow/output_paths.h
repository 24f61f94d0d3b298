// The one rule every command applies to what it writes, before any work:
// an output never replaces what the command reads, never a device node,
// never another output of the same run.
//
// A command lists what it reads (files; folders, every file under which
// counts as read: a campaign folder) and every path it will write (the -o
// file, the companions of an -o prefix such as PREFIX.csv and PREFIX.json,
// --csv, --curves' .csv/.gp/.png, --screenshot, a folder it fills). Check()
// resolves each (links followed, `..` removed: weakly_canonical) and throws
// InputError (exit 2) naming the option when an output
//   - is empty;
//   - equals an input file (the same path or the same file by another name,
//     a hard link), or lies inside a folder the command reads (write
//     elsewhere: a campaign folder holds only the campaign);
//   - holds an input (a folder the command fills that contains what it reads);
//   - equals another output of the same run (-o X --csv X);
//   - exists and is neither a regular file nor a character device (a folder,
//     a FIFO, a socket, a block device), or for a folder output, exists and
//     is not a folder.
// Character devices (/dev/null, /dev/stdout) are allowed: the writer
// (hb/text_file.h) writes them in place. Check() also creates each output's
// folder and proves it writable, so that a run is refused at once rather
// than after minutes of work.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace beamid::workflow {

class OutputPaths {
 public:
  // A file the command reads (ignored when empty: an option not given).
  OutputPaths& Input(const std::filesystem::path& file);
  // A folder the command reads: everything under it is an input.
  OutputPaths& InputFolder(const std::filesystem::path& folder);
  // A file the command writes; option names it in messages ("-o", "--csv",
  // "--curves (PREFIX.png)").
  OutputPaths& Output(const std::string& option, const std::filesystem::path& file);
  // The files PREFIX + suffix of an option that takes a prefix ("-o" for
  // PREFIX.csv and PREFIX.json); an empty prefix is refused as such.
  OutputPaths& OutputPrefix(const std::string& option, const std::string& prefix,
                            std::initializer_list<std::string_view> suffixes);
  // A folder the command creates and fills.
  OutputPaths& OutputFolder(const std::string& option, const std::filesystem::path& folder);

  // Throws InputError on the first output that breaks the rule above.
  void Check() const;

 private:
  struct Named {
    std::string option;
    std::filesystem::path path;
    bool folder = false;
    bool prefix = false;  // an empty prefix, given as such
  };
  std::vector<std::filesystem::path> input_files_;
  std::vector<std::filesystem::path> input_folders_;
  std::vector<Named> outputs_;
};

}  // namespace beamid::workflow
