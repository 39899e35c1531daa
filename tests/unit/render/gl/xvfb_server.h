// Test helper: an Xvfb child process on a free display number (-displayfd), for X11 tests.
#pragma once

#include <csignal>
#include <cstdlib>
#include <string>

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

namespace cb {

inline bool xvfbInstalled() {
  return std::system("command -v Xvfb >/dev/null 2>&1") == 0;
}

// An Xvfb child process; -displayfd makes the server pick a free display number and tell us.
class Xvfb {
 public:
  Xvfb(int width, int height) {
    int pipe_fds[2];
    if (pipe(pipe_fds) != 0) return;
    pid_ = fork();
    if (pid_ == 0) {
      close(pipe_fds[0]);
      const std::string fd = std::to_string(pipe_fds[1]);
      const std::string screen = std::to_string(width) + "x" + std::to_string(height) + "x24";
      const int devnull = open("/dev/null", O_WRONLY);
      dup2(devnull, 2);
      execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", screen.c_str(), "-nolisten",
             "tcp", "-noreset", static_cast<char*>(nullptr));
      _exit(127);
    }
    close(pipe_fds[1]);
    // Read up to the newline; the read end stays open for the server's lifetime, since Xvfb
    // writes the number and the newline separately and dies of SIGPIPE if nobody listens.
    read_fd_ = pipe_fds[0];
    std::string number;
    for (char c = 0; c != '\n';) {
      pollfd pfd{read_fd_, POLLIN, 0};
      if (poll(&pfd, 1, 20000) != 1 || read(read_fd_, &c, 1) != 1) return;
      if (c >= '0' && c <= '9') number += c;
    }
    if (!number.empty()) name_ = ":" + number;
  }
  ~Xvfb() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
    if (read_fd_ >= 0) close(read_fd_);
  }
  const std::string& name() const { return name_; }  // empty if it did not start

 private:
  pid_t pid_ = -1;
  int read_fd_ = -1;
  std::string name_;
};

}  // namespace cb
