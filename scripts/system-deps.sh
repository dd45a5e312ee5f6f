#!/usr/bin/env bash
# Makes sure the system libraries Sward needs are present: Mesa's GL/EGL, the xcb libraries of
# Qt's xcb platform, Xvfb for the test suite, xdotool for the latency benchmark, and with the
# argument `test` Node.js with npm for the glTF validator that the export tests run. On Debian as
# root it installs what is missing; elsewhere it names what to install.
set -uo pipefail
pkgs=(xvfb libegl1 libgl1 libegl-mesa0 libgl1-mesa-dri libxkbcommon-x11-0 libxcb-cursor0
      libxcb-icccm4 libxcb-keysyms1 libxcb-shape0 libxcb-render-util0 libxcb-image0
      libxcb-randr0 libxcb-xfixes0 libxcb-xinerama0 libfontconfig1 libdbus-1-3 xdotool)
if [ "${1:-}" = test ]; then
  pkgs+=(nodejs)
  # Debian's nodejs comes without npm; some builds of it carry their own
  command -v npm >/dev/null 2>&1 || pkgs+=(npm)
fi
if ! command -v dpkg-query >/dev/null 2>&1; then
  echo "sward setup: not a Debian system; make sure Mesa (GL + EGL), Xvfb and Qt's xcb libraries are installed:"
  echo "  ${pkgs[*]}"
  exit 0
fi
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null 2>&1; then
  echo "sward setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq >/dev/null && apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null \
    || { echo "sward setup: apt-get install ${missing[*]} failed" >&2; exit 1; }
else
  echo "sward setup: missing system packages; install them with:" >&2
  echo "  sudo apt-get install ${missing[*]}" >&2
  exit 1
fi
