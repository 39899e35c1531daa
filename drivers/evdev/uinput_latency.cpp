#include "drivers/evdev/uinput_latency.h"

#include <fcntl.h>
#include <linux/uinput.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "drivers/core/clock.h"
#include "drivers/evdev/evdev_pen_source.h"

namespace cb {
namespace {

int64_t nowNs() {
  return MonotonicClock().nowNs();
}

void emit(int fd, uint16_t type, uint16_t code, int32_t value) {
  input_event e{};
  e.type = type;
  e.code = code;
  e.value = value;
  (void)!write(fd, &e, sizeof e);
}

int createUinputPen(std::string* error) {
  int fd = open("/dev/uinput", O_WRONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *error = std::string("/dev/uinput: ") + std::strerror(errno);
    return -1;
  }
  ioctl(fd, UI_SET_EVBIT, EV_KEY);
  ioctl(fd, UI_SET_EVBIT, EV_ABS);
  for (int key : {BTN_TOOL_PEN, BTN_TOUCH, BTN_STYLUS}) ioctl(fd, UI_SET_KEYBIT, key);
  ioctl(fd, UI_SET_PROPBIT, INPUT_PROP_DIRECT);
  auto abs = [&](uint16_t code, int32_t max, int32_t res) {
    uinput_abs_setup a{};
    a.code = code;
    a.absinfo.maximum = max;
    a.absinfo.resolution = res;
    ioctl(fd, UI_ABS_SETUP, &a);
  };
  abs(ABS_X, 44800, 200);
  abs(ABS_Y, 29600, 200);
  abs(ABS_PRESSURE, 8191, 0);
  uinput_setup setup{};
  setup.id.bustype = BUS_VIRTUAL;
  setup.id.vendor = 0x056A;  // discovered first, as a Wacom would be
  setup.id.product = 0xCB01;
  std::snprintf(setup.name, sizeof setup.name, "cloudbrush latency probe pen");
  if (ioctl(fd, UI_DEV_SETUP, &setup) != 0 || ioctl(fd, UI_DEV_CREATE) != 0) {
    *error = std::string("uinput device creation failed: ") + std::strerror(errno);
    close(fd);
    return -1;
  }
  return fd;
}

std::vector<double> pipeWakeups(int n) {
  std::vector<double> out;
  int p[2];
  if (pipe(p) != 0) return out;
  std::thread reader([&] {
    for (int i = 0; i < n; ++i) {
      int64_t sent = 0;
      pollfd pf{p[0], POLLIN, 0};
      poll(&pf, 1, 1000);
      if (read(p[0], &sent, sizeof sent) == sizeof sent) out.push_back((nowNs() - sent) / 1e3);
    }
  });
  for (int i = 0; i < n; ++i) {
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    int64_t t = nowNs();
    (void)!write(p[1], &t, sizeof t);
  }
  reader.join();
  close(p[0]);
  close(p[1]);
  return out;
}

}  // namespace

EvdevLatencyResult measureEvdevLatency(int samples, double rate_hz) {
  EvdevLatencyResult r;
  int fd = createUinputPen(&r.error);
  if (fd < 0) return r;
  // Find the node: the source discovers Wacom-vendor pens first.
  EvdevPenSource src({});
  std::vector<PenSample> got;
  const int64_t deadline = nowNs() + 3'000'000'000;
  while ((src.connection() != PenConnection::kConnected ||
          std::string(src.deviceInfo().name) != "cloudbrush latency probe pen") &&
         nowNs() < deadline)
    src.poll(20, got);
  if (std::string(src.deviceInfo().name) != "cloudbrush latency probe pen") {
    r.error = "the uinput pen did not appear in /dev/input (" + src.statusMessage() + ")";
    ioctl(fd, UI_DEV_DESTROY);
    close(fd);
    return r;
  }
  std::atomic<bool> done{false};
  std::thread consumer([&] {
    std::vector<PenSample> batch;
    while (!done) {
      batch.clear();
      src.poll(50, batch);
      const int64_t now = nowNs();
      for (const PenSample& s : batch)
        if (s.in_proximity) r.delay_us.push_back((now - s.t_ns) / 1e3);
    }
  });
  const auto period = std::chrono::nanoseconds(static_cast<int64_t>(1e9 / rate_hz));
  emit(fd, EV_KEY, BTN_TOOL_PEN, 1);
  for (int i = 0; i < samples; ++i) {
    emit(fd, EV_ABS, ABS_X, 1000 + (i % 40000));
    emit(fd, EV_ABS, ABS_PRESSURE, i % 8000);
    emit(fd, EV_SYN, SYN_REPORT, 0);
    std::this_thread::sleep_for(period);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  done = true;
  consumer.join();
  ioctl(fd, UI_DEV_DESTROY);
  close(fd);
  r.wakeup_us = pipeWakeups(samples);
  r.ran = true;
  return r;
}

}  // namespace cb
