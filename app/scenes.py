"""Built-in scenes: a patch, a grid of cells and named cameras."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from core.camera import Camera
from core.design_maps import DesignMaps
from core.grid import grid_instances
from core.lod import LodConfig
from core.terrain import Terrain
from core.params import DEFAULT_PRESET, PRESETS, PatchParams


@dataclass(frozen=True)
class CameraSpec:
    eye: tuple[float, float, float]
    target: tuple[float, float, float]

    def camera(self) -> Camera:
        return Camera.from_eye_target(self.eye, self.target)


@dataclass(frozen=True)
class Scene:
    name: str
    description: str
    params: PatchParams
    grid: tuple[int, int]
    density: float = 1.0
    cameras: dict[str, CameraSpec] = field(default_factory=dict)
    default_camera: str = "default"
    lod: LodConfig = field(default_factory=LodConfig)
    mirror_seed: int | None = None  # aperiodic tiling (thesis 6.3); None: every cell alike
    tint: float = 0.0  # alpha of the procedural colour-modulation map (thesis 6.4.2)

    def instances(self) -> np.ndarray:
        return grid_instances(*self.grid, mirror_seed=self.mirror_seed)

    def terrain(self) -> Terrain:
        return Terrain.centred(*self.grid, mirror_seed=self.mirror_seed)

    def design_maps(self) -> DesignMaps:
        """The scene's design-map stack: procedural defaults until maps are painted."""
        return DesignMaps.procedural(256, seed=self.params.seed, tint=self.tint)

    def camera(self, name: str | None = None) -> Camera:
        name = name or self.default_camera
        if name not in self.cameras:
            raise KeyError(name)
        return self.cameras[name].camera()


SCENES: dict[str, Scene] = {
    "patch-grid": Scene(
        name="patch-grid",
        description="the current patch tiled over an 8 × 8 grid of flat cells",
        params=PRESETS[DEFAULT_PRESET],
        grid=(8, 8),
        cameras={
            "default": CameraSpec((4.6, 2.4, 5.4), (0.0, 0.0, 0.0)),
            "close": CameraSpec((1.2, 0.55, 1.6), (0.0, 0.1, 0.0)),
            "top": CameraSpec((0.0, 9.0, 0.01), (0.0, 0.0, 0.0)),
            "grazing": CameraSpec((0.0, 1.3, 4.2), (0.0, 0.0, -1.5)),
        },
        # the grazing camera sees all three: geometry to 3.5, volume to 6.5, image beyond
        lod=LodConfig.zones(geometry_end=3.5, volume_end=6.5, transition=1.5),
        mirror_seed=1,
        tint=0.2,
    ),
    # "zones" looks across all three LOD zones: the view of the thesis's Figs. 7.1-7.6
    "bench": Scene(
        name="bench",
        description="32 × 32 flat cells, aperiodic tiling: the benchmarks of thesis Tables 7.1, 7.2",
        params=PRESETS[DEFAULT_PRESET],
        grid=(32, 32),
        cameras={
            "default": CameraSpec((0.0, 9.0, 22.0), (0.0, 0.0, 2.0)),
            "top": CameraSpec((0.0, 40.0, 0.01), (0.0, 0.0, 0.0)),
            "grazing": CameraSpec((0.0, 0.6, 17.0), (0.0, 0.1, 0.0)),
            "zones": CameraSpec((0.0, 2.0, 17.5), (0.0, 0.0, 6.0)),
        },
        lod=LodConfig.zones(geometry_end=5.0, volume_end=16.0, transition=4.0),
        mirror_seed=1,
        tint=0.2,
    ),
}
DEFAULT_SCENE = "patch-grid"


def get_scene(name: str) -> Scene:
    try:
        return SCENES[name]
    except KeyError:
        raise KeyError(
            f"unknown scene {name!r}; built-in scenes: {', '.join(sorted(SCENES))}"
        ) from None
