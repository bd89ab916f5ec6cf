#include "alphaflex/io/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

#include "alphaflex/core/error.hpp"

namespace alphaflex {
namespace {

std::string host_name() {
  char h[256] = "";
  if (gethostname(h, sizeof h - 1) != 0) return "?";
  return h;
}

/// This process's command line, words separated by spaces (for the other run's message).
std::string command_line() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), out;
  for (char c : all) out += c == '\0' ? ' ' : (c == '\n' ? ' ' : c);
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

/// The lock file's text: "key value" lines.
struct Holder {
  std::string host, pid, started, command;
  static Holder read(int fd) {
    Holder h;
    std::string text(4096, '\0');
    const ssize_t n = pread(fd, text.data(), text.size(), 0);
    text.resize(n > 0 ? static_cast<size_t>(n) : 0);
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      const size_t sp = line.find(' ');
      if (sp == std::string::npos) continue;
      const std::string key = line.substr(0, sp), value = line.substr(sp + 1);
      if (key == "host") h.host = value;
      else if (key == "pid") h.pid = value;
      else if (key == "started") h.started = value;
      else if (key == "command") h.command = value;
    }
    return h;
  }
  bool empty() const { return host.empty() && pid.empty(); }
  std::string describe() const {
    std::string s = "PID " + (pid.empty() ? std::string("?") : pid) + " on host " + (host.empty() ? std::string("?") : host);
    if (!started.empty()) s += ", started " + started;
    if (!command.empty()) s += ": " + command;
    return s;
  }
};

std::string failure(const std::string& operation, const std::string& path) {
  return "cannot " + operation + ": " + path + (errno != 0 ? std::string(" (") + std::strerror(errno) + ")" : std::string());
}

}  // namespace

OutputLock::OutputLock(const std::string& outdir, const std::string& name, std::string* note)
    : path_(outdir + "/" + name + ".lock") {
  // A run that ends removes the file while holding the lock; one that opened the old file just
  // before gets a lock on a file no longer in the directory: it checks that the path is still the
  // file it locked, and tries again if not (a few rounds at most: each round another run ended).
  for (int round = 0; round < 100; ++round) {
    errno = 0;
    const int fd = open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw OutputError(failure("create the lock file", path_));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      const Holder h = Holder::read(fd);
      close(fd);
      if (e != EWOULDBLOCK) {
        errno = e;
        throw OutputError(failure("lock", path_));
      }
      throw OutputError(path_ + ": another run writes the results of '" + name + "' in this directory (" + h.describe() +
                        "); wait for it to end, or give another output directory (-o)");
    }
    struct stat mine {}, now {};
    if (fstat(fd, &mine) != 0 || stat(path_.c_str(), &now) != 0 || mine.st_ino != now.st_ino || mine.st_dev != now.st_dev) {
      close(fd);
      continue;
    }
    // Ours. A text left in it is a run that ended without removing it (killed, or its node died).
    const Holder before = Holder::read(fd);
    if (note && !before.empty())
      *note = path_ + ": the lock of a run that did not end cleanly (" + before.describe() +
              ") was taken over: no process holds it any more";
    std::ostringstream text;
    text << "host " << host_name() << "\npid " << getpid() << "\nstarted " << now_utc() << "\ncommand " << command_line() << "\n";
    const std::string s = text.str();
    errno = 0;
    if (ftruncate(fd, 0) != 0 || pwrite(fd, s.data(), s.size(), 0) != static_cast<ssize_t>(s.size())) {
      const std::string msg = failure("write the lock file", path_);
      close(fd);
      throw OutputError(msg);
    }
    fd_ = fd;
    return;
  }
  throw OutputError(path_ + ": cannot be locked (it is replaced again and again by other runs)");
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  unlink(path_.c_str());  // while holding the lock: a run that opened it will see a new file
  close(fd_);
}

}  // namespace alphaflex
