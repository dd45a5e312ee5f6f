#!/usr/bin/env bash
# Creates the virtual environment and installs Sward into it with the extras named (default:
# its test tools). The wheels go in through uv, several times faster than pip; pip does it where
# uv cannot be had.
set -euo pipefail
venv=${1:-.venv}
extras=${2:-test}
py=${PYTHON:-python3}
if ! command -v "$py" >/dev/null 2>&1; then
  echo "sward setup: $py not found; install Python 3.11 or newer" >&2; exit 1
fi
if ! "$py" -c 'import sys; sys.exit(sys.version_info < (3, 11))'; then
  echo "sward setup: $("$py" --version) is too old; Sward needs Python 3.11 or newer (set PYTHON=...)" >&2; exit 1
fi
if [ ! -x "$venv/bin/python" ]; then
  echo "sward setup: creating $venv"
  "$py" -m venv "$venv" || { echo "sward setup: python venv failed; on Debian: apt-get install python3-venv" >&2; exit 1; }
fi
if [ ! -x "$venv/bin/uv" ]; then
  "$venv/bin/python" -m pip install --quiet uv || echo "sward setup: uv not to be had; installing with pip"
fi
echo "sward setup: installing sward[$extras] into $venv"
if [ -x "$venv/bin/uv" ]; then
  "$venv/bin/uv" pip install --quiet --python "$venv/bin/python" -e ".[$extras]"
else
  "$venv/bin/python" -m pip install --quiet --upgrade pip
  "$venv/bin/python" -m pip install --quiet -e ".[$extras]"
fi
