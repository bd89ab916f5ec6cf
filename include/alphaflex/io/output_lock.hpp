#pragma once
// The lock of a run's results in an output directory: OUTDIR/NAME.lock, held from the creation of
// the results writer to its end. Two runs of the same scene name writing to one directory would
// replace each other's parts, index and CSV rows (issue 24, defect 2); the second one is refused
// at start with the first one named.
//
// How: rank 0 opens NAME.lock and takes an exclusive flock(2) on it without waiting. The kernel
// releases a flock when its process dies, however it dies (SIGKILL, a node crash on a local file
// system), so a lock left by a dead run is free and is taken over; the file's text (host, PID,
// start time, command) only names the holder in the message. The lock file is removed at the end;
// a run that finds the file of a run that died says it took it over. Why flock and not a PID test:
// a PID says nothing on another host sharing the file system, and a dead process can still have a
// PID (a zombie nobody reaps); the kernel's lock is held exactly while the run's process exists
// (NFS v4 and Lustre carry flock locks between hosts).
#include <string>

namespace alphaflex {

class OutputLock {
 public:
  /// Takes the lock of `name`'s results in `outdir` (which exists). Throws OutputError naming the
  /// run that holds it (host, PID, start time, command) if another process does, or if the lock
  /// file cannot be created. `note` receives a line when a stale lock was taken over.
  OutputLock(const std::string& outdir, const std::string& name, std::string* note = nullptr);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace alphaflex
