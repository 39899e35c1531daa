#include "app/render/gl/display_kms_vt.h"

#include <linux/kd.h>
#include <linux/vt.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace cb {
namespace {

std::atomic<int> g_locked_fd{-1};

// VT_PROCESS: the kernel asks before switching away (release signal) and tells when the VT is
// ours again (acquire signal). A kiosk never lets go.
void onReleaseRequest(int) {
  const int saved = errno;
  const int fd = g_locked_fd.load();
  if (fd >= 0) ::ioctl(fd, VT_RELDISP, 0);
  errno = saved;
}

void onAcquire(int) {
  const int saved = errno;
  const int fd = g_locked_fd.load();
  if (fd >= 0) ::ioctl(fd, VT_RELDISP, VT_ACKACQ);
  errno = saved;
}

std::string failed(const char* what) {
  return std::string(what) + " failed: " + std::strerror(errno);
}

}  // namespace

std::unique_ptr<VtLock> VtLock::lock(int fd, std::string* why) {
  struct stat st {};
  // Virtual terminals are character devices of major 4, minors 1..63 (/dev/tty1..63).
  if (::fstat(fd, &st) != 0 || !S_ISCHR(st.st_mode) || major(st.st_rdev) != 4 ||
      minor(st.st_rdev) < 1 || minor(st.st_rdev) > 63) {
    *why = "stdin is not a virtual terminal (/dev/ttyN)";
    return nullptr;
  }
  if (g_locked_fd.load() >= 0) {
    *why = "a VT is already locked by this process";
    return nullptr;
  }
  std::unique_ptr<VtLock> vt(new VtLock);
  vt->fd_ = fd;
  vt->number_ = int(minor(st.st_rdev));
  long mode = 0;
  if (::ioctl(fd, KDGKBMODE, &mode) != 0) {
    *why = "/dev/tty" + std::to_string(vt->number_) + ": " + failed("KDGKBMODE");
    return nullptr;
  }
  vt->keyboard_mode_ = mode;
  // Bring our VT to the foreground (under the unit it may not be yet).
  vt_stat state{};
  if (::ioctl(fd, VT_GETSTATE, &state) == 0 && state.v_active != vt->number_) {
    ::ioctl(fd, VT_ACTIVATE, vt->number_);
    ::ioctl(fd, VT_WAITACTIVE, vt->number_);
  }
  struct sigaction release {
  }, acquire{};
  release.sa_handler = onReleaseRequest;
  acquire.sa_handler = onAcquire;
  release.sa_flags = acquire.sa_flags = SA_RESTART;
  sigemptyset(&release.sa_mask);
  sigemptyset(&acquire.sa_mask);
  ::sigaction(SIGUSR1, &release, nullptr);
  ::sigaction(SIGUSR2, &acquire, nullptr);
  g_locked_fd.store(fd);
  vt_mode process{};
  process.mode = VT_PROCESS;
  process.relsig = SIGUSR1;
  process.acqsig = SIGUSR2;
  const std::string where = "/dev/tty" + std::to_string(vt->number_) + ": ";
  if (::ioctl(fd, VT_SETMODE, &process) != 0) {
    *why = where + failed("VT_SETMODE VT_PROCESS");
    g_locked_fd.store(-1);
    return nullptr;
  }
  if (::ioctl(fd, KDSKBMODE, K_OFF) != 0) {
    *why = where + failed("KDSKBMODE K_OFF");
    vt_mode automatic{};
    automatic.mode = VT_AUTO;
    ::ioctl(fd, VT_SETMODE, &automatic);
    g_locked_fd.store(-1);
    return nullptr;
  }
  ::ioctl(fd, KDSETMODE, KD_GRAPHICS);  // cosmetic: no console text over the frames
  return vt;
}

VtLock::~VtLock() {
  ::ioctl(fd_, KDSETMODE, KD_TEXT);
  ::ioctl(fd_, KDSKBMODE, keyboard_mode_);
  vt_mode automatic{};
  automatic.mode = VT_AUTO;
  ::ioctl(fd_, VT_SETMODE, &automatic);
  g_locked_fd.store(-1);
}

}  // namespace cb
