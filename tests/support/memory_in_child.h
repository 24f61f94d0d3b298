// The memory a call takes, measured in a forked child so that nothing the
// test process held before counts: the child's resident peak (getrusage
// ru_maxrss) minus its resident size when it starts, and, outside
// AddressSanitizer (whose shadow reserves terabytes of address space), an
// address-space limit of its size at the start plus the budget, so that a
// reservation beyond the budget fails (std::bad_alloc) even where its pages
// would never be touched and never count as resident.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstddef>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <new>
#include <string>

namespace beamid::testing {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

struct ChildMemory {
  bool ran = false;             // the child reported back
  long long growth_bytes = -1;  // resident peak minus resident size at the start
  std::string text;             // what the call returned, or the exception that escaped it
};

namespace internal {

// Virtual and resident size of this process [bytes] (/proc/self/statm).
inline void ProcessSize(long long& virtual_bytes, long long& resident_bytes) {
  std::ifstream statm("/proc/self/statm");
  long long pages_virtual = 0, pages_resident = 0;
  statm >> pages_virtual >> pages_resident;
  const long long page = ::sysconf(_SC_PAGESIZE);
  virtual_bytes = pages_virtual * page;
  resident_bytes = pages_resident * page;
}

}  // namespace internal

// Runs `call` in a forked child with `budget_bytes` of memory beyond what it
// starts with; `call` returns what the test is to check (an error message).
inline ChildMemory MemoryInChild(long long budget_bytes, const std::function<std::string()>& call) {
  int channel[2];
  if (::pipe(channel) != 0) return {};
  const pid_t child = ::fork();
  if (child < 0) return {};
  if (child == 0) {
    ::close(channel[0]);
    long long start_virtual = 0, start_resident = 0;
    internal::ProcessSize(start_virtual, start_resident);
    if (!kAddressSanitizer) {
      const rlimit limit{static_cast<rlim_t>(start_virtual + budget_bytes),
                         static_cast<rlim_t>(start_virtual + budget_bytes)};
      ::setrlimit(RLIMIT_AS, &limit);
    }
    std::string text;
    try {
      text = call();
    } catch (const std::bad_alloc&) {
      text = "std::bad_alloc: more memory than the budget";
    } catch (const std::exception& e) {
      text = std::string("unexpected exception: ") + e.what();
    } catch (...) {
      text = "unexpected exception";
    }
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    const std::string report = std::to_string(usage.ru_maxrss * 1024LL - start_resident) + "\n" + text;
    for (std::size_t written = 0; written < report.size();) {
      const ssize_t n = ::write(channel[1], report.data() + written, report.size() - written);
      if (n <= 0) break;
      written += static_cast<std::size_t>(n);
    }
    ::_exit(0);
  }
  ::close(channel[1]);
  std::string report;
  char buffer[4096];
  for (ssize_t n; (n = ::read(channel[0], buffer, sizeof buffer)) > 0;)
    report.append(buffer, static_cast<std::size_t>(n));
  ::close(channel[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  ChildMemory result;
  const std::size_t end = report.find('\n');
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || end == std::string::npos) return result;
  result.ran = true;
  result.growth_bytes = std::stoll(report.substr(0, end));
  result.text = report.substr(end + 1);
  return result;
}

}  // namespace beamid::testing
