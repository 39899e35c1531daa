#include "qemu_vm.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

namespace cb::hil {

QemuVm::QemuVm(const std::string& kernel, const std::string& initrd, const std::string& device,
               const std::string& work_dir)
    : QemuVm(kernel, initrd, Options{device, {"-vga", "none", "-device", device}, false},
             work_dir) {}

QemuVm::QemuVm(const std::string& kernel, const std::string& initrd, const Options& options,
               const std::string& work_dir) {
  // File names from the name alone ("bochs-display,xres=640" -> "bochs-display").
  const std::string name = options.name.substr(0, options.name.find(','));
  serial_log_ = work_dir + "/serial-" + name + ".log";
  monitor_socket_ = work_dir + "/monitor-" + name + ".sock";
  unlink(serial_log_.c_str());
  unlink(monitor_socket_.c_str());
  // no_timer_check: on a loaded host TCG can be too slow for the kernel's IO-APIC timer check,
  // which then panics at boot ("IO-APIC + timer doesn't work").
  std::vector<std::string> args = {"qemu-system-x86_64",
                                   "-accel",
                                   "tcg",
                                   "-m",
                                   "1024",
                                   "-smp",
                                   "2",
                                   "-display",
                                   "none",
                                   "-kernel",
                                   kernel,
                                   "-initrd",
                                   initrd,
                                   "-append",
                                   "console=ttyS0 quiet panic=-1 no_timer_check",
                                   "-serial",
                                   "file:" + serial_log_,
                                   "-monitor",
                                   "unix:" + monitor_socket_ + ",server,nowait",
                                   "-nodefaults"};
  if (!options.reboot) args.push_back("-no-reboot");
  args.insert(args.end(), options.args.begin(), options.args.end());
  pid_ = fork();
  if (pid_ == 0) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int devnull = open("/dev/null", O_RDWR);
    dup2(devnull, 0);
    execvp(argv[0], argv.data());
    _exit(127);
  }
}

QemuVm::~QemuVm() {
  if (pid_ > 0) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  unlink(monitor_socket_.c_str());
}

void QemuVm::readNewLines() {
  std::ifstream in(serial_log_, std::ios::binary);
  if (!in) return;
  in.seekg(std::streamoff(read_offset_));
  std::string chunk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  read_offset_ += chunk.size();
  for (char c : chunk) {
    if (c == '\n') {
      if (!partial_.empty() && partial_.back() == '\r') partial_.pop_back();
      lines_.push_back(partial_);
      partial_.clear();
    } else {
      partial_ += c;
    }
  }
}

std::string QemuVm::waitForLine(const std::string& marker, const std::string& failure,
                                int timeout_seconds) {
  return waitForLine(marker, failure, timeout_seconds, 0, nullptr);
}

bool QemuVm::running() {
  int status = 0;
  if (pid_ > 0 && waitpid(pid_, &status, WNOHANG) == pid_) pid_ = -1;
  readNewLines();
  return pid_ > 0;
}

std::string QemuVm::waitForLine(const std::string& marker, const std::string& failure,
                                int timeout_seconds, size_t from, size_t* at) {
  size_t checked = from;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    readNewLines();
    for (; checked < lines_.size(); ++checked) {
      const std::string& line = lines_[checked];
      if (line.find(marker) != std::string::npos ||
          (!failure.empty() && line.find(failure) != std::string::npos)) {
        if (at) *at = checked;
        return line;
      }
    }
    int status = 0;
    if (pid_ > 0 && waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;  // the guest powered off; read what is left once more
      readNewLines();
      for (; checked < lines_.size(); ++checked)
        if (lines_[checked].find(marker) != std::string::npos) {
          if (at) *at = checked;
          return lines_[checked];
        }
      return "";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return "";
}

bool QemuVm::monitor(const std::string& command, std::string* output, std::string* error) {
  const int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  snprintf(address.sun_path, sizeof(address.sun_path), "%s", monitor_socket_.c_str());
  if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    *error = "cannot connect to the qemu monitor at " + monitor_socket_;
    close(fd);
    return false;
  }
  // Reads until the "(qemu) " prompt; `prompts` counts how many to wait for.
  auto read_prompt = [&](std::string* text) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < deadline) {
      pollfd pfd{fd, POLLIN, 0};
      if (poll(&pfd, 1, 200) == 1) {
        char buf[4096];
        const ssize_t n = read(fd, buf, sizeof(buf));
        if (n <= 0) return false;
        text->append(buf, size_t(n));
        if (text->find("(qemu) ") != std::string::npos) return true;
      }
    }
    return false;
  };
  std::string banner;
  bool ok = read_prompt(&banner);
  const std::string line = command + "\n";
  ok = ok && write(fd, line.data(), line.size()) == ssize_t(line.size());
  std::string reply;
  ok = ok && read_prompt(&reply);
  close(fd);
  if (!ok) *error = "the qemu monitor did not answer '" + command + "'";
  if (output) *output = reply;
  return ok;
}

bool readPpm(const std::string& path, PpmImage* image, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int maxval = 0;
  if (!(in >> magic >> image->width >> image->height >> maxval) || magic != "P6" || maxval != 255 ||
      image->width <= 0 || image->height <= 0) {
    *error = path + ": not an 8-bit binary PPM";
    return false;
  }
  in.get();  // the single whitespace after maxval
  image->rgb.resize(size_t(image->width) * image->height * 3);
  if (!in.read(reinterpret_cast<char*>(image->rgb.data()), std::streamsize(image->rgb.size()))) {
    *error = path + ": truncated pixel data";
    return false;
  }
  return true;
}

int runCommand(const std::string& command, std::string* out) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), pipe)) > 0) out->append(buf, n);
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace cb::hil
