#!/usr/bin/env bash
# viewer_shots.sh RECORDING.rrd OUT_DIR [SECONDS ...]: screenshots of a recording in Rerun's
# official web viewer, as a user sees it: OUT_DIR/open.png at open, and OUT_DIR/at-<SECONDS>s.png
# with the time cursor at SECONDS of simulated time (425.3: inside the paper case's first rupture).
#
# Needs: Xvfb, Chromium and ImageMagick (apt-get install -y xvfb chromium imagemagick), the rerun
# CLI 0.36 (pip install "rerun-sdk==0.36.*"; `python3 -m rerun` serves the web viewer) and
# slipfront (target/release/slipfront, or SLIPFRONT=PATH). Software rendering, no GPU. The time
# cursor is set by the blueprint file `slipfront view RECORDING --at SECONDS --no-open` writes,
# served with the recording; no clicks. Each shot waits VIEWER_SHOTS_WAIT seconds (default 60)
# for the viewer to load: give a long recording on a busy machine more.
set -euo pipefail
[ $# -ge 2 ] || { sed -n 2,10p "$0"; exit 2; }
rec=$(realpath "$1"); out=$2; shift 2
mkdir -p "$out"
slipfront=${SLIPFRONT:-$(dirname "$0")/../target/release/slipfront}
missing=()
for tool in Xvfb chromium import python3; do command -v $tool >/dev/null || missing+=("$tool"); done
python3 -c "import rerun" 2>/dev/null || missing+=("rerun-sdk (pip install \"rerun-sdk==0.36.*\")")
[ -x "$slipfront" ] || missing+=("slipfront at $slipfront (cargo build --release, or SLIPFRONT=PATH)")
if [ ${#missing[@]} -gt 0 ]; then
  echo "viewer_shots: missing: ${missing[*]} (apt-get install -y xvfb chromium imagemagick)" >&2
  exit 2
fi
pids=()
tmp=$(mktemp -d)
cleanup() { for p in "${pids[@]}"; do kill -- "-$p" 2>/dev/null || true; done; rm -rf "$tmp" 2>/dev/null || true; }
trap cleanup EXIT
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }

# One screenshot of a fresh viewer serving the given files.
shot() {
  local png=$1; shift
  local display=:$((90 + RANDOM % 400)) grpc web
  grpc=$(free_port); web=$(free_port)
  setsid Xvfb "$display" -screen 0 1920x1080x24 -nolisten tcp >"$tmp/xvfb.log" 2>&1 & pids+=($!)
  setsid python3 -m rerun --serve-web --port "$grpc" --web-viewer-port "$web" "$@" >"$tmp/rerun.log" 2>&1 & pids+=($!)
  for _ in $(seq 60); do grep -q "Hosting a web-viewer" "$tmp/rerun.log" 2>/dev/null && break; sleep 0.5; done
  DISPLAY=$display setsid chromium --no-sandbox --disable-dev-shm-usage --use-angle=swiftshader \
    --enable-unsafe-swiftshader --ignore-gpu-blocklist --no-first-run --disable-infobars \
    --user-data-dir="$tmp/profile-$RANDOM" --window-position=0,0 --window-size=1920,1080 \
    --app="http://127.0.0.1:$web/?url=rerun%2Bhttp%3A%2F%2F127.0.0.1%3A$grpc%2Fproxy" \
    >"$tmp/chromium.log" 2>&1 & pids+=($!)
  sleep "${VIEWER_SHOTS_WAIT:-60}"
  # Without Chromium's warning bar about --no-sandbox (the top 55 px).
  DISPLAY=$display import -window root -crop 1920x1025+0+55 +repage "$png"
  for p in "${pids[@]}"; do kill -- "-$p" 2>/dev/null || true; done
  pids=()
  echo "viewer_shots: $png"
}

shot "$out/open.png" "$rec"
for seconds in "$@"; do
  "$slipfront" view "$rec" --at "$seconds" --blueprint "$tmp/at.rbl" --no-open >/dev/null
  shot "$out/at-${seconds}s.png" "$rec" "$tmp/at.rbl"
done
