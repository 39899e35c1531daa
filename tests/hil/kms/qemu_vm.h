// A qemu guest for the KMS tests: boots Debian's kernel with an initramfs on TCG, its serial
// console written to a log file the test reads line by line, its monitor on a unix socket (for
// `screendump`). Ends the guest (SIGKILL of the child it started) on destruction.
#pragma once

#include <string>
#include <vector>

namespace cb::hil {

class QemuVm {
 public:
  // `device` is the display device, e.g. "bochs-display" or "virtio-gpu-pci", with properties
  // ("bochs-display,xres=640,yres=400": a smaller mode for TCG); `work_dir` holds
  // the serial log and the monitor socket.
  QemuVm(const std::string& kernel, const std::string& initrd, const std::string& device,
         const std::string& work_dir);
  // Any guest: `name` names the serial log and monitor socket, `args` are added to qemu's (disks,
  // devices), `reboot` lets a reset or a guest reboot start the guest again (the display tests
  // end on one: -no-reboot).
  struct Options {
    std::string name;
    std::vector<std::string> args;
    bool reboot = false;
  };
  QemuVm(const std::string& kernel, const std::string& initrd, const Options& options,
         const std::string& work_dir);
  ~QemuVm();
  QemuVm(const QemuVm&) = delete;
  QemuVm& operator=(const QemuVm&) = delete;

  bool started() const { return pid_ > 0; }
  // Waits until a console line contains `marker` (returns it) or `failure` (returns it too), or
  // the timeout passes (returns ""). Every line read is kept in lines().
  std::string waitForLine(const std::string& marker, const std::string& failure,
                          int timeout_seconds);
  // The same from console line `from` on; *at (if given) is the index of the line returned.
  std::string waitForLine(const std::string& marker, const std::string& failure,
                          int timeout_seconds, size_t from, size_t* at);
  // Whether qemu is still running (reads the console so far).
  bool running();
  const std::vector<std::string>& lines() const { return lines_; }
  // Runs one monitor command and returns its output (up to the next prompt).
  bool monitor(const std::string& command, std::string* output, std::string* error);
  const std::string& serialLog() const { return serial_log_; }

 private:
  void readNewLines();

  int pid_ = -1;
  std::string serial_log_, monitor_socket_;
  size_t read_offset_ = 0;
  std::string partial_;
  std::vector<std::string> lines_;
};

// A binary PPM (P6) as written by qemu's screendump.
struct PpmImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  const unsigned char* at(int x, int y) const { return &rgb[(size_t(y) * width + x) * 3]; }
};
bool readPpm(const std::string& path, PpmImage* image, std::string* error);

// Runs a shell command, returns its exit status and stdout.
int runCommand(const std::string& command, std::string* out);

}  // namespace cb::hil
