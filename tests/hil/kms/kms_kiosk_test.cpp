// The exhibition kiosk end to end in one qemu boot (labels hil + slow, ≈ 10 min on TCG): Debian's
// kernel with a bochs display card (640x400, so llvmpipe under TCG keeps up), its PS/2 keyboard
// fed by the monitor's `sendkey`, and a Wacom tablet made through /dev/uhid (the kernel's own
// wacom driver). The guest runs kiosk_guest.sh; this test plays the visitor's keyboard and checks:
//   - control: without the kiosk, Ctrl+Alt+F2 switches VT 1 → VT 2 (so the check below can fail);
//   - `cloudbrush kiosk --display kms` locks its VT, shows the attract loop by page flip (two
//     screendumps differ: the camera orbits) and, with the kiosk running, Ctrl+Alt+F2 leaves
//     /sys/class/tty/tty0/active at tty1;
//   - the mode keys 1–5 reach the painter through the KMS keyboard path (evdev + keymap):
//     3, 1 and 4 change the mode (paint, camera, erase), 2 and 5 are refused in visitor mode; Esc,
//     q, Ctrl+C, Alt+F4, Ctrl+Alt+Backspace and Ctrl+Alt+Delete do not end the kiosk (or reboot the
//     guest);
//   - the tablet plugged in 20 times during the attract loop and 20 times mid-visit: every time
//     the first pen sample reaches the screen showing (attract / visitor), measured from the
//     uhid device's creation (the figure; ≤ 1 s wanted), and the strokes are painted; when the
//     frame after that sample was presented is printed beside it (not held to the 1 s);
//   - the kiosk ends on SIGTERM with its last page flip reported.
// Screendumps are kept in <build>/tests/hil/kms/work/kiosk/kiosk-*.ppm for looking.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "qemu_vm.h"

// The visitor texts' font (app/shell/ui_overlay.cpp), so the guest's screens show their words.
#define CB_UI_FONT "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc"

namespace cb::hil {
namespace {

std::string fetchKernel(std::string* vmlinuz, std::string* cache_dir) {
  const char* env = std::getenv("CB_HIL_CACHE");
  const std::string cache = env && *env ? env : CB_HIL_CACHE;
  *cache_dir = cache;
  std::string out, moddir;
  runCommand("bash " CB_SOURCE_DIR "/tests/hil/common/fetch_kernel.sh '" + cache + "'", &out);
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("VMLINUZ=", 0) == 0) *vmlinuz = line.substr(8);
    if (line.rfind("MODDIR=", 0) == 0) moddir = line.substr(7);
  }
  return moddir;
}

double meanBrightness(const PpmImage& image) {
  double sum = 0.0;
  for (unsigned char c : image.rgb) sum += c;
  return image.rgb.empty() ? 0.0 : sum / double(image.rgb.size());
}

double meanDifference(const PpmImage& a, const PpmImage& b) {
  if (a.rgb.size() != b.rgb.size() || a.rgb.empty()) return -1.0;
  double sum = 0.0;
  for (size_t i = 0; i < a.rgb.size(); ++i) sum += std::abs(int(a.rgb[i]) - int(b.rgb[i]));
  return sum / double(a.rgb.size());
}

void sleepSeconds(double s) {
  std::this_thread::sleep_for(std::chrono::milliseconds(long(s * 1000)));
}

// Everything the guest's serial console said so far, a line a line.
std::string consoleText(QemuVm& vm) {
  std::string text;
  for (const std::string& l : vm.lines()) text += l + "\n";
  return text;
}

// The initramfs: the kiosk, its configuration and font, the pen hotplug tool and the guest script.
void makeInitrd(const std::string& cache, const std::string& initrd) {
  std::string log;
  ASSERT_EQ(runCommand("CB_KMS_WITH_LIBS=1 CB_KMS_MODULES='evdev uhid wacom hid-generic' "
                       "CB_KMS_FILES='" CB_SOURCE_DIR "/config:/config " CB_UI_FONT ":" CB_UI_FONT
                       "' bash " CB_SOURCE_DIR "/tests/hil/kms/make_kms_initramfs.sh '" +
                           cache + "' '" + initrd + "' 'sh /bin/kiosk_guest.sh' '" +
                           CB_CLOUDBRUSH_BIN "' '" CB_KIOSK_PEN_HOTPLUG "' '" CB_SOURCE_DIR
                                             "/tests/hil/kms/kiosk_guest.sh' '" CB_HID_FIXTURE_DIR
                                             "/wacom-pth660_v145.rdesc' 2>&1",
                       &log),
            0)
      << log;
}

// 1. Control: the same key with no kiosk running does switch.
void checkControlSwitches(QemuVm& vm) {
  std::string reply, error;
  ASSERT_NE(vm.waitForLine("KIOSK-HIL control-ready", "Kernel panic", 240).find("ready tty1"),
            std::string::npos)
      << consoleText(vm);
  ASSERT_TRUE(vm.monitor("sendkey ctrl-alt-f2", &reply, &error)) << error;
  const std::string control = vm.waitForLine("KIOSK-HIL control-after", "Kernel panic", 120);
  EXPECT_NE(control.find("tty2"), std::string::npos)
      << "without the kiosk Ctrl+Alt+F2 should switch to VT 2: " << control;
  ASSERT_NE(vm.waitForLine("KIOSK-HIL back", "", 60).find("tty1"), std::string::npos)
      << consoleText(vm);
}

// 2. The kiosk: its VT locked, the attract loop by page flip.
void checkAttractByPageFlip(QemuVm& vm, const std::string& work) {
  std::string reply, error;
  ASSERT_FALSE(vm.waitForLine("KIOSK-HIL kiosk-up", "Kernel panic", 600).empty())
      << consoleText(vm);
  EXPECT_NE(consoleText(vm).find("cloudbrush: kms: VT 1 locked"), std::string::npos)
      << consoleText(vm);
  // Screendumps 5 s apart until two differ (the first frames take a while under TCG).
  const std::string shot_a = work + "/kiosk-attract-a.ppm", shot_b = work + "/kiosk-attract-b.ppm";
  PpmImage a, b;
  double brightness = 0.0, change = 0.0;
  ASSERT_TRUE(vm.monitor("screendump " + shot_a, &reply, &error)) << error;
  ASSERT_TRUE(readPpm(shot_a, &a, &error)) << error;
  for (int tries = 0; tries < 60 && !(change > 0.2 && brightness > 20.0); ++tries) {
    sleepSeconds(5.0);
    ASSERT_TRUE(vm.monitor("screendump " + shot_b, &reply, &error)) << error;
    ASSERT_TRUE(readPpm(shot_b, &b, &error)) << error;
    brightness = meanBrightness(b);
    change = meanDifference(a, b);
    if (!(change > 0.2 && brightness > 20.0)) std::rename(shot_b.c_str(), shot_a.c_str()), a = b;
  }
  EXPECT_EQ(b.width, 640);
  EXPECT_EQ(b.height, 400);
  std::printf("attract screendumps: mean brightness %.1f/255, mean change over 5 s %.2f/255\n",
              brightness, change);
  EXPECT_GT(brightness, 20.0) << "the attract loop is on the screen, not a black card";
  EXPECT_GT(change, 0.2) << "the attract loop's frames reach the screen by page flip";
}

// 3. Ctrl+Alt+F2 with the kiosk running (the VT must stay), Space (a visitor), then the
//    mode keys, then the quit combinations.
void checkVtLockedAndKeys(QemuVm& vm) {
  std::string reply, error;
  const size_t before_keys = vm.lines().size();
  ASSERT_TRUE(vm.monitor("sendkey ctrl-alt-f2", &reply, &error)) << error;
  // F2 means nothing to the kiosk (the guest has no xkb-data: the built-in US table has no F
  // keys); Space hands the attract loop to a visitor.
  sleepSeconds(2.0);
  ASSERT_TRUE(vm.monitor("sendkey spc", &reply, &error)) << error;
  ASSERT_FALSE(vm.waitForLine("KIOSK-LOG cloudbrush kiosk: visitor 1 painting", "", 300).empty())
      << consoleText(vm);
  // One key at a time, each after the kiosk said the last one: under TCG a frame takes seconds,
  // and keys sent faster overflow the kernel's evdev buffer (all queued events are dropped).
  // 3 first: a visitor starts in Camera mode, where 1 changes nothing (and says nothing).
  for (const auto& [key, said] : std::vector<std::pair<std::string, std::string>>{
           {"3", "KIOSK-LOG cloudbrush: paint"},
           {"1", "KIOSK-LOG cloudbrush: camera"},
           {"4", "KIOSK-LOG cloudbrush: erase"},
           {"2", "That key is for the operator / 该按键仅供操作员使用 (2)"},
           {"5", "That key is for the operator / 该按键仅供操作员使用 (5)"},
           {"esc", "That key is for the operator / 该按键仅供操作员使用 (Esc)"}}) {
    ASSERT_TRUE(vm.monitor("sendkey " + key, &reply, &error)) << error;
    EXPECT_FALSE(vm.waitForLine(said, "", 120).empty()) << key << ": " << consoleText(vm);
  }
  for (const char* key : {"q", "ctrl-c", "alt-f4", "ctrl-alt-backspace", "ctrl-alt-delete"}) {
    ASSERT_TRUE(vm.monitor(std::string("sendkey ") + key, &reply, &error)) << error;
    sleepSeconds(2.0);
  }
  ASSERT_FALSE(vm.waitForLine("KIOSK-HIL keys-seen", "Kernel panic", 300).empty())
      << consoleText(vm);
  sleepSeconds(4.0);
  vm.waitForLine("KIOSK-HIL never", "", 1);  // read what arrived
  long active_lines = 0, switched = 0;
  for (size_t i = before_keys; i < vm.lines().size(); ++i) {
    const std::string& l = vm.lines()[i];
    if (l.rfind("KIOSK-HIL active ", 0) != 0) continue;
    ++active_lines;
    switched += l != "KIOSK-HIL active tty1";
  }
  std::printf("after Ctrl+Alt+F2 with the kiosk running: %ld active-VT readings, %ld not tty1\n",
              active_lines, switched);
  EXPECT_GE(active_lines, 3) << consoleText(vm);
  EXPECT_EQ(switched, 0) << "Ctrl+Alt+F2 switched the VT away from the kiosk";
  const std::string text = consoleText(vm);
  EXPECT_NE(text.find("That key is for the operator / 该按键仅供操作员使用 (Esc)"),
            std::string::npos)
      << text;
}

// 4. The tablet: 20 plugs during the attract loop, 20 mid-visit, then SIGTERM: the kiosk ended
// as asked (`all`: the console).
void checkKioskEnded(QemuVm& vm, std::string* all) {
  const std::string exit_line = vm.waitForLine("KIOSK-HIL kiosk-exit", "Kernel panic", 1500);
  *all = consoleText(vm);
  ASSERT_NE(exit_line.find("kiosk-exit 0"), std::string::npos) << *all;
  EXPECT_NE(all->find("(signal)"), std::string::npos) << "ended by SIGTERM only: " << *all;
  EXPECT_NE(all->find("cloudbrush: last page flip: vblank sequence"), std::string::npos) << *all;
  EXPECT_EQ(all->find("KIOSK-PEN FAIL"), std::string::npos) << *all;
  EXPECT_EQ(all->find("KIOSK-PEN unseen"), std::string::npos) << *all;
  // The kiosk's mean loop iteration in the guest (llvmpipe under TCG: seconds, not the ~30 ms of
  // real hardware): a new device is found by one iteration's poll and shown by the next.
  long frames = 0;
  double loop_seconds = 0.0;
  if (const size_t k = all->rfind(" frames in "); k != std::string::npos)
    std::sscanf(all->c_str() + all->rfind("cloudbrush: ", k), "cloudbrush: %ld frames in %lf s",
                &frames, &loop_seconds);
  const double frame_s = frames > 0 ? loop_seconds / double(frames) : 0.0;
  std::printf("the kiosk in the guest: %ld frames in %.1f s (%.2f s per frame)\n", frames,
              loop_seconds, frame_s);
  ASSERT_GT(frames, 0) << *all;
}

// A tablet plug: when uhid made it, when its first sample reached the screen (and which), when
// the frame after it was presented (-1: never).
struct Plug {
  std::string label;
  double created = 0.0, reached = -1.0, shown = -1.0;
  std::string screen;
};

// Pairs each uhid creation with the kiosk's next "first sample since it connected" line.
std::vector<Plug> pairPlugs(const std::vector<std::string>& lines) {
  std::vector<Plug> plugs;
  for (const std::string& l : lines) {
    char label[32];
    int index = 0;
    double t = 0.0;
    if (std::sscanf(l.c_str(), "KIOSK-PEN created %31s %d %lf", label, &index, &t) == 3) {
      plugs.push_back({label, t, -1.0, -1.0, ""});
      continue;
    }
    // The frame drawn after that sample (what the visitor sees answer the pen).
    const size_t f = l.find("cloudbrush kiosk: pen: the first frame after that sample");
    if (f != std::string::npos && !plugs.empty() && plugs.back().reached >= 0.0 &&
        plugs.back().shown < 0.0) {
      const size_t at = l.find("presented at ", f);
      if (at != std::string::npos) plugs.back().shown = std::atof(l.c_str() + at + 13);
      continue;
    }
    const size_t k = l.find("cloudbrush kiosk: pen: first sample since it connected");
    if (k == std::string::npos || plugs.empty() || plugs.back().reached >= 0.0) continue;
    char screen[32];
    double event = 0.0, reached = 0.0;
    if (std::sscanf(l.c_str() + k,
                    "cloudbrush kiosk: pen: first sample since it connected (event at %lf s) "
                    "reached the %31s screen at %lf s",
                    &event, screen, &reached) == 3) {
      plugs.back().reached = reached;
      plugs.back().screen = screen;
    }
  }
  return plugs;
}

// The plugs of one phase (`label`: attract or visit): every one reached the expected screen
// within the 1 s.
void checkPlugs(const std::vector<Plug>& plugs, const char* label, const std::string& all) {
  std::vector<double> delays, shown;
  long on_expected_screen = 0, index = 0;
  for (const Plug& p : plugs) {
    if (p.label != label) continue;
    if (p.reached >= 0.0) delays.push_back(p.reached - p.created);
    if (p.shown >= 0.0) shown.push_back(p.shown - p.created);
    // The visit phase's first plug comes after the attract phase's idle reset: it finds the
    // attract loop and starts the visit the other 19 are plugged into.
    const bool attract_expected = std::string(label) == "attract" || index++ == 0;
    on_expected_screen += p.screen == (attract_expected ? "attract" : "visitor");
  }
  std::sort(delays.begin(), delays.end());
  std::sort(shown.begin(), shown.end());
  ASSERT_EQ(delays.size(), 20u) << label << ": a plug whose samples never reached the screen\n"
                                << all;
  // The bound, per plug, with the guest's frames inside it: a frame the loop is
  // drawing when the pen's first report arrives delays the report's reaching the screen, and
  // a visitor waits for that as much as for the kernel (the guest's mean frame is printed
  // above, for telling the two apart). A slow attract frame is drawn in slices and given up
  // for the pen (app/shell/kiosk/attract_screen.h); before that, this missed (max 1.14–1.65 s).
  std::printf(
      "hotplug during %s: uhid creation -> first pen sample at the screen: median %.3f s, "
      "max %.3f s (20 plugs, %ld on the %s screen); 1 s wanted%s\n",
      label, delays[10], delays.back(), on_expected_screen,
      std::string(label) == "attract" ? "attract"
                                      : "expected (the first on the attract, 19 visitor)",
      delays.back() <= 1.0 ? " and met" : " and MISSED");
  EXPECT_LE(delays.back(), 1.0) << label << ": creation to first sample at the screen";
  // And the frame drawn next, which answers the pen on the display (the painter's first frame
  // after a hand-over): printed, not held to the 1 s.
  if (!shown.empty())
    std::printf(
        "hotplug during %s: uhid creation -> the next frame presented: median %.3f s, max "
        "%.3f s (%zu plugs)\n",
        label, shown[shown.size() / 2], shown.back(), shown.size());
  EXPECT_EQ(on_expected_screen, 20) << label;
}

TEST(KmsKiosk, AttractByPageFlipVtLockedModeKeysAndTabletHotplug) {
  std::string vmlinuz, cache;
  ASSERT_FALSE(fetchKernel(&vmlinuz, &cache).empty())
      << "fetch_kernel.sh failed (needs apt access once)";
  // A folder of its own: QemuVm names its serial log and monitor socket after the device, and
  // kms_flip_test / kms_egl_test boot bochs-display too (ctest -j runs them side by side).
  const std::string work = std::string(CB_KMS_WORK) + "/kiosk";
  std::filesystem::create_directories(work);
  const std::string initrd = work + "/kms_kiosk.cpio.gz";
  ASSERT_NO_FATAL_FAILURE(makeInitrd(cache, initrd));

  QemuVm vm(vmlinuz, initrd, "bochs-display,xres=640,yres=400", work);
  ASSERT_TRUE(vm.started());
  ASSERT_NO_FATAL_FAILURE(checkControlSwitches(vm));
  ASSERT_NO_FATAL_FAILURE(checkAttractByPageFlip(vm, work));
  ASSERT_NO_FATAL_FAILURE(checkVtLockedAndKeys(vm));
  std::string all;
  ASSERT_NO_FATAL_FAILURE(checkKioskEnded(vm, &all));
  const std::vector<Plug> plugs = pairPlugs(vm.lines());
  ASSERT_EQ(plugs.size(), 40u) << all;
  for (const char* label : {"attract", "visit"})
    ASSERT_NO_FATAL_FAILURE(checkPlugs(plugs, label, all));
  long samples = 0, strokes = 0;
  const size_t summary = all.find(" pen samples, ");
  if (summary != std::string::npos) {
    const size_t start = all.rfind("cloudbrush: ", summary);
    std::sscanf(all.c_str() + start, "cloudbrush: %ld pen samples, %ld strokes mapped", &samples,
                &strokes);
  }
  std::printf("the kiosk painted %ld strokes from %ld pen samples\n", strokes, samples);
  EXPECT_GE(strokes, 40) << "every plug's stroke became a cloud";
}

}  // namespace
}  // namespace cb::hil
