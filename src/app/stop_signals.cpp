#include "alphaflex/app/stop_signals.hpp"

#include <csignal>
#include <cstring>
#include <initializer_list>
#include <unistd.h>

namespace alphaflex {
namespace {

volatile std::sig_atomic_t received = 0;

extern "C" void on_stop_signal(int sig) {
  if (received != 0 && (sig == SIGINT || sig == SIGTERM)) _exit(128 + sig);  // the second one: at once
  received = sig;
}

}  // namespace

void install_stop_signals() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // system calls in progress (file writes, MPI) go on
  for (int sig : {SIGTERM, SIGINT, SIGUSR1}) sigaction(sig, &sa, nullptr);
}

int stop_signal() { return received; }

const char* signal_name(int sig) {
  switch (sig) {
    case SIGTERM: return "SIGTERM";
    case SIGINT: return "SIGINT";
    case SIGUSR1: return "SIGUSR1";
    default: return "a signal";
  }
}

}  // namespace alphaflex
