// The version of beamid, written into every file it produces ("beamid_version")
// so that a result can always be traced to the program that made it. The
// number comes from the project() line of the top CMakeLists.txt.
#pragma once

namespace beamid {

#ifndef BEAMID_VERSION
#error "BEAMID_VERSION is defined by CMake for every target that links beamid_hb"
#endif
inline constexpr const char* kVersion = BEAMID_VERSION;

}  // namespace beamid
