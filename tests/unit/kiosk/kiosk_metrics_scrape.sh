#!/usr/bin/env bash
# Fleet monitoring end to end: the real `cloudbrush kiosk` (surfaceless, a visit started by a
# key) writes cloudbrush.prom into a folder given with --metrics-dir; Debian's
# prometheus-node-exporter (config/setup.sh) serves that folder through its textfile collector
# (all other collectors off) on loopback; curl scrapes it and the kiosk's metrics must be there
# with their values, and node_exporter must report no textfile error. Proves the check bites: a
# malformed file in the folder makes node_exporter report the error.
# usage: kiosk_metrics_scrape.sh CLOUDBRUSH_BINARY VERSION
set -euo pipefail
bin=$1
version=$2
exporter=$(command -v prometheus-node-exporter || true)
if [ -z "$exporter" ]; then
  echo "SKIPPED: prometheus-node-exporter is not installed (config/setup.sh installs it)" >&2
  exit 77
fi
command -v curl >/dev/null || { echo "SKIPPED: curl is not installed (config/setup.sh)" >&2; exit 77; }
work=$(mktemp -d)
exporter_pid=
cleanup() {
  if [ -n "$exporter_pid" ]; then
    kill "$exporter_pid" 2>/dev/null || true
    wait "$exporter_pid" 2>/dev/null || true
  fi
  rm -rf "$work"
}
trap cleanup EXIT
mkdir -p "$work/textfile" "$work/data"

LIBGL_ALWAYS_SOFTWARE=1 "$bin" kiosk --display surfaceless --size 320x180 --grid 32 \
  --backend none --no-record --data-dir "$work/data" --metrics-dir "$work/textfile" \
  --seconds 3 --keys a >"$work/out" 2>"$work/err" || {
  echo "FAIL: the kiosk exited with $?"; cat "$work/err"; exit 1; }
[ -s "$work/textfile/cloudbrush.prom" ] || { echo "FAIL: no $work/textfile/cloudbrush.prom"; cat "$work/err"; exit 1; }
ls -A "$work/textfile" | grep -q '\.tmp\.' && { echo "FAIL: a temporary file was left"; exit 1; }

# A port on loopback that is free now.
port=$(( 20000 + $$ % 20000 ))
"$exporter" --web.listen-address="127.0.0.1:$port" --collector.disable-defaults \
  --collector.textfile --collector.textfile.directory="$work/textfile" \
  >"$work/exporter.log" 2>&1 &
exporter_pid=$!
scrape() {
  for _ in $(seq 50); do
    if curl -sf "http://127.0.0.1:$port/metrics" -o "$1"; then return 0; fi
    sleep 0.2
  done
  echo "FAIL: node_exporter did not answer on 127.0.0.1:$port"; cat "$work/exporter.log"; exit 1
}
scrape "$work/scrape"

fail=0
expect() {  # a line (regex) the scrape must have
  if ! grep -qE "$1" "$work/scrape"; then echo "FAIL: the scrape lacks /$1/"; fail=1; fi
}
expect '^cloudbrush_visits_total 1$'
expect '^cloudbrush_frames_total [1-9][0-9]*$'
expect '^cloudbrush_saves_failed_total 0$'
expect '^cloudbrush_strokes_total 0$'
expect '^cloudbrush_storage_ok 1$'
expect '^cloudbrush_disk_free_bytes [0-9.e+]+$'
expect '^cloudbrush_frames_per_second [0-9.e+]+$'
expect '^cloudbrush_last_input_age_seconds [0-9.e+-]+$'
expect "^cloudbrush_version_info\\{version=\"$version\"\\} 1\$"
expect '^cloudbrush_screen_info\{screen="visitor"\} 1$'
expect '^cloudbrush_device_info\{state="no tablet backend"\} 1$'
expect '^# TYPE cloudbrush_visits_total counter$'
expect '^node_textfile_scrape_error 0$'
expect 'node_textfile_mtime_seconds\{file=".*cloudbrush.prom"\}'
grep '^cloudbrush_' "$work/scrape" | sed 's/^/  scraped: /'

# The check bites: a malformed metrics file is reported by node_exporter.
printf 'cloudbrush_broken{ 1\n' >"$work/textfile/broken.prom"
scrape "$work/scrape"
if ! grep -qE '^node_textfile_scrape_error 1$' "$work/scrape"; then
  echo "FAIL: node_exporter did not report a malformed textfile; the check cannot catch one"
  fail=1
fi
[ "$fail" -eq 0 ] && echo "PASS: node_exporter serves the kiosk's metrics"
exit "$fail"
