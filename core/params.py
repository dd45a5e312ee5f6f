"""Blade parameters of a grass patch (thesis 4.1) and the presets of Fig. 4.1.

Lengths are in patch units: the patch is the unit square of ground, so a blade length of 0.3
means 30 % of a cell's edge. Angles are in degrees.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any


class ParameterError(ValueError):
    """A parameter value outside its allowed range; the message names the parameter."""


@dataclass(frozen=True)
class Spec:
    """Allowed range and user-facing description of one parameter."""

    low: float
    high: float
    label: str
    unit: str = ""
    integer: bool = False


def _f(default: Any, low: float, high: float, label: str, unit: str = "", integer: bool = False):
    return field(default=default, metadata={"spec": Spec(low, high, label, unit, integer)})


@dataclass(frozen=True)
class PatchParams:
    """Everything that decides the geometry and look of one procedural grass patch."""

    blade_count: int = _f(2400, 1, 100_000, "Blade count", integer=True)
    length_min: float = _f(0.18, 0.005, 2.0, "Length min", "patch units")
    length_max: float = _f(0.30, 0.005, 2.0, "Length max", "patch units")
    width_min: float = _f(0.010, 0.001, 0.2, "Width min", "patch units")
    width_max: float = _f(0.016, 0.001, 0.2, "Width max", "patch units")
    tilt_min: float = _f(0.0, 0.0, 85.0, "Tilt min", "°")
    tilt_max: float = _f(35.0, 0.0, 85.0, "Tilt max", "°")
    bending: float = _f(0.35, 0.0, 0.95, "Bending (gravity)", "× length")
    subdivisions: int = _f(4, 1, 16, "Subdivisions", integer=True)
    blade_color_variation: float = _f(0.25, 0.0, 1.0, "Blade colour variation")
    vertex_light_variation: float = _f(0.15, 0.0, 1.0, "Vertex light variation")
    root_color: tuple[float, float, float] = (0.16, 0.30, 0.06)
    tip_color: tuple[float, float, float] = (0.52, 0.68, 0.22)
    dry_color: tuple[float, float, float] = (0.62, 0.58, 0.26)
    clustered: bool = True
    cluster_sigma: float = _f(0.12, 0.0, 10.0, "Clustering sigma")
    patch_height: float = _f(0.40, 0.01, 2.0, "Patch height", "patch units")
    seed: int = _f(1, 0, 2**31 - 1, "Random seed", integer=True)

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            spec: Spec | None = f.metadata.get("spec")
            if spec is not None:
                _check_scalar(f.name, value, spec)
            elif f.name.endswith("_color"):
                _check_color(f.name, value)
        for lo, hi in (
            ("length_min", "length_max"),
            ("width_min", "width_max"),
            ("tilt_min", "tilt_max"),
            # the slices and the cuboids hold the patch up to its height: a longer blade would
            # be drawn cut off there by the volume and image-based grass
            ("length_max", "patch_height"),
        ):
            if getattr(self, lo) > getattr(self, hi):
                raise ParameterError(
                    f"{lo} ({getattr(self, lo):g}) must not exceed {hi} ({getattr(self, hi):g})"
                )

    def replace(self, **changes: Any) -> PatchParams:
        """A copy with some fields changed; validated like any new instance."""
        unknown = set(changes) - {f.name for f in dataclasses.fields(self)}
        if unknown:
            raise ParameterError(f"unknown patch parameter(s): {', '.join(sorted(unknown))}")
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> PatchParams:
        known = {f.name: f for f in dataclasses.fields(cls)}
        unknown = set(data) - set(known)
        if unknown:
            raise ParameterError(f"unknown patch parameter(s): {', '.join(sorted(unknown))}")
        clean: dict[str, Any] = {
            k: tuple(v) if k.endswith("_color") else v for k, v in data.items()
        }
        return cls(**clean)

    @staticmethod
    def spec(name: str) -> Spec:
        for f in dataclasses.fields(PatchParams):
            if f.name == name and "spec" in f.metadata:
                return f.metadata["spec"]
        raise KeyError(name)


def _check_scalar(name: str, value: Any, spec: Spec) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(f"{name} must be a number, got {value!r}")
    if spec.integer and int(value) != value:
        raise ParameterError(f"{name} must be a whole number, got {value!r}")
    if not (spec.low <= value <= spec.high):
        raise ParameterError(
            f"{name} = {value:g} is out of range; allowed {spec.low:g} … {spec.high:g}"
            + (f" {spec.unit}" if spec.unit else "")
        )


def _check_color(name: str, value: Any) -> None:
    ok = (
        isinstance(value, tuple)
        and len(value) == 3
        and all(isinstance(c, (int, float)) and 0.0 <= c <= 1.0 for c in value)
    )
    if not ok:
        raise ParameterError(f"{name} must be three numbers in 0 … 1 (r, g, b), got {value!r}")


# Presets after thesis Fig. 4.1: (a) medium long grass, (b) short-cut turf,
# (c) long thin meadow grass, (d) utility lawn.
PRESETS: dict[str, PatchParams] = {
    "medium long grass": PatchParams(),
    "short-cut turf": PatchParams(
        blade_count=5000,
        length_min=0.05,
        length_max=0.08,
        width_min=0.008,
        width_max=0.012,
        tilt_min=0.0,
        tilt_max=20.0,
        bending=0.15,
        subdivisions=2,
        blade_color_variation=0.12,
        vertex_light_variation=0.10,
        root_color=(0.12, 0.30, 0.06),
        tip_color=(0.36, 0.62, 0.16),
        cluster_sigma=1.0,
        clustered=False,
        patch_height=0.10,
    ),
    "long thin meadow grass": PatchParams(
        blade_count=1600,
        length_min=0.35,
        length_max=0.65,
        width_min=0.005,
        width_max=0.009,
        tilt_min=5.0,
        tilt_max=45.0,
        bending=0.45,
        subdivisions=6,
        blade_color_variation=0.45,
        vertex_light_variation=0.2,
        root_color=(0.20, 0.30, 0.08),
        tip_color=(0.62, 0.66, 0.30),
        cluster_sigma=0.12,
        clustered=True,
        patch_height=0.70,
    ),
    "utility lawn": PatchParams(
        blade_count=3200,
        length_min=0.10,
        length_max=0.18,
        width_min=0.010,
        width_max=0.018,
        tilt_min=0.0,
        tilt_max=30.0,
        bending=0.25,
        subdivisions=3,
        blade_color_variation=0.3,
        vertex_light_variation=0.15,
        root_color=(0.18, 0.32, 0.07),
        tip_color=(0.45, 0.64, 0.2),
        cluster_sigma=0.3,
        clustered=True,
        patch_height=0.22,
    ),
}
DEFAULT_PRESET = "medium long grass"


SLICE_COUNTS = (1, 2, 4, 8, 16)  # the thesis's choices per direction (Table 7.1, ch. 7)
SLICE_SIZES = ((128, 32), (256, 64), (512, 128))
TOP_SIZES = (64, 128, 256, 512, 1024)


@dataclass(frozen=True)
class SliceParams:
    """How a patch is converted into slices (thesis 4.2.1): vertical slices per direction, their
    texture size, and the horizontal slice's size. Sizes are powers of two (the mip chain)."""

    slices: int = 8
    width: int = 256
    height: int = 64
    top: int = 128

    def __post_init__(self) -> None:
        if not 1 <= self.slices <= 32:
            raise ParameterError(f"slices = {self.slices} is out of range; allowed 1 … 32")
        for name, value, low, high in (
            ("slice width", self.width, 16, 2048),
            ("slice height", self.height, 8, 1024),
            ("top slice size", self.top, 16, 2048),
        ):
            if not low <= value <= high or value & (value - 1):
                raise ParameterError(
                    f"{name} = {value} must be a power of two between {low} and {high}"
                )

    def replace(self, **changes: Any) -> SliceParams:
        return dataclasses.replace(self, **changes)
