#!/usr/bin/env bash
# The figures on a GPU (issue 40): sward bench's representations, macrocells, traversal,
# conversion, volume_cost and wind suites and `sward profile` of the football and the meadow,
# each as JSON under $OUT, with `sward info` saying which OpenGL renderer drew them.
#
# On a fresh machine with no network (the lent GPU machine), prepare here, in the repo's root,
# once: the EGL/GL loaders as .deb files in .gl/ and the Python packages as wheels in .whl/
# (the device tool's README gives both recipes); carry both. Where neither is there it uses
# .venv, or makes it (`make setup`, which needs the network).
#
#   OUT=out bash benchmarks/gpu.sh                                  # the figures
#   GPU_ANY=1 GPU_SIZE=320x180 GPU_FRAMES=2 GPU_SUITES=wind OUT=out bash benchmarks/gpu.sh
#                                                 # a quick try on any renderer (llvmpipe)
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-gpu-figures}
SIZE=${GPU_SIZE:-1920x1080}
FRAMES=${GPU_FRAMES:-30}
SUITES=${GPU_SUITES:-representations macrocells traversal conversion volume_cost wind}
mkdir -p "$OUT"

if compgen -G ".gl/*.deb" >/dev/null; then
    for f in .gl/*.deb; do dpkg -x "$f" /; done
    ldconfig
fi
if compgen -G ".whl/*.whl" >/dev/null; then
    python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade \
        --target /tmp/site .whl/*.whl
    export PYTHONPATH="/tmp/site:$PWD"
    PY=python3
else
    [ -x .venv/bin/python ] || make setup
    PY=.venv/bin/python
fi
sward() { "$PY" -c 'import sys; from app.cli import main; sys.exit(main())' "$@"; }

sward info | tee "$OUT/info.txt"
if ! grep -qi nvidia "$OUT/info.txt" && [ -z "${GPU_ANY:-}" ]; then
    echo "gpu.sh: sward info names no NVIDIA renderer ($(cat "$OUT/info.txt")); the figures" \
         "would be this renderer's, not the GPU's: stopping (GPU_ANY=1 runs anyway)" >&2
    exit 2
fi
args=()
for suite in $SUITES; do args+=(--suite "$suite"); done
sward bench "${args[@]}" --out "$OUT/bench.json"
for scene in football meadow; do
    sward profile --scene "$scene" --frames "$FRAMES" --size "$SIZE" --out "$OUT/profile-$scene.json"
done
echo "gpu.sh: wrote $(ls "$OUT" | tr '\n' ' ')under $OUT"
