#!/usr/bin/env bash
# Builds a busybox-static initramfs for booting Debian's stock kernel in qemu, for any
# in-the-loop test (tablet, KMS display, ...).
#
#   build_initramfs.sh --kernel-cache DIR --out FILE.cpio.gz --init SCRIPT
#                      [--module NAME]... [--binary PATH[:DEST]]... [--file SRC:DEST]...
#
#   --kernel-cache  the cache fetch_kernel.sh filled (the kernel is fetched if missing)
#   --init          shell script run as /init (busybox sh); it may call /bin/load-modules,
#                   which inserts the requested modules and their dependencies in order
#   --module        kernel module by name (wacom, uhid, dummy_hcd, bochs, ...); dependencies
#                   are resolved from each module's .modinfo "depends=" (no kmod needed)
#   --binary        an ELF executable or library copied with its ldd closure (same path inside
#                   unless :DEST is given); use it for dlopen()ed libraries too
#   --file          any extra file or directory (copied recursively)
#
# Prints KVER=, VMLINUZ= (from fetch_kernel.sh) and INITRD= on stdout.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cache="" out="" init=""
modules=() binaries=() files=()
while [ $# -gt 0 ]; do
  case "$1" in
    --kernel-cache) cache=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --init) init=$2; shift 2 ;;
    --module) modules+=("$2"); shift 2 ;;
    --binary) binaries+=("$2"); shift 2 ;;
    --file) files+=("$2"); shift 2 ;;
    *) echo "build_initramfs: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ -n "$cache" ] && [ -n "$out" ] && [ -n "$init" ] || {
  echo "build_initramfs: --kernel-cache, --out and --init are required" >&2; exit 2; }
[ -f "$init" ] || { echo "build_initramfs: init script $init does not exist" >&2; exit 2; }
busybox=$(command -v busybox || true)
if [ -z "$busybox" ] || ! file -L "$busybox" 2>/dev/null | grep -q static; then
  for b in /bin/busybox /usr/bin/busybox; do [ -x "$b" ] && busybox=$b; done
fi
[ -x "$busybox" ] || { echo "build_initramfs: busybox-static is not installed (apt-get install busybox-static)" >&2; exit 2; }

eval "$("$here/fetch_kernel.sh" "$cache")"
echo "KVER=$KVER"
echo "VMLINUZ=$VMLINUZ"

root=$(mktemp -d "${out}.root.XXXXXX")
trap 'rm -rf "$root"' EXIT
mkdir -p "$root"/{bin,sbin,dev,proc,sys,tmp,run,etc,lib/modules/"$KVER"}
cp "$busybox" "$root/bin/busybox"
for applet in $("$busybox" --list); do
  [ -e "$root/bin/$applet" ] || ln -s busybox "$root/bin/$applet"
done

# Modules: resolve dependencies depth-first so each is inserted after what it needs.
declare -A seen=()
order=()
find_module() {
  local name=$1 alt=${1//-/_} alt2=${1//_/-}
  find "$MODDIR/kernel" \( -name "$name.ko" -o -name "$alt.ko" -o -name "$alt2.ko" \
       -o -name "$name.ko.xz" -o -name "$alt.ko.xz" -o -name "$alt2.ko.xz" \) | head -n1
}
add_module() {
  local name=${1//-/_}
  [ -n "${seen[$name]:-}" ] && return 0
  seen[$name]=1
  local path
  path=$(find_module "$1")
  if [ -z "$path" ]; then
    if grep -qE "/(${1}|${name}|${1//_/-})\.ko" "$MODDIR/modules.builtin" 2>/dev/null; then
      return 0  # built into the kernel
    fi
    echo "build_initramfs: module $1 not found in $MODDIR" >&2
    exit 2
  fi
  local deps
  deps=$(objcopy -O binary --only-section=.modinfo "$path" /dev/stdout 2>/dev/null |
         tr '\0' '\n' | sed -n 's/^depends=//p' | tr ',' ' ')
  for d in $deps; do add_module "$d"; done
  order+=("$path")
}
for m in "${modules[@]}"; do add_module "$m"; done
: > "$root/etc/modules.order"
for path in "${order[@]}"; do
  rel=${path#"$MODDIR"/}
  mkdir -p "$root/lib/modules/$KVER/$(dirname "$rel")"
  cp "$path" "$root/lib/modules/$KVER/$rel"
  echo "/lib/modules/$KVER/$rel" >> "$root/etc/modules.order"
done
cat > "$root/bin/load-modules" <<'LOAD'
#!/bin/sh
# Inserts the modules listed in /etc/modules.order (dependencies first).
while read -r m; do
  insmod "$m" 2>/dev/null || echo "load-modules: insmod $m failed" >&2
done < /etc/modules.order
LOAD
chmod +x "$root/bin/load-modules"

copy_with_closure() {
  local src=${1%%:*} dest=${1#*:}
  [ "$dest" = "$1" ] && dest=$src
  [ -e "$src" ] || { echo "build_initramfs: $src does not exist" >&2; exit 2; }
  mkdir -p "$root/$(dirname "$dest")"
  cp -L "$src" "$root/$dest"
  ldd "$src" 2>/dev/null | awk '/=> \//{print $3} /^\s*\/lib/{print $1}' | while read -r lib; do
    mkdir -p "$root/$(dirname "$lib")"
    [ -e "$root/$lib" ] || cp -L "$lib" "$root/$lib"
  done
}
for b in "${binaries[@]}"; do copy_with_closure "$b"; done
for f in "${files[@]}"; do
  src=${f%%:*} dest=${f#*:}
  mkdir -p "$root/$(dirname "$dest")"
  cp -rL "$src" "$root/$dest"
done
# The loader path glibc binaries ask for.
if [ -e /lib64/ld-linux-x86-64.so.2 ] && [ ! -e "$root/lib64/ld-linux-x86-64.so.2" ]; then
  mkdir -p "$root/lib64"
  cp -L /lib64/ld-linux-x86-64.so.2 "$root/lib64/"
fi
cp "$init" "$root/init"
chmod +x "$root/init"
(cd "$root" && find . -print0 | cpio --null -o -H newc --quiet) | gzip -1 > "$out"
echo "INITRD=$out"
