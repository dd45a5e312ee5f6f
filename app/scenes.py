"""The catalogue of built-in scenes: each makes a new project (core/document.py)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from core.design_maps import DesignMaps
from core.document import MAIN_GRASS, CameraSpec, Document, GrassType, Prop, TerrainSpec
from core.lighting import Lighting
from core.lod import LodConfig, LodLevel
from core.markings import football_colour_map
from core.params import DEFAULT_PRESET, PRESETS, PatchParams
from core.project_schema import MAX_CELLS

# a resized scene's maps (Scene.resized): 1024² texels × the stack's layers is ~60 MB
MAX_MAP_SIDE = 1024


@dataclass(frozen=True)
class GrassRecipe:
    """A further grass type of a built-in scene: its patch, LOD levels, density channel and how
    its density map is made."""

    name: str
    params: PatchParams
    lod: LodConfig
    channel: int  # 1 … 3: the density map's channel (0 is the scene's first grass)
    density_map: Callable[[int, int], np.ndarray] | None = None  # (width, height) -> 0 … 1


@dataclass(frozen=True, eq=False)
class Scene:
    """A built-in scene: what `document()` builds a new project from."""

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
    # (width, height) -> RGBA colour-modulation map replacing the procedural one
    colour_map: Callable[[int, int], np.ndarray] | None = None
    map_size: tuple[int, int] = (256, 256)
    props: tuple = ()  # ((x, z), (w, h, d), (r, g, b)[, lift[, shape]]) rows
    fog_distance: float = 160.0  # world units (core/lighting.py)
    paths: dict[str, tuple[CameraSpec, ...]] = field(default_factory=dict)  # for profiling
    # (width, height) -> (height, width) arrays in 0 … 1 for the stack's height and density maps
    height_map: Callable[[int, int], np.ndarray] | None = None
    height_scale: float = 0.0  # world units of the height map's 1 (thesis 6.4.4)
    density_map: Callable[[int, int], np.ndarray] | None = None
    grass: tuple[GrassRecipe, ...] = ()  # further grass types beside the first

    def document(self) -> Document:
        """A new project made from this scene."""
        return Document(
            self.name,
            [
                GrassType(MAIN_GRASS, self.params, self.lod, 0),
                *(GrassType(g.name, g.params, g.lod, g.channel) for g in self.grass),
            ],
            TerrainSpec(*self.grid, self.mirror_seed, self.height_scale),
            self._design_maps(),
            description=self.description,
            density=self.density,
            light=Lighting(fog_distance=self.fog_distance),
            cameras=self.cameras,
            default_camera=self.default_camera,
            paths=self.paths,
            props=tuple(Prop(*row) for row in self.props),
        )

    def recoloured(self, root: tuple, tip: tuple) -> Scene:
        """Every grass type's blades in one ramp from `root` to `tip`, without variation: for
        the tests that compare representations by light or coverage alone."""

        def ramp(params: PatchParams) -> PatchParams:
            return params.replace(root_color=root, tip_color=tip, blade_color_variation=0.0)

        grass = tuple(replace(g, params=ramp(g.params)) for g in self.grass)
        return replace(self, params=ramp(self.params), grass=grass)

    def resized(self, columns: int, rows: int) -> Scene:
        """The scene over columns × rows cells: its maps are made anew at a size that keeps
        their texels per cell (so hills, paths and markings stretch with the terrain), at most
        MAX_MAP_SIDE texels a side; cameras and props keep their places."""
        if not (1 <= columns and 1 <= rows and columns * rows <= MAX_CELLS):
            raise ValueError(
                f"terrain {columns} × {rows} cells out of range; at least 1 × 1, at most "
                f"{MAX_CELLS:,} cells"
            )
        (w, h), (gx, gz) = self.map_size, self.grid
        tx, tz = w * columns / gx, h * rows / gz
        fit = min(1.0, MAX_MAP_SIDE / max(tx, tz))
        size = (max(round(tx * fit), 8), max(round(tz * fit), 8))
        return replace(self, grid=(columns, rows), map_size=size)

    def _design_maps(self) -> DesignMaps:
        """Procedural defaults: colour variation, the height map, the density maps."""
        if self.colour_map is None:
            maps = DesignMaps.procedural(self.map_size[0], seed=self.params.seed, tint=self.tint)
            if maps.size != self.map_size:
                maps = DesignMaps(*self.map_size)
        else:
            maps = DesignMaps(*self.map_size)
            maps.write("color", 0, 0, self.colour_map(*self.map_size))
        if self.height_map is not None:
            heights = np.asarray(self.height_map(*self.map_size), np.float32)
            maps.write("height", 0, 0, heights.astype(np.float16).astype(np.float32))
        if self.density_map is not None:
            maps.write("density", 0, 0, self.density_map(*self.map_size))
        for kind in self.grass:
            if kind.density_map is not None:
                maps.write("density", 0, 0, kind.density_map(*self.map_size), channel=kind.channel)
        return maps


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
        paths={
            "orbit": tuple(
                CameraSpec((6.0 * math.sin(a), 2.4, 6.0 * math.cos(a)), (0.0, 0.0, 0.0))
                for a in np.linspace(0.0, 2.0 * math.pi, 9)
            )
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
        paths={
            "approach": (
                CameraSpec((0.0, 9.0, 22.0), (0.0, 0.0, 2.0)),
                CameraSpec((0.0, 2.0, 17.5), (0.0, 0.0, 6.0)),
                CameraSpec((0.0, 0.6, 12.0), (0.0, 0.1, 0.0)),
            )
        },
        lod=LodConfig.zones(geometry_end=5.0, volume_end=16.0, transition=4.0),
        mirror_seed=1,
        tint=0.2,
    ),
}


def _goals() -> tuple:
    """Goal posts and crossbars at both ends, and a ball on the centre spot (props for t_m).
    One cell is 0.2 m across the pitch (380 cells for 76 m) and 0.21 m along it."""
    white = (0.92, 0.92, 0.9)
    half_goal, post, height = 3.66 * 5.0, 0.6, 2.44 * 5.0
    z_line = 105.0 / 2 * 532 / 113.0
    rows = [((0.0, 0.0), (1.1, 1.1, 1.1), (0.9, 0.9, 0.85))]
    for z in (-z_line, z_line):
        for x in (-half_goal, half_goal):
            rows.append(((x, z), (post, height, post), white))
        rows.append(((0.0, z), (2 * half_goal + post, post, post), white, height - post))
    return tuple(rows)


SCENES["football"] = Scene(
    name="football",
    description="380 × 532 cells of 5000-blade turf, the thesis's five LOD levels and markings",
    params=PRESETS["short-cut turf"],
    grid=(380, 532),
    cameras={
        "high": CameraSpec((-260.0, 140.0, -190.0), (0.0, 0.0, 20.0), 1500.0, 0.5),
        "player": CameraSpec((25.0, 9.0, -210.0), (0.0, 4.0, -60.0), 1500.0, 0.1),
        "ant": CameraSpec((10.0, 0.25, 20.0), (14.0, 0.3, 120.0), 1500.0, 0.02),
    },
    default_camera="player",
    # thesis ch. 7: geometry to 20; volume 2×8 slices 5-80, 2×2 50-160, 2×1 100-300, macro-cells
    # up to 40 (here 32: a power of two); image-based from 200, macro-cells up to 500 (512)
    lod=LodConfig(
        (
            LodLevel("geometry", 0.0, 20.0),
            LodLevel("volume", 5.0, 80.0, slices=8, macro=32),
            LodLevel("volume", 50.0, 160.0, slices=2, macro=32),
            LodLevel("volume", 100.0, 300.0, slices=1, macro=32),
            LodLevel("image", 200.0, None, macro=512),
        )
    ),
    mirror_seed=3,
    colour_map=football_colour_map,
    map_size=(760, 1064),
    props=_goals(),
    fog_distance=1500.0,
    paths={
        # from the stands down onto the pitch, along it at player height, into the grass
        "flyover": (
            CameraSpec((-260.0, 140.0, -190.0), (0.0, 0.0, 20.0), 1500.0, 0.5),
            CameraSpec((-60.0, 40.0, -240.0), (0.0, 0.0, -60.0), 1500.0, 0.2),
            CameraSpec((25.0, 9.0, -210.0), (0.0, 4.0, -60.0), 1500.0, 0.1),
            CameraSpec((10.0, 2.0, -60.0), (14.0, 0.3, 120.0), 1500.0, 0.05),
        ),
    },
)


def _meadow_heights(width: int, height: int) -> np.ndarray:
    from core.heights import hills

    return hills(width, seed=7, period=3)[:height, :width]


def _meadow_clumps(width: int, height: int) -> np.ndarray:
    """Clumps of tall meadow grass: where a noise rises high, and never on the path."""
    from core.noise import fractal_noise

    c = (np.arange(width) + 0.5) / width
    u, v = np.meshgrid(c, (np.arange(height) + 0.5) / height)
    n = fractal_noise(u, v, period=8, seed=21, octaves=2)
    clumps = np.clip((n - 0.15) / 0.2, 0.0, 1.0)
    return (clumps * _meadow_path(width, height)).astype(np.float32)


def _meadow_path(width: int, height: int) -> np.ndarray:
    """Full density with a bare, winding footpath across the meadow (thesis Fig. 6.8)."""
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    U, V = np.meshgrid(u, v)  # rows along v
    centre = 0.5 + 0.18 * np.sin(V * 2 * np.pi * 1.3 + 0.6)
    d = np.abs(U - centre) * 48  # cells from the path's centre line (48 cells across)
    return np.clip((d - 0.6) / 1.2, 0.0, 1.0).astype(np.float32)


SCENES["meadow"] = Scene(
    name="meadow",
    description="a hilly 48 × 48-cell meadow, clustered grass with a bare path, a few rocks",
    params=PRESETS[DEFAULT_PRESET].replace(blade_count=1600),
    grid=(48, 48),
    cameras={
        "default": CameraSpec((7.0, 4.5, 27.0), (0.0, 1.5, 10.0), 300.0),
        "path": CameraSpec((1.5, 3.2, 22.0), (0.0, 1.5, 8.0), 300.0),
        "hill": CameraSpec((-30.0, 12.0, -30.0), (0.0, 1.5, 0.0), 300.0),
    },
    # small geometry zone and few ray steps: interactive on a CPU renderer (DESIGN.md)
    lod=LodConfig(
        (
            LodLevel("geometry", 0.0, 7.0),
            LodLevel("volume", 5.0, 22.0, slices=8, macro=4),
            LodLevel("image", 18.0, None, macro=16, max_unplanarity=0.6),
        ),
        silhouettes=True,
    ),
    mirror_seed=5,
    tint=0.25,
    map_size=(256, 256),
    height_map=_meadow_heights,
    height_scale=3.0,
    density_map=_meadow_path,
    grass=(
        GrassRecipe(
            "tall meadow grass",
            PRESETS["long thin meadow grass"].replace(
                blade_count=900, width_min=0.008, width_max=0.014, tip_color=(0.78, 0.72, 0.36)
            ),
            LodConfig(
                (
                    LodLevel("geometry", 0.0, 6.0),
                    LodLevel("volume", 4.5, 16.0, slices=4, macro=4),
                    LodLevel("image", 14.0, None, macro=16, max_unplanarity=0.6),
                )
            ),
            channel=1,
            density_map=_meadow_clumps,
        ),
    ),
    props=(  # rocks, a little sunk into the ground
        ((6.0, 10.0), (1.2, 0.9, 1.0), (0.45, 0.44, 0.42), -0.1, "rock"),
        ((-9.0, -4.0), (2.0, 1.4, 1.6), (0.5, 0.48, 0.45), -0.15, "rock"),
        ((12.0, -12.0), (0.8, 0.6, 0.9), (0.42, 0.41, 0.4), -0.08, "rock"),
    ),
    paths={
        "walk": (
            CameraSpec((1.5, 3.2, 30.0), (0.0, 1.5, 10.0), 300.0),
            CameraSpec((0.0, 3.5, 10.0), (0.0, 1.5, -10.0), 300.0),
            CameraSpec((-10.0, 6.0, -20.0), (0.0, 1.0, 0.0), 300.0),
        )
    },
)


def _landscape_heights(width: int, height: int) -> np.ndarray:
    from core.heights import hills

    return hills(width, seed=11, period=5)[:height, :width]


SCENES["landscape"] = Scene(
    name="landscape",
    description="1024 × 1024 cells of 800-blade grass over large hills, volume to the horizon",
    params=PRESETS[DEFAULT_PRESET].replace(blade_count=800),
    grid=(1024, 1024),
    cameras={
        "valley": CameraSpec((0.0, 40.0, 480.0), (0.0, 25.0, 300.0), 2500.0, 0.1),
        "ridge": CameraSpec((-300.0, 120.0, -300.0), (0.0, 30.0, 0.0), 2500.0, 0.2),
    },
    default_camera="valley",
    # no image-based level: on large hills its flat macro-cells would split to single cells;
    # volume macro-cells stay on gentle ground too: a tall extruded cuboid leaves the rays many
    # empty steps above the grass before they reach it
    lod=LodConfig(
        (
            LodLevel("geometry", 0.0, 15.0),
            LodLevel("volume", 10.0, 60.0, slices=8, macro=8, max_unplanarity=5.0),
            LodLevel("volume", 45.0, 200.0, slices=2, macro=32, max_unplanarity=5.0),
            LodLevel("volume", 150.0, None, slices=1, macro=64, max_unplanarity=5.0),
        )
    ),
    mirror_seed=9,
    tint=0.3,
    map_size=(512, 512),
    height_map=_landscape_heights,
    height_scale=80.0,
    fog_distance=900.0,
    paths={
        "glide": (
            CameraSpec((0.0, 40.0, 480.0), (0.0, 25.0, 300.0), 2500.0, 0.1),
            CameraSpec((0.0, 60.0, 0.0), (100.0, 30.0, -200.0), 2500.0, 0.1),
            CameraSpec((300.0, 90.0, -300.0), (0.0, 30.0, 0.0), 2500.0, 0.2),
        )
    },
)
DEFAULT_SCENE = "meadow"


def get_scene(name: str) -> Scene:
    try:
        return SCENES[name]
    except KeyError:
        raise KeyError(
            f"unknown scene {name!r}; built-in scenes: {', '.join(sorted(SCENES))}"
        ) from None
