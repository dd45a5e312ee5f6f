"""A volume cuboid on a slope lies between two planes that follow it (core/terrain.py planes_of,
shaders/volume.glsl): it draws the same grass as the level cuboid over the whole height range
(for fewer fragments, each of which costs a ray on a CPU renderer: `sward bench --suite
volume_cost`)."""

import numpy as np

from app.scenes import get_scene
from benchmarks.references import quarter
from core.image_diff import flip
from core.terrain import Terrain
from render.volume import VolumeRenderer

SIZE = (320, 240)


def _frame_and_grass(headless, monkeypatch, level: bool):
    """The meadow's default frame and the samples its volume passes' grass covers (depth test
    off; a fragment whose ray meets no grass is discarded and not counted)."""
    if level:

        def level_planes(self, instances):
            out = np.zeros((len(instances), 4), np.float32)
            out[:, 3] = instances["ground"][:, 1]
            return out

        monkeypatch.setattr(Terrain, "planes_of", level_planes)
    document = get_scene("meadow").document()
    renderer = headless(document)
    camera = document.camera("default")
    image = renderer.render(camera, SIZE)[0]
    counted = [0]
    draw, prepare = VolumeRenderer.draw, VolumeRenderer.prepare

    def counting_draw(self):
        query = self.ctx.query(samples=True)
        with query:
            draw(self)
        counted[0] += query.samples

    def prepare_without_depth(self, frame):
        prepare(self, frame)
        self.ctx.disable(self.ctx.DEPTH_TEST)

    monkeypatch.setattr(VolumeRenderer, "draw", counting_draw)
    monkeypatch.setattr(VolumeRenderer, "prepare", prepare_without_depth)
    renderer.render(camera, SIZE)
    monkeypatch.undo()
    return image, counted[0]


def test_cuboids_on_slopes_draw_the_same_grass(headless, monkeypatch):
    level, level_samples = _frame_and_grass(headless, monkeypatch, level=True)
    sloped, sloped_samples = _frame_and_grass(headless, monkeypatch, level=False)
    moved, _ = flip(quarter(level), quarter(sloped))
    assert moved < 0.005
    assert abs(sloped_samples - level_samples) < 0.01 * level_samples
