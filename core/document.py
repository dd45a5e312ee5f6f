"""The open project as one Qt-free, evented document: its grass types (blade parameters, LOD
levels, density-map channel), the design maps, the global density, how patches become slices,
the light, the terrain, the props, the named cameras and camera paths. It is the only copy: the
designer's panels change it through undoable commands, loading builds it (core/project_file.py),
saving serialises it, and the renderer follows its events (render/binding.py).

Every setter announces a change only when the value changed; `events` is a psygnal group, so a
view connects `document.events.<name>` without Qt.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from psygnal import Signal, SignalGroup

from core.camera import Camera
from core.design_maps import LAYER_INDEX, DesignMaps
from core.evented import Field, check_type
from core.heights import bilinear
from core.lighting import Lighting
from core.lod import LodConfig
from core.paint_rule import PaintRule
from core.params import PatchParams, SliceParams
from core.paths import sample_path
from core.props import boxes
from core.species import Species
from core.terrain import Terrain
from core.wind import Wind

MAIN_GRASS = "main grass"  # the first grass type's name (density channel 0)


@dataclass(frozen=True)
class CameraSpec:
    eye: tuple[float, float, float]
    target: tuple[float, float, float]
    far: float = 500.0
    near: float = 0.02

    def __post_init__(self) -> None:
        if not 0.0 < self.near < self.far:
            raise ValueError(f"a camera needs 0 < near < far, got near {self.near}, far {self.far}")
        if tuple(self.eye) == tuple(self.target):
            raise ValueError("a camera's eye and target must differ")

    def camera(self) -> Camera:
        return Camera.from_eye_target(self.eye, self.target, near=self.near, far=self.far)


@dataclass(frozen=True)
class GrassType:
    """One grass type on the terrain (thesis 6.4.5): its patch, LOD levels and the channel of the
    density map it grows by; it shares the terrain and the light and colour maps."""

    name: str
    params: PatchParams
    lod: LodConfig = field(default_factory=LodConfig)
    channel: int = 0

    def __post_init__(self) -> None:
        if not 0 <= self.channel <= 3:
            raise ValueError(f"grass type {self.name}: density channel must be 0 … 3")


@dataclass(frozen=True)
class Prop:
    """A box or a rock standing in the grass: centre (x, z), size (w, h, d), colour, lift above
    the ground under its centre (a crossbar); `shape` "box" or "rock" (core/props.py)."""

    position: tuple[float, float]
    size: tuple[float, float, float]
    color: tuple[float, float, float]
    lift: float = 0.0
    shape: str = "box"


@dataclass(frozen=True)
class TerrainSpec:
    """The grid of cells and how its ground is shaped (the heights are the height map)."""

    columns: int
    rows: int
    mirror_seed: int | None = None  # aperiodic tiling (thesis 6.3); None: every cell alike
    height_scale: float = 0.0  # world units of the height map's 1 (thesis 6.4.4)

    def __post_init__(self) -> None:
        if not (1 <= self.columns <= 16384 and 1 <= self.rows <= 16384):
            raise ValueError(f"terrain {self.columns} × {self.rows}: each side must be 1 … 16384")
        if not 0.0 <= self.height_scale <= 10_000.0:
            raise ValueError(f"height scale {self.height_scale:g} is out of range; 0 … 10000")


def _check_density(_doc: Document, value: float) -> float:
    if not 0.0 <= value <= 1.0:
        raise ValueError(f"density = {value:g} is out of range; allowed 0 … 1")
    return float(value)


def _check_cameras(doc: Document, value: dict) -> dict[str, CameraSpec]:
    value = dict(value)
    if not all(isinstance(spec, CameraSpec) for spec in value.values()):
        raise TypeError("cameras must be CameraSpecs")
    if getattr(doc, "_default_camera", None) not in (None, *value):
        raise ValueError(f"the default camera {doc.default_camera!r} cannot be removed")
    return value


def _check_default_camera(doc: Document, value: str) -> str:
    if value not in doc.cameras:
        raise ValueError(f"default camera {value!r} is not one of the cameras")
    return value


def _check_paths(_doc: Document, value: dict) -> dict[str, tuple[CameraSpec, ...]]:
    value = {name: tuple(keys) for name, keys in dict(value).items()}
    if not all(isinstance(k, CameraSpec) for keys in value.values() for k in keys):
        raise TypeError("camera paths must be CameraSpecs")
    return value


def _check_props(_doc: Document, value: tuple) -> tuple[Prop, ...]:
    value = tuple(value)
    if not all(isinstance(prop, Prop) for prop in value):
        raise TypeError("props must be Props")
    return value


def _check_species(doc: Document, value: Species) -> Species:
    value = check_type(Species)(doc, value)
    if len(value.kinds) > len(doc.grass_types):
        raise ValueError(
            f"species rules for {len(value.kinds)} grass types; the project has "
            f"{len(doc.grass_types)}"
        )
    return value


def _check_terrain_spec(doc: Document, value: TerrainSpec) -> TerrainSpec:
    check_type(TerrainSpec)(doc, value)
    old = getattr(doc, "_terrain_spec", None)
    if old is not None and (value.columns, value.rows) != (old.columns, old.rows):
        raise ValueError("the terrain's size is fixed with its maps")
    if value != old:
        doc._terrain = None  # built again from the new spec when next asked for
    return value


class Document:
    name = Field(check_type(str), "The project's name.")
    description = Field(check_type(str))
    density = Field(_check_density, "The global density, 0 … 1.")
    slices = Field(check_type(SliceParams), "How patches become slices.")
    light = Field(check_type(Lighting), "Sun, ambient light and fog (core/lighting.py).")
    wind = Field(check_type(Wind), "The wind over the terrain (core/wind.py).")
    cameras = Field(_check_cameras, "The named cameras, bookmarks among them.")
    default_camera = Field(_check_default_camera)
    paths = Field(_check_paths, "Camera paths: name -> key cameras.")
    props = Field(_check_props, "Boxes and rocks standing in the grass.")
    terrain_spec = Field(_check_terrain_spec, "The grid of cells and how its ground is shaped.")
    species = Field(_check_species, "How a colour map places the grass types (core/species.py).")
    paint_rule = Field(check_type(PaintRule), "Where the brush takes: slope, height.")

    def __init__(
        self,
        name: str,
        grass_types: list[GrassType] | tuple[GrassType, ...],
        terrain: TerrainSpec,
        maps: DesignMaps,
        *,
        description: str = "",
        density: float = 1.0,
        slices: SliceParams | None = None,
        light: Lighting | None = None,
        cameras: dict[str, CameraSpec] | None = None,
        default_camera: str = "default",
        paths: dict[str, tuple[CameraSpec, ...]] | None = None,
        props: tuple[Prop, ...] = (),
        wind: Wind | None = None,
        species: Species | None = None,
        paint_rule: PaintRule | None = None,
    ) -> None:
        if not 1 <= len(grass_types) <= 4:
            raise ValueError(f"a project has 1 … 4 grass types, not {len(grass_types)}")
        channels = [kind.channel for kind in grass_types]
        if len(set(channels)) != len(channels):
            raise ValueError("two grass types share one density channel")
        self.events = DocumentEvents()
        self._grass = list(grass_types)
        self._terrain: Terrain | None = None
        self.maps = maps
        self.name, self.description = name, description
        self.terrain_spec = terrain
        self.density = density
        self.slices = slices or SliceParams()
        self.light = light or Lighting()
        self.wind = wind or Wind()
        self.cameras = cameras or {"default": CameraSpec((0.0, 5.0, 10.0), (0.0, 0.0, 0.0))}
        self.default_camera = default_camera
        self.paths = paths or {}
        self.props = props
        self.species = species or Species()
        self.paint_rule = paint_rule or PaintRule()

    # -- one change, made again --------------------------------------------------------------
    def apply(self, name: str, args: tuple) -> None:
        """Make a change that another document's `events.all` announced (the event's name and
        arguments): the render processes' copies follow the window's document through this one
        method. The terrain event carries no arguments here: the copy rebuilds its own."""
        if name == "params":
            self.set_params(*args)
        elif name == "lod":
            self.set_lod(*args)
        elif name == "terrain":
            self.rebuild_terrain()
        elif isinstance(getattr(Document, name, None), Field):
            setattr(self, name, *args)
        else:
            raise ValueError(f"no document field {name!r}")

    # -- grass types -------------------------------------------------------------------------
    @property
    def grass_types(self) -> tuple[GrassType, ...]:
        return tuple(self._grass)

    @property
    def grass_names(self) -> list[str]:
        return [kind.name for kind in self._grass]

    def params(self, index: int) -> PatchParams:
        return self._grass[index].params

    def lod(self, index: int) -> LodConfig:
        return self._grass[index].lod

    def set_params(self, index: int, params: PatchParams) -> None:
        if not isinstance(params, PatchParams):
            raise TypeError("blade parameters must be a PatchParams")
        kind = self._grass[index]
        if params != kind.params:
            self._grass[index] = GrassType(kind.name, params, kind.lod, kind.channel)
            self.events.params.emit(index, params)

    def set_lod(self, index: int, lod: LodConfig) -> None:
        if not isinstance(lod, LodConfig):
            raise TypeError("a grass type's LOD levels must be a LodConfig")
        kind = self._grass[index]
        if lod != kind.lod:
            self._grass[index] = GrassType(kind.name, kind.params, lod, kind.channel)
            self.events.lod.emit(index, lod)

    @property
    def lods(self) -> list[LodConfig]:
        """Every grass type's LodConfig, in the types' order."""
        return [kind.lod for kind in self._grass]

    def set_lods(self, lods: list[LodConfig]) -> None:
        """Every grass type's LodConfig at once (one event per type that changes)."""
        if len(lods) != len(self._grass):
            raise ValueError(f"{len(lods)} LOD configurations for {len(self._grass)} grass types")
        for index, lod in enumerate(lods):
            self.set_lod(index, lod)

    # -- cameras -----------------------------------------------------------------------------
    def camera(self, name: str | None = None) -> Camera:
        name = name or self.default_camera
        if name not in self.cameras:
            raise KeyError(name)
        return self.cameras[name].camera()

    def path_cameras(self, name: str, frames: int) -> list[Camera]:
        """`frames` cameras spread along the named path."""
        keys = self.paths[name]
        near = min(k.near for k in keys)
        far = max(k.far for k in keys)
        return [
            Camera.from_eye_target(eye, target, near=near, far=far)
            for eye, target in sample_path([(k.eye, k.target) for k in keys], frames)
        ]

    # -- terrain and props -------------------------------------------------------------------
    def heights(self) -> np.ndarray | None:
        """The height map as the GPU holds it (half floats), so that the terrain's bounding
        volumes and the rendered ground agree to the last bit; None on flat terrain."""
        if self.terrain_spec.height_scale <= 0:
            return None
        h = self.maps.stack[LAYER_INDEX["height"], :, :, 0]
        return h.astype(np.float16).astype(np.float32)

    @property
    def terrain(self) -> Terrain:
        """The cells and their quadtree (core/terrain.py), built once and again only by
        `rebuild_terrain` (after the height map changed)."""
        if self._terrain is None:
            t = self.terrain_spec
            self._terrain = Terrain.centred(
                t.columns,
                t.rows,
                mirror_seed=t.mirror_seed,
                heights=self.heights(),
                height_scale=t.height_scale,
                grass_height=self._grass[0].params.patch_height,
            )
        return self._terrain

    def set_heights(self, values: np.ndarray | None, height_scale: float) -> None:
        """A new height map ((rows, columns, 1) at the maps' size; None keeps the map) and
        height scale. Named cameras and the keys of camera paths keep the height above the
        ground under their eye (eye and target move up or down together), so a view made for
        the old ground does not end up inside a new hill."""

        def ground(spec: CameraSpec) -> float:
            return self.ground_at(spec.eye[0], spec.eye[2])

        specs = [*self.cameras.values(), *(k for keys in self.paths.values() for k in keys)]
        before = [ground(s) for s in specs]
        if values is not None:
            self.maps.write("height", 0, 0, values)
        self.terrain_spec = replace(self.terrain_spec, height_scale=height_scale)
        self.rebuild_terrain()

        def moved(spec: CameraSpec, old: float) -> CameraSpec:
            dy = ground(spec) - old
            eye, target = spec.eye, spec.target
            return replace(
                spec,
                eye=(eye[0], eye[1] + dy, eye[2]),
                target=(target[0], target[1] + dy, target[2]),
            )

        shifted = iter([moved(s, old) for s, old in zip(specs, before, strict=True)])
        self.cameras = {name: next(shifted) for name in self.cameras}
        self.paths = {name: tuple(next(shifted) for _ in keys) for name, keys in self.paths.items()}

    def rebuild_terrain(self) -> Terrain:
        """Bounding volumes and ground ranges follow a changed height map."""
        self._terrain = None
        terrain = self.terrain
        self.events.terrain.emit(terrain)
        return terrain

    def ground_at(self, x: float, z: float) -> float:
        """World height of the ground at world (x, z)."""
        heights = self.heights()
        if heights is None:
            return 0.0
        t = self.terrain_spec
        u, v = (x + t.columns / 2) / t.columns, (z + t.rows / 2) / t.rows
        return float(bilinear(heights, np.array([u]), np.array([v]))[0]) * t.height_scale

    def prop_boxes(self) -> np.ndarray:
        """The props, standing on the ground where they are (their lift added to it)."""
        return boxes(
            (p.position, p.size, p.color, p.lift + self.ground_at(*p.position), p.shape)
            for p in self.props
        )

    # -- comparison --------------------------------------------------------------------------
    def same_as(self, other: Document) -> bool:
        """Equal in everything a project file keeps, the maps to the last bit."""
        return (
            self._fields() == other._fields()
            and self.maps.stack.shape == other.maps.stack.shape
            and bool(np.array_equal(self.maps.stack, other.maps.stack))
        )

    def _fields(self) -> tuple:
        return (tuple(self._grass), *(getattr(self, f"_{name}") for name in FIELDS))


FIELDS = tuple(name for name, value in vars(Document).items() if isinstance(value, Field))

# One signal per document field (Document's `Field`s) and three more: a grass type's blade
# parameters or LOD levels changed (its index, the new value), and the terrain was rebuilt after
# the height map changed (`Document.rebuild_terrain`). `events.all` relays every one of them:
# the render processes follow the document through it.
DocumentEvents = type(
    "DocumentEvents",
    (SignalGroup,),
    {
        "params": Signal(int, object),  # grass type, PatchParams
        "lod": Signal(int, object),  # grass type, LodConfig
        "terrain": Signal(object),  # Terrain, rebuilt after the height map changed
        **{name: Signal(object) for name in FIELDS},
    },
)
