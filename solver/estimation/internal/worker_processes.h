// Internal: runs independent jobs in worker processes (fork), each job
// returning its result through a pipe: a vector of doubles, or a text (a
// serialised struct) for results with more shape than that. Used where a
// library keeps global state that forbids threads (Ipopt's MUMPS). With one
// worker the jobs run in this process, in order.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace beamid::solver::internal {

// job(i) runs in a worker; collect(i, result, error, done) runs in this
// process as results arrive (error non-empty if the job threw or the worker
// died; done = results received so far).
void RunInWorkers(int num_jobs, int num_workers, const std::function<std::vector<double>(int)>& job,
                  const std::function<void(int, const std::vector<double>&, const std::string&, int)>& collect);

// The same with a text result, passed on byte for byte.
void RunTextJobsInWorkers(int num_jobs, int num_workers, const std::function<std::string(int)>& job,
                          const std::function<void(int, const std::string&, const std::string&, int)>& collect);

}  // namespace beamid::solver::internal
