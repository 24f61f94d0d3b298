// matio and the HDF5 C library keep global state (error stacks, log
// functions, open-object tables) and are built without thread safety: every
// call into them, from any .mat or HDF5 file (signal/array_file.h), holds
// this one lock.
#pragma once

#include <mutex>

namespace beamid::signal::internal {

inline std::mutex& ArrayLibraryLock() {
  static std::mutex lock;
  return lock;
}

}  // namespace beamid::signal::internal
