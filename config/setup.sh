#!/usr/bin/env bash
# Installs everything cloudbrush needs to build, run and test on Debian 12, with apt-get only.
# Idempotent: packages already present are skipped by apt-get.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git clang clang-format libclang-rt-14-dev ccache
  # display: EGL/GL (libglvnd; libopengl-dev holds opengl.pc), GBM/KMS, X11, Mesa software
  # rasteriser (llvmpipe)
  libegl-dev libgl-dev libopengl-dev libgles-dev libgbm-dev libdrm-dev libx11-dev
  libgl1-mesa-dri libegl-mesa0 libgbm1 xvfb xauth
  # math, images, volumes, config
  libglm-dev libopenexr-dev libpng-dev libopenvdb-dev libopenvdb-tools libtbb-dev
  libtomlplusplus-dev
  # model → cloud: OBJ, PLY, glTF meshes (app/tools)
  libassimp-dev
  # undo history (compressed brick deltas), keymaps on KMS, the on-screen UI and its CJK font
  libzstd-dev libxkbcommon-dev xkb-data libimgui-dev fonts-noto-cjk
  # OpenVDB's headers need Boost's (the .vdb converter for `bench render`)
  libboost-dev
  # input devices
  libevdev-dev libhidapi-dev libusb-1.0-0-dev libudev-dev
  # the operator PIN hash (crypt/yescrypt)
  libcrypt-dev
  # tests and benchmarks (strace: the kiosk's data-dir confinement test)
  libgtest-dev libgmock-dev libbenchmark-dev strace
  # reading the study's InkML exports back in tests
  libxml2-dev
  # virtual tablet / KMS in the loop (qemu + Debian's stock kernel)
  qemu-system-x86 busybox-static cpio
  # packaging checks: systemd-analyze verify on the kiosk unit, the .deb (dpkg-shlibdeps, lintian),
  # the .deb installed into a throwaway Debian 12 root (mmdebstrap; slow label)
  systemd dpkg-dev lintian mmdebstrap
  # fleet monitoring: the kiosk's metrics scraped through node_exporter's textfile collector
  prometheus-node-exporter curl
  # a study re-exported as a Slurm job array on a one-node Slurm (slow label)
  slurmctld slurmd slurm-client munge
  # the BIDS validator of the study export test (npm's bids-validator, installed by the test into
  # the build folder; it runs on Debian 12's Node 18)
  nodejs
)
# npm from Debian, unless the Node.js installed already bundles it (one that does conflicts with it)
command -v npm >/dev/null 2>&1 || packages+=(npm)
export DEBIAN_FRONTEND=noninteractive
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "setup: installing ${#missing[@]} packages: ${missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all packages present"
fi
