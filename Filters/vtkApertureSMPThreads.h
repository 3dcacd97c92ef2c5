// SPDX-License-Identifier: BSD-3-Clause
// Internal (not installed, not wrapped): the vtkSMPTools::LocalScope configuration for a
// filter's or writer's NumberOfThreads property, and a tally of the threads that ran.
#ifndef vtkApertureSMPThreads_h
#define vtkApertureSMPThreads_h

#include "ApertureFiltersModule.h" // for the export macro
#include "vtkSMPTools.h"

#include "ap_memory.h"

#include <algorithm>
#include <mutex>
#include <set>
#include <string>
#include <system_error>
#include <thread>
#include <utility>

/** Cores this process may run on (at least 1): the machine's, or fewer where its affinity
 *  mask or its control group's CPU quota allows fewer (ap_cpu_usable: a container run with
 *  --cpus or --cpuset-cpus, taskset). */
inline int vtkApertureCores()
{
  return std::max(1, ap_cpu_usable());
}

/** A LocalScope configuration that runs on `requested` threads: 0 = all cores, larger counts
 *  capped at the cores. On vtkSMPTools' STDThread backend, whatever the default: the TBB
 *  backend of Debian's VTK 9.1 honours a LocalScope's thread count only when it differs from
 *  the previous scope's (a second LocalScope(1) in a process runs on every core), and its
 *  GetEstimatedNumberOfThreads() then reports that count, not the cores. One thread runs on
 *  the Sequential backend: in the calling thread, starting none (STDThread would start one,
 *  and its std::thread throws std::system_error when the system refuses it). */
inline vtkSMPTools::Config vtkApertureSMPConfig(int requested)
{
  const int cores = vtkApertureCores();
  const int n = requested > 0 ? std::min(requested, cores) : cores;
  return vtkSMPTools::Config{ n, n == 1 ? "Sequential" : "STDThread", false };
}

/** The one lock of the process's Aperture SMP scopes (vtkApertureSMPScope): one for the
 *  filters and the writers alike, in the Filters library. Recursive: a progress observer
 *  within a scope may update another filter on the same thread, whose scope nests (and
 *  restores in order); try_lock of a plain mutex its thread holds is undefined behaviour. */
APERTUREFILTERS_EXPORT std::recursive_mutex& vtkApertureSMPScopeMutex();

/** f() within vtkSMPTools::LocalScope(config) when no other Aperture scope is running in the
 *  process, else within the configuration in force. LocalScope sets the process-wide SMP
 *  configuration and restores the one it found: two overlapping from different threads
 *  (pipelines updated in parallel) restored in the wrong order, and left every VTK filter of
 *  the process on one's configuration for good (Sequential, one thread). Results do not depend
 *  on the threads; only the speed of a scope run within another's does. */
template <typename F>
void vtkApertureSMPScope(const vtkSMPTools::Config& config, F&& f)
{
  std::unique_lock<std::recursive_mutex> lock(vtkApertureSMPScopeMutex(), std::try_to_lock);
  if (lock.owns_lock())
  {
    // The scope's backend is made the active one first: VTK 9.1's LocalScope gives its thread
    // count to the backend active before it (Initialize, then SetBackend) and restores the
    // count on the scope's own, so that Debian's default TBB backend kept a NumberOfThreads
    // below the cores (its thread limit and GetEstimatedNumberOfThreads) for the rest of the
    // process. Switched back afterwards, which also refreshes its count to the one restored.
    struct Backend
    {
      const std::string Previous = vtkSMPTools::GetBackend();
      ~Backend() { vtkSMPTools::SetBackend(this->Previous.c_str()); }
    } restore;
    vtkSMPTools::SetBackend(config.Backend.c_str());
    vtkSMPTools::LocalScope(config, std::forward<F>(f));
  }
  else
  {
    f();
  }
}

/** Why an operation on `threads` threads failed when the system refused to start one (the
 *  STDThread backend's std::thread threw `e`), in words the command line maps to --threads. */
inline std::string vtkApertureThreadsRefused(int threads, const std::system_error& e)
{
  return "could not start " + std::to_string(threads) + " threads (" + e.what() +
    "); use fewer threads (NumberOfThreads; 1 starts none)";
}

/** The distinct threads that ran an operation's parallel chunks: Note() at the start of each
 *  chunk (a lock per chunk), Count() afterwards. */
class vtkApertureThreadTally
{
public:
  void Note()
  {
    const std::lock_guard<std::mutex> lock(this->Mutex);
    this->Ids.insert(std::this_thread::get_id());
  }
  int Count()
  {
    const std::lock_guard<std::mutex> lock(this->Mutex);
    return static_cast<int>(this->Ids.size());
  }

private:
  std::mutex Mutex;
  std::set<std::thread::id> Ids;
};

#endif
