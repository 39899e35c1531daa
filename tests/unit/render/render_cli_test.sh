#!/bin/sh
# `cloudbrush render` end to end: a good volume renders to PNG and EXR, in every --style; bad
# input (missing, truncated, mismatched volume, bad size/camera/output/style) exits non-zero with
# a message naming the problem. Usage: render_cli_test.sh PATH/TO/cloudbrush
set -u
CB="$1"
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
fails=0
expect_ok() {  # description, command...
  desc="$1"; shift
  if ! "$@" >"$DIR/out" 2>&1; then echo "FAIL: $desc: exit $?"; cat "$DIR/out"; fails=$((fails+1)); fi
}
expect_error() {  # description, expected text, command...
  desc="$1"; text="$2"; shift 2
  if "$@" >"$DIR/out" 2>&1; then echo "FAIL: $desc: exit 0"; fails=$((fails+1)); return; fi
  if ! grep -q -- "$text" "$DIR/out"; then
    echo "FAIL: $desc: message lacks '$text':"; cat "$DIR/out"; fails=$((fails+1))
  fi
}
# A 4x4x4 volume with one dense voxel: header line + 256 bytes of float32.
printf '{"format":"cloudbrush-volume","version":1,"dims":[4,4,4],"world_min":[-1,-1,-1],"world_max":[1,1,1],"type":"float32","endian":"little","order":"x-fastest"}\n' >"$DIR/v.cbvol"
head -c 84 /dev/zero >>"$DIR/v.cbvol"
printf '\000\000\200\077' >>"$DIR/v.cbvol"   # 1.0f at voxel 21 = (1,1,1)
head -c 168 /dev/zero >>"$DIR/v.cbvol"

expect_ok "png render" "$CB" render --volume "$DIR/v.cbvol" --out "$DIR/a.png" --size 64x40 --stats
grep -q "samples: total" "$DIR/out" || { echo "FAIL: --stats printed no statistics"; fails=$((fails+1)); }
[ -s "$DIR/a.png" ] || { echo "FAIL: no PNG written"; fails=$((fails+1)); }
expect_ok "exr render with camera and light" "$CB" render --volume "$DIR/v.cbvol" \
  --out "$DIR/a.exr" --size 32x32 --camera 0,0.5,3,0,0,0,50 --light -2,3,1 --no-skip
[ -s "$DIR/a.exr" ] || { echo "FAIL: no EXR written"; fails=$((fails+1)); }

head -c 200 "$DIR/v.cbvol" >"$DIR/truncated.cbvol"
sed 's/\[4,4,4\]/[4,4,8]/' "$DIR/v.cbvol" >"$DIR/mismatched.cbvol"
expect_error "missing volume" "cannot open" "$CB" render --volume "$DIR/none.cbvol" --out "$DIR/x.png"
expect_error "truncated volume" "truncated" "$CB" render --volume "$DIR/truncated.cbvol" --out "$DIR/x.png"
expect_error "mismatched dims" "truncated" "$CB" render --volume "$DIR/mismatched.cbvol" --out "$DIR/x.png"
expect_error "bad size" "--size" "$CB" render --volume "$DIR/v.cbvol" --out "$DIR/x.png" --size 0x10
expect_error "bad camera" "--camera" "$CB" render --volume "$DIR/v.cbvol" --out "$DIR/x.png" --camera 1,2
expect_error "bad output type" ".png or .exr" "$CB" render --volume "$DIR/v.cbvol" --out "$DIR/x.jpg"
expect_error "no volume" "--volume FILE is required" "$CB" render --out "$DIR/x.png"
expect_error "unknown option" "unknown option --colour" "$CB" render --volume "$DIR/v.cbvol" --out "$DIR/x.png" --colour red
# --style: every style renders, each differently from the thesis style; a bad name is named.
expect_ok "thesis style" "$CB" render --volume "$DIR/v.cbvol" --out "$DIR/s-thesis.png" --size 64x40 --style thesis
for style in physical ink cartoon sketch; do
  expect_ok "$style style" "$CB" render --volume "$DIR/v.cbvol" --out "$DIR/s-$style.png" --size 64x40 --style "$style"
  if cmp -s "$DIR/s-thesis.png" "$DIR/s-$style.png"; then
    echo "FAIL: --style $style rendered the thesis image"; fails=$((fails+1))
  fi
done
expect_error "bad style" "thesis|physical|ink|cartoon|sketch" "$CB" render --volume "$DIR/v.cbvol" --out "$DIR/x.png" --style watercolour
# [sky] in the config: the export shows it (differs from the flat background); a sky image that
# is missing still renders (with the flat background) and says which file and line.
printf '[sky]\nkind = "lic"\nlic_size = 64\n' >"$DIR/sky.toml"
expect_ok "lic sky" "$CB" render --volume "$DIR/v.cbvol" --out "$DIR/sky.png" --size 64x40 --config "$DIR/sky.toml"
if cmp -s "$DIR/s-thesis.png" "$DIR/sky.png"; then
  echo "FAIL: [sky] kind lic rendered the flat background"; fails=$((fails+1))
fi
printf '[sky]\nkind = "image"\nimage = "missing-sky.png"\n' >"$DIR/nosky.toml"
expect_ok "missing sky image falls back" "$CB" render --volume "$DIR/v.cbvol" --out "$DIR/nosky.png" --size 64x40 --config "$DIR/nosky.toml"
if ! grep -q "nosky.toml:3:9: sky.image cannot be used: .*missing-sky.png" "$DIR/out"; then
  echo "FAIL: missing sky image: no FILE:LINE:COL message"; cat "$DIR/out"; fails=$((fails+1))
fi
[ "$fails" -eq 0 ] && echo "render CLI: all checks passed"
exit "$fails"
