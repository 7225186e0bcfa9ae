#!/usr/bin/env bash
# viewer_shots.sh RECORDING.rrd OUT_DIR [FRACTION ...]: screenshots of a recording in Rerun's
# official web viewer, as a user sees it: OUT_DIR/open.png at open, and OUT_DIR/at-<FRACTION>.png
# with the time cursor moved to that fraction of the run (0.4245: 424.5 s of a 1000 s run).
#
# The web viewer is served by `rerun --serve-web` (pip install "rerun-sdk==0.36.*") and shown in
# Chromium on a virtual display (apt-get install -y xvfb chromium imagemagick xdotool; software
# rendering, no GPU). The cursor is moved by a click on the collapsed time panel's slider, which
# the recording's blueprint puts at the bottom of a 1920 x 1080 window. Rerun 0.36 has no
# blueprint setting for the cursor, and a `#when=` URL fragment applies to dataset URLs only
# (whose segments open without the recording's blueprint).
set -euo pipefail
[ $# -ge 2 ] || { sed -n 2,11p "$0"; exit 2; }
rec=$(realpath "$1"); out=$2; shift 2
mkdir -p "$out"
for tool in Xvfb chromium import xdotool python3; do
  command -v $tool >/dev/null || { echo "viewer_shots: $tool is missing (see the header)" >&2; exit 2; }
done
pids=()
tmp=$(mktemp -d)
cleanup() { for p in "${pids[@]}"; do kill -- "-$p" 2>/dev/null || true; done; rm -rf "$tmp" 2>/dev/null || true; }
trap cleanup EXIT
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }

# One screenshot: a fresh viewer, then an optional click at a fraction of the run.
shot() {
  local png=$1 fraction=${2:-}
  local display=:$((90 + RANDOM % 400)) grpc web
  grpc=$(free_port); web=$(free_port)
  setsid Xvfb "$display" -screen 0 1920x1080x24 -nolisten tcp >"$tmp/xvfb.log" 2>&1 & pids+=($!)
  setsid python3 -m rerun --serve-web --port "$grpc" --web-viewer-port "$web" "$rec" >"$tmp/rerun.log" 2>&1 & pids+=($!)
  for _ in $(seq 60); do grep -q "Hosting a web-viewer" "$tmp/rerun.log" 2>/dev/null && break; sleep 0.5; done
  DISPLAY=$display setsid chromium --no-sandbox --disable-dev-shm-usage --use-angle=swiftshader \
    --enable-unsafe-swiftshader --ignore-gpu-blocklist --no-first-run --disable-infobars \
    --user-data-dir="$tmp/profile-$RANDOM" --window-position=0,0 --window-size=1920,1080 \
    --app="http://127.0.0.1:$web/?url=rerun%2Bhttp%3A%2F%2F127.0.0.1%3A$grpc%2Fproxy" \
    >"$tmp/chromium.log" 2>&1 & pids+=($!)
  sleep 60
  if [ -n "$fraction" ]; then
    # The slider runs from x = 258 px (t = 0) to x = 1710 px (t = t_end), at y = 1064.
    DISPLAY=$display xdotool mousemove "$(python3 -c "print(round(258 + $fraction * 1452))")" 1064 click 1
    sleep 15
  fi
  # Without Chromium's warning bar about --no-sandbox (the top 55 px).
  DISPLAY=$display import -window root -crop 1920x1025+0+55 +repage "$png"
  for p in "${pids[@]}"; do kill -- "-$p" 2>/dev/null || true; done
  pids=()
  echo "viewer_shots: $png"
}

shot "$out/open.png"
for fraction in "$@"; do
  shot "$out/at-$fraction.png" "$fraction"
done
