#!/usr/bin/env bash
# Creates the virtual environment and installs Sward with its test tools into it.
set -euo pipefail
venv=${1:-.venv}
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
"$venv/bin/python" -m pip install --quiet --upgrade pip
echo "sward setup: installing sward and its test tools into $venv"
"$venv/bin/python" -m pip install --quiet -e '.[test]'
echo "sward setup: compiling the traversal kernels (numba, once)"
"$venv/bin/python" scripts/compile_kernels.py
