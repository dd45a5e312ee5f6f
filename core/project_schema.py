"""The rules a project file's project.json must follow, as one msgspec schema: every field's
type (no coercion: a name that is a list, `clustered: "yes"` or `Infinity` is refused), its range,
finiteness (JSON has no NaN), bounded counts and sizes, and the relations between fields (near
< far, eye != target, the default camera among the cameras). docs/project-format.md lists them.

`decode(raw)` returns the validated `Project`, or raises msgspec.ValidationError /
msgspec.DecodeError whose message names the field (`$.terrain.columns`) and the rule.
"""

from __future__ import annotations

import dataclasses
from typing import Annotated, Literal, cast

import msgspec
from msgspec import Meta

from core.params import SLICE_COUNTS, PatchParams
from core.segments import TOLERANCE_PX

MAX_CELLS = 4096 * 4096  # terrain columns × rows (the quadtree's memory and build time)
MAX_SIDE = 16384
WORLD = 1.0e6  # |coordinate| of cameras and props
MAX_PROPS = 1000
MAX_CAMERAS = 256
MAX_PATHS = 64
MAX_PATH_KEYS = 1000
MAX_LEVELS = 16

Finite = Annotated[float, Meta(ge=-WORLD, le=WORLD)]
Unit = Annotated[float, Meta(ge=0.0, le=1.0)]
Name = Annotated[str, Meta(min_length=1, max_length=200)]
Vec3 = tuple[Finite, Finite, Finite]
Colour = tuple[Unit, Unit, Unit]
LightColour = tuple[
    Annotated[float, Meta(ge=0.0, le=4.0)],
    Annotated[float, Meta(ge=0.0, le=4.0)],
    Annotated[float, Meta(ge=0.0, le=4.0)],
]


def _params_struct() -> type:
    """PatchParams as a Struct: each field's type and the range of its spec (core/params.py)."""
    fields = []
    for f in dataclasses.fields(PatchParams):
        if f.name.endswith("_color"):
            kind: object = Colour
        elif f.type in ("bool", bool):
            kind = bool
        else:
            spec = f.metadata["spec"]
            base = int if spec.integer else float
            kind = Annotated[base, Meta(ge=spec.low, le=spec.high)]
        fields.append((f.name, kind))
    return msgspec.defstruct("Params", fields, forbid_unknown_fields=True)


Params = _params_struct()


class Level(msgspec.Struct, forbid_unknown_fields=True):
    representation: Literal["geometry", "volume", "image"]
    begin: Annotated[float, Meta(ge=0.0, le=WORLD)] = 0.0
    end: Annotated[float, Meta(gt=0.0, le=WORLD)] | None = None
    slices: Literal[SLICE_COUNTS] = 8  # type: ignore[valid-type]
    macro: Annotated[int, Meta(ge=1, le=4096)] = 1
    max_unplanarity: Annotated[float, Meta(ge=0.0, le=WORLD)] | None = None


class Lod(msgspec.Struct, forbid_unknown_fields=True):
    levels: Annotated[list[Level], Meta(min_length=1, max_length=MAX_LEVELS)]
    epsilon: Annotated[float, Meta(ge=0.0, le=1.0)] = 0.05
    silhouettes: bool = False
    # the view height (pixels) the distances hold for; none: world units (core/lod.py)
    view_height: Annotated[float, Meta(ge=16.0, le=16384.0)] | None = None
    segment_tolerance: Annotated[float, Meta(ge=0.0, le=8.0)] = TOLERANCE_PX


class Grass(msgspec.Struct, forbid_unknown_fields=True):
    name: Name
    params: Params  # type: ignore[valid-type]
    lod: Lod
    channel: Annotated[int, Meta(ge=1, le=3)]


class Terrain(msgspec.Struct, forbid_unknown_fields=True):
    columns: Annotated[int, Meta(ge=1, le=MAX_SIDE)]
    rows: Annotated[int, Meta(ge=1, le=MAX_SIDE)]
    mirror_seed: Annotated[int, Meta(ge=0, le=2**31 - 1)] | None = None
    height_scale: Annotated[float, Meta(ge=0.0, le=10_000.0)] = 0.0

    def __post_init__(self) -> None:
        if self.columns * self.rows > MAX_CELLS:
            raise ValueError(
                f"terrain {self.columns} × {self.rows} has more than {MAX_CELLS:,} cells"
            )


class Camera(msgspec.Struct, forbid_unknown_fields=True):
    eye: Vec3
    target: Vec3
    far: Annotated[float, Meta(gt=0.0, le=1.0e7)]
    near: Annotated[float, Meta(gt=0.0, le=1.0e7)]

    def __post_init__(self) -> None:
        if not self.near < self.far:
            raise ValueError(f"a camera's near ({self.near:g}) must be less than far")
        if self.eye == self.target:
            raise ValueError("a camera's eye and target must differ")


class Light(msgspec.Struct, forbid_unknown_fields=True):
    sun_elevation: Annotated[float, Meta(ge=-10.0, le=90.0)] = 50.0
    sun_azimuth: Annotated[float, Meta(ge=-720.0, le=720.0)] = 135.0
    sun_color: LightColour = (1.0, 0.96, 0.86)
    ambient_color: LightColour = (0.36, 0.42, 0.52)
    translucency: Unit = 0.35
    blade_ao_impact: Unit = 0.6
    blade_ao_height: Annotated[float, Meta(gt=0.0, le=100.0)] = 0.3
    blade_shadows: bool = False
    shadow_strength: Unit = 0.6


class Wind(msgspec.Struct, forbid_unknown_fields=True):
    """core/wind.py Wind, whose ranges these are."""

    enabled: bool = False
    direction: Annotated[float, Meta(ge=-360.0, le=360.0)] = 30.0
    speed: Annotated[float, Meta(ge=0.0, le=30.0)] = 2.0
    gust_strength: Annotated[float, Meta(ge=0.0, le=0.9)] = 0.35
    gust_scale: Annotated[float, Meta(ge=0.5, le=200.0)] = 8.0
    turbulence_strength: Annotated[float, Meta(ge=0.0, le=0.5)] = 0.08
    turbulence_scale: Annotated[float, Meta(ge=0.1, le=50.0)] = 1.5
    blade_reach: Annotated[float, Meta(ge=1.0, le=2.0)] = 1.4


class Slices(msgspec.Struct, forbid_unknown_fields=True):
    slices: Annotated[int, Meta(ge=1, le=32)] = 8
    width: Annotated[int, Meta(ge=16, le=2048)] = 256
    height: Annotated[int, Meta(ge=8, le=1024)] = 64
    top: Annotated[int, Meta(ge=16, le=2048)] = 128


class SpeciesKind(msgspec.Struct, forbid_unknown_fields=True):
    """core/species.py SpeciesTuning: a reference colour in HSV (none: the design's), a weight
    per component, the exponent."""

    weights: tuple[
        Annotated[float, Meta(ge=0.0, le=100.0)],
        Annotated[float, Meta(ge=0.0, le=100.0)],
        Annotated[float, Meta(ge=0.0, le=100.0)],
    ] = (1.0, 1.0, 1.0)
    exponent: Annotated[float, Meta(ge=0.1, le=32.0)] = 4.0
    reference: Colour | None = None

    def __post_init__(self) -> None:
        if not any(self.weights):
            raise ValueError("a species rule's weights cannot all be 0")


class Species(msgspec.Struct, forbid_unknown_fields=True):
    kinds: Annotated[list[SpeciesKind], Meta(max_length=4)] = []
    soil: SpeciesKind = msgspec.field(default_factory=SpeciesKind)


Span = tuple[Finite, Finite]


class PaintRule(msgspec.Struct, forbid_unknown_fields=True):
    """core/paint_rule.py PaintRule: where the brush takes."""

    slope: (
        tuple[Annotated[float, Meta(ge=0.0, le=90.0)], Annotated[float, Meta(ge=0.0, le=90.0)]]
        | None
    ) = None
    height: Span | None = None
    soft_slope: Annotated[float, Meta(ge=0.0, le=45.0)] = 2.0
    soft_height: Annotated[float, Meta(ge=0.0, le=1.0e4)] = 0.1

    def __post_init__(self) -> None:
        for name, span in (("slope", self.slope), ("height", self.height)):
            if span is not None and span[0] > span[1]:
                raise ValueError(f"paint_rule.{name}: the least first")


# a prop: [[x, z], [w, h, d], [r, g, b]], an optional lift and an optional shape
PropRow = Annotated[
    list[Annotated[list[Finite], Meta(max_length=3)] | Finite | Literal["box", "rock"]],
    Meta(max_length=5),
]


class Project(msgspec.Struct, forbid_unknown_fields=True):
    format: Literal["sward-project"]
    version: int
    name: Annotated[str, Meta(max_length=200)]
    params: Params  # type: ignore[valid-type]
    terrain: Terrain
    lod: Lod
    cameras: Annotated[dict[Name, Camera], Meta(min_length=1, max_length=MAX_CAMERAS)]
    default_camera: Name
    description: Annotated[str, Meta(max_length=10_000)] = ""
    density: Unit = 1.0
    grass: Annotated[list[Grass], Meta(max_length=3)] = []
    paths: Annotated[
        dict[Name, Annotated[list[Camera], Meta(min_length=2, max_length=MAX_PATH_KEYS)]],
        Meta(max_length=MAX_PATHS),
    ] = {}
    props: Annotated[list[PropRow], Meta(max_length=MAX_PROPS)] = []
    fog_distance: Annotated[float, Meta(gt=0.0, le=1.0e7)] = 160.0
    light: Light = msgspec.field(default_factory=Light)
    slices: Slices = msgspec.field(default_factory=Slices)
    wind: Wind = msgspec.field(default_factory=Wind)
    species: Species = msgspec.field(default_factory=Species)
    paint_rule: PaintRule = msgspec.field(default_factory=PaintRule)

    def __post_init__(self) -> None:
        if self.default_camera not in self.cameras:
            raise ValueError(f"default_camera {self.default_camera!r} is not one of the cameras")
        if len(self.species.kinds) > 1 + len(self.grass):
            raise ValueError(
                f"species.kinds has {len(self.species.kinds)} rules for {1 + len(self.grass)} "
                "grass types"
            )
        for i, row in enumerate(self.props):
            shapes = [len(v) if isinstance(v, list) else 0 for v in row]
            tail = [isinstance(v, str) for v in row[3:]]  # lift, shape
            if shapes[:3] != [2, 3, 3] or tail not in ([], [False], [False, True]):
                raise ValueError(
                    f"props[{i}] must be [[x, z], [w, h, d], [r, g, b], lift, shape]"
                    ' (shape "box" or "rock")'
                )
            size, colour = cast(list, row[1]), cast(list, row[2])
            if min(size) <= 0 or not all(0.0 <= c <= 1.0 for c in colour):
                raise ValueError(f"props[{i}]: size must be positive, colour in 0 … 1")


def decode(raw: bytes) -> Project:
    return msgspec.json.decode(raw, type=Project)


class Head(msgspec.Struct):
    format: object = None
    version: object = None


def head(raw: bytes) -> Head:
    """`format` and `version` alone (to tell another file, or an older or newer project, from a
    broken one); malformed JSON raises msgspec.DecodeError."""
    return msgspec.json.decode(raw, type=Head)
