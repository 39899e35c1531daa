# Sourced by check_deb_package.sh once its install-and-purge check is done: the installer's
# steps in the same Debian 12 root, on a second install of the package. Uses its `root`, `deb`,
# `out`, `build`, `source`, `fail` and `in_root`.
#   - /etc/cloudbrush/kiosk.toml is a conffile (dpkg lists it) with every key commented out; an
#     edited one survives a reinstall and an upgrade whose template changed (--force-confold, as
#     an unattended installer runs apt; dpkg keeps the new template as .dpkg-dist);
#   - `cloudbrush kiosk --set-pin` stores the PIN hashed (yescrypt), 0600, owned by the service's
#     user;
#   - cloudbrush-kiosk-setup without systemd says what it skipped (exit 3), with systemd
#     installed but not running (this chroot) enables the unit and the target for the next boot;
#   - the installed binary ignores the build tree's config/: broken files planted at the source
#     path compiled into it do not stop it rendering;
#   - purge removes the conffile and the setup's logind drop-in.
steps_deb="/tmp/$(basename "$deb")"
cp "$deb" "$root$steps_deb"
etc_toml="$root/etc/cloudbrush/kiosk.toml"
if ! in_root apt-get install -y -qq --no-install-recommends "$steps_deb" >"$out/install2.log" 2>&1; then
  echo "FAIL: the second install:"; tail -20 "$out/install2.log"; fail=1
fi
conffiles=$(in_root dpkg-query -W -f='${Conffiles}\n' cloudbrush || true)
if grep -q '^ /etc/cloudbrush/kiosk.toml [0-9a-f]\{32\}$' <<<"$conffiles"; then
  echo "  dpkg lists the conffile:$conffiles"
else
  echo "FAIL: /etc/cloudbrush/kiosk.toml is not a conffile of the package: '$conffiles'"; fail=1
fi
if [ ! -f "$etc_toml" ] || grep -qE '^[a-z_]+ *=' "$etc_toml"; then
  echo "FAIL: $etc_toml missing or sets a key as installed"; fail=1
fi

# The installer turns the gallery on; a reinstall and an upgrade keep that.
sed -i 's/^#enabled = false/enabled = true/' "$etc_toml"
edited=$(md5sum <"$etc_toml")
grep -qx 'enabled = true' "$etc_toml" || { echo "FAIL: could not edit $etc_toml"; fail=1; }
in_root apt-get install --reinstall -y -qq "$steps_deb" >>"$out/install2.log" 2>&1 ||
  { echo "FAIL: apt-get install --reinstall"; fail=1; }
[ "$(md5sum <"$etc_toml")" = "$edited" ] && echo "  reinstalled: the edited kiosk.toml kept" ||
  { echo "FAIL: a reinstall changed the edited $etc_toml"; fail=1; }
# The next version, its template changed (a comment added).
up=$(mktemp -d)
dpkg-deb -R "$deb" "$up/pkg"
version=$(dpkg-deb -f "$deb" Version)
sed -i "s/^Version: .*/Version: $version+1/" "$up/pkg/DEBIAN/control"
echo "# a new default explained" >>"$up/pkg/etc/cloudbrush/kiosk.toml"
(cd "$up/pkg" && find . -type f ! -path './DEBIAN/*' -printf '%P\n' | sort | xargs md5sum) \
  >"$up/pkg/DEBIAN/md5sums"
dpkg-deb --root-owner-group -b "$up/pkg" "$root/tmp/cloudbrush-up.deb" >/dev/null
rm -rf "$up"
if in_root apt-get install -y -qq -o Dpkg::Options::=--force-confold /tmp/cloudbrush-up.deb \
     >>"$out/install2.log" 2>&1 &&
   [ "$(in_root dpkg-query -W -f='${Version}' cloudbrush || true)" = "$version+1" ]; then
  if [ "$(md5sum <"$etc_toml")" = "$edited" ] && [ -f "$etc_toml.dpkg-dist" ]; then
    echo "  upgraded to $version+1 (template changed): the edited kiosk.toml kept, the new one beside it as kiosk.toml.dpkg-dist"
  else
    echo "FAIL: the upgrade did not keep the edited $etc_toml (or no .dpkg-dist)"; fail=1
  fi
else
  echo "FAIL: the upgrade to $version+1:"; tail -20 "$out/install2.log"; fail=1
fi
rm -f "$root/tmp/cloudbrush-up.deb" "$etc_toml.dpkg-dist"

# The PIN, hashed, for root and the service only.
data=/var/lib/cloudbrush
in_root install -d -m 0750 -o cloudbrush -g cloudbrush "$data"
pin_file="$root$data/operator-pin"
if echo 13579 | in_root cloudbrush kiosk --set-pin --data-dir "$data" >"$out/pin.log" 2>&1 &&
   [ "$(in_root stat -c '%a %U %G' "$data/operator-pin")" = "600 cloudbrush cloudbrush" ] &&
   grep -qE '^\$y\$' "$pin_file" && ! grep -q 13579 "$pin_file"; then
  echo "  cloudbrush kiosk --set-pin: $(cat "$out/pin.log"); $(in_root stat -c '%A %U:%G' "$data/operator-pin"), "$(cut -c1-7 "$pin_file")..." (yescrypt, no length)"
else
  echo "FAIL: --set-pin in the root:"; cat "$out/pin.log"; in_root ls -l "$data/operator-pin" || true; fail=1
fi
if in_root runuser -u nobody -- cat "$data/operator-pin" >/dev/null 2>&1; then
  echo "FAIL: another user can read the PIN's hash"; fail=1
fi

# cloudbrush-kiosk-setup without systemd, then with systemd installed but not running.
before_hash=$(cat "$pin_file")
set +e
echo 24680 | in_root cloudbrush-kiosk-setup --pin-stdin >"$out/setup.log" 2>&1
status=$?
set -e
if [ "$status" -eq 3 ] && grep -q 'SKIPPED (systemctl not found' "$out/setup.log" &&
   [ -f "$root/etc/systemd/logind.conf.d/cloudbrush-kiosk.conf" ] &&
   [ "$(cat "$pin_file")" != "$before_hash" ]; then
  echo "  cloudbrush-kiosk-setup without systemd: exit 3, $(tr '\n' ' ' <"$out/setup.log" | cut -c1-300)"
else
  echo "FAIL: cloudbrush-kiosk-setup without systemd (exit $status):"; cat "$out/setup.log"; fail=1
fi
if in_root apt-get install -y -qq --no-install-recommends systemd >"$out/systemd.log" 2>&1; then
  if echo 24680 | in_root cloudbrush-kiosk-setup --pin-stdin >"$out/setup.log" 2>&1 &&
     grep -q 'enabled but not started' "$out/setup.log" &&
     [ "$(readlink "$root/etc/systemd/system/default.target")" = /lib/systemd/system/graphical.target ] &&
     [ -L "$root/etc/systemd/system/graphical.target.wants/cloudbrush-kiosk.service" ]; then
    echo "  cloudbrush-kiosk-setup with systemd (not running): $(tr '\n' ' ' <"$out/setup.log" | cut -c1-300)"
  else
    echo "FAIL: cloudbrush-kiosk-setup with systemd in the root:"; cat "$out/setup.log"
    ls -l "$root/etc/systemd/system" || true; fail=1
  fi
else
  echo "FAIL: apt-get install systemd in the root:"; tail -20 "$out/systemd.log"; fail=1
fi

# The build tree's config/ is never read by the installed binary.
mkdir -p "$root$source/config"
for f in render.toml brush.toml mapping.toml kiosk.toml calibration.toml; do
  echo 'planted = [ "not toml' >"$root$source/config/$f"
done
# The planted files do stop a binary told to read them (so the check below can fail).
if in_root env CLOUDBRUSH_CONFIG_DIR="$source/config" LIBGL_ALWAYS_SOFTWARE=1 \
     cloudbrush --size 160x100 --grid 32 --out-dir /tmp/planted >"$out/planted.log" 2>&1; then
  echo "FAIL: the planted config did not stop a binary pointed at it"; fail=1
fi
if in_root runuser -u cloudbrush -- env HOME="$data" LIBGL_ALWAYS_SOFTWARE=1 \
     MESA_SHADER_CACHE_DIR="$data/mesa-shader-cache" sh -c \
     "cd $data && cloudbrush --size 160x100 --grid 32 --out-dir $data/out2" >"$out/planted.log" 2>&1 &&
   [ -s "$root$data/out2/cloudbrush-cumulus.png" ]; then
  echo "  broken config planted at the build tree's $source/config: the installed binary ignores it (rendered)"
else
  echo "FAIL: the installed binary read the build tree's config ($source/config):"; cat "$out/planted.log"; fail=1
fi
rm -rf "$root$source/config" "$root/tmp/planted"

rm -f "$root$steps_deb"
if in_root apt-get purge -y -qq cloudbrush >"$out/purge2.log" 2>&1 && [ ! -e "$root/etc/cloudbrush" ] &&
   [ ! -e "$root/etc/systemd/logind.conf.d/cloudbrush-kiosk.conf" ]; then
  echo "  purged again: /etc/cloudbrush and the logind drop-in are gone"
else
  echo "FAIL: purge after the kiosk's steps left files:"; ls -la "$root/etc/cloudbrush" \
    "$root/etc/systemd/logind.conf.d" 2>&1 | head; fail=1
fi
