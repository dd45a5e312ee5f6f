"""The patch being designed: blade parameters, global density and how it is converted into
slices, announcing changes (psygnal)."""

from __future__ import annotations

from psygnal import Signal

from core.params import PatchParams, SliceParams


class PatchDesign:
    """Qt-free model. Views connect to `params_changed` / `density_changed` /
    `slices_changed`."""

    params_changed = Signal(object)
    density_changed = Signal(float)
    slices_changed = Signal(object)

    def __init__(
        self,
        params: PatchParams | None = None,
        density: float = 1.0,
        slices: SliceParams | None = None,
    ) -> None:
        self._params = params or PatchParams()
        self._density = float(density)
        self._slices = slices or SliceParams()

    @property
    def slices(self) -> SliceParams:
        return self._slices

    @slices.setter
    def slices(self, value: SliceParams) -> None:
        if not isinstance(value, SliceParams):
            raise TypeError("slices must be a SliceParams")
        if value != self._slices:
            self._slices = value
            self.slices_changed.emit(value)

    @property
    def params(self) -> PatchParams:
        return self._params

    @params.setter
    def params(self, value: PatchParams) -> None:
        if not isinstance(value, PatchParams):
            raise TypeError("params must be a PatchParams")
        if value != self._params:
            self._params = value
            self.params_changed.emit(value)

    @property
    def density(self) -> float:
        return self._density

    @density.setter
    def density(self, value: float) -> None:
        if not 0.0 <= value <= 1.0:
            raise ValueError(f"density = {value:g} is out of range; allowed 0 … 1")
        if value != self._density:
            self._density = float(value)
            self.density_changed.emit(self._density)
