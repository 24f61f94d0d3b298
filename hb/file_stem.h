// A file name made of a text the user wrote (a level's label, a channel's
// name, a figure's id), for the files beamid writes one per item: letters,
// digits, '-', '_' and '.' are kept, any other byte becomes '_'; a name
// that would start with '.' or '-' (a hidden file, an option) gets `prefix`
// in front; at most 120 bytes. "1,5 N" gives "1_5_N", "../x" gives ".._x"
// after the prefix ("plot_.._x"): never a path.
#pragma once

#include <set>
#include <string>

namespace beamid::hb {

std::string FileStem(const std::string& text, const std::string& prefix);

// FileStem, then "-2", "-3", ... until it is not in `taken`; adds it there.
std::string UniqueFileStem(const std::string& text, const std::string& prefix, std::set<std::string>& taken);

}  // namespace beamid::hb
