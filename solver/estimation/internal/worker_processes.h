// Internal: runs independent jobs in worker processes (fork), each job
// returning its result through a pipe as a serialised struct (text). Used where a
// library keeps global state that forbids threads (Ipopt's MUMPS). With one
// worker the jobs run in this process, in order.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace beamid::solver::internal {

// job(i) runs in a worker and returns a serialised struct (text, passed on
// byte for byte); collect(i, text, error, done) runs in this process as
// results arrive (error non-empty if the job threw or the worker died;
// done = results received so far).
void RunTextJobsInWorkers(int num_jobs, int num_workers, const std::function<std::string(int)>& job,
                          const std::function<void(int, const std::string&, const std::string&, int)>& collect);

}  // namespace beamid::solver::internal
