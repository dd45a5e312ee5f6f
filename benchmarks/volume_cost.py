"""Where the volume pass's time goes (issue: faster frames): the meadow's default frame at
950 × 720 with variants of the volume renderer, t_v medians and their share of the baseline's,
in one run (this machine's times drift; the shares are what to compare):

- `baseline`: the renderer as it is;
- `fragment_floor`: every fragment returns before its ray (a condition the compiler cannot
  fold away, so the shader keeps its size): what rasterising the cuboids, the shader's set-up
  and blending cost — llvmpipe runs it for every fragment, in front or behind;
- `one_step`: rays of one step instead of VolumeRenderer.max_steps;
- `half_steps`: rays of half the steps;

and the image-based pass of the `bench` scene (`--only image`, 1024 × 768, Table 7.1's frame)
beside its own floor, every fragment writing a constant colour: on llvmpipe the image pass costs
what rasterising its quads under 4× MSAA costs, whatever its shader does, so the volume / image
ratio of Table 7.1 falls as the volume pass gets faster.

Run: `sward bench --suite volume_cost --out results.json`.
"""

from __future__ import annotations

import statistics
from contextlib import contextmanager

SIZE = (950, 720)
FRAMES = 5
_FLOOR = "    if (gl_FragCoord.x > -1.0) { f_color = vec4(0.0); gl_FragDepth = 1.0; return; }\n"
_IMAGE_FLOOR = "    if (gl_FragCoord.x > -1.0) { f_color = vec4(0.3, 0.5, 0.1, 1.0); return; }\n"
IMAGE_SIZE = (1024, 768)


def floor_loader(patch: str, whole: bool = False):
    """load_program for a renderer module whose fragment stage begins with `patch`; `whole`:
    whose fragment stage's main() is `patch` alone (its inputs unread, so the linker drops
    them and the vertex stage's work for them)."""
    from render.shaders import ShaderError, stage_source

    made: dict = {}  # compiled once per variant: the renderers ask for theirs every pass

    def floor_program(ctx, file, defines=()):
        key = (ctx, file, tuple(defines))
        if key not in made:
            made[key] = compile_floor(ctx, file, defines)
        return made[key]

    def compile_floor(ctx, file, defines):
        def stage(kind):
            text = stage_source(file, kind, defines)
            marker = "void main() {\n"
            if kind == "FRAGMENT_SHADER":  # the file's last main(): the fragment stage's
                head, found, tail = text.rpartition(marker)
                if not found:
                    raise ShaderError(f"shaders/{file}: no main() to patch")
                if whole:  # the rest of main() goes: up to its closing brace
                    tail = "}\n" + tail.split("\n}\n", 1)[1]
                text = head + marker + patch + tail
            return text

        return ctx.program(
            vertex_shader=stage("VERTEX_SHADER"), fragment_shader=stage("FRAGMENT_SHADER")
        )

    return floor_program


@contextmanager
def _variant(name: str):
    """The volume renderers made inside get the variant's program or step count."""
    import render.volume as volume

    load, steps = volume.load_program, volume.VolumeRenderer.max_steps
    if name == "fragment_floor":
        volume.load_program = floor_loader(_FLOOR)
    elif name == "one_step":
        volume.VolumeRenderer.max_steps = 1
    elif name == "half_steps":
        volume.VolumeRenderer.max_steps = max(steps // 2, 1)
    try:
        yield
    finally:
        volume.load_program, volume.VolumeRenderer.max_steps = load, steps


def run() -> list[dict]:
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    document = get_scene("meadow").document()
    camera = document.camera()
    rows = []
    for name in ("baseline", "fragment_floor", "one_step", "half_steps"):
        with _variant(name), HeadlessRenderer(document) as renderer:
            renderer.render(camera, SIZE)  # compiles, converts, warms up
            times = [renderer.render(camera, SIZE)[1].t_v_ms for _ in range(FRAMES)]
        rows.append({"name": f"meadow_t_v_{name}", "median_ms": statistics.median(times)})
    base = rows[0]["median_ms"]
    for row in rows:
        row["share_of_baseline"] = row["median_ms"] / base
    return rows + _image_floor()


def _image_floor() -> list[dict]:
    import render.image as image
    from app.scenes import get_scene
    from render.headless import HeadlessRenderer

    document = get_scene("bench").document()
    camera = document.camera()
    rows, load = [], image.load_program
    for name in ("baseline", "fragment_floor"):
        image.load_program = load if name == "baseline" else floor_loader(_IMAGE_FLOOR)
        try:
            with HeadlessRenderer(document, mode="image") as renderer:
                renderer.render(camera, IMAGE_SIZE)
                times = [renderer.render(camera, IMAGE_SIZE)[1].t_i_ms for _ in range(FRAMES)]
        finally:
            image.load_program = load
        rows.append({"name": f"bench_t_i_{name}", "median_ms": statistics.median(times)})
    for row in rows:
        row["share_of_baseline"] = row["median_ms"] / rows[0]["median_ms"]
    return rows
