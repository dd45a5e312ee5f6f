"""Converts the viewport's patch into slices without freezing the window: one slice is captured
per event-loop turn on the viewport's GL context, the mip chains are computed on a worker thread,
and the textures are uploaded back on the GL thread. The newest request wins; until it is done,
the slices of the previous patch stay in use."""

from __future__ import annotations

from PySide6.QtCore import QObject, QRunnable, Qt, QThreadPool, QTimer, Signal

from render.slices import SliceLevels, SliceTextures


class _Delivery(QObject):
    ready = Signal(int, object)  # generation, SliceLevels


class _ComputeLevels(QRunnable):
    def __init__(self, generation: int, sliced, delivery: _Delivery) -> None:
        super().__init__()
        self.generation, self.sliced, self.delivery = generation, sliced, delivery

    def run(self) -> None:
        self.delivery.ready.emit(self.generation, SliceLevels.compute(self.sliced))


class SliceBuilder(QObject):
    progress = Signal(int, int)  # captures done, total; (0, 0) when idle again
    finished = Signal()

    def __init__(self, viewport) -> None:
        super().__init__(viewport)
        self.viewport = viewport
        self._timer = QTimer(self)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self._step)
        self._pool = QThreadPool(self)
        self._pool.setMaxThreadCount(1)
        self._delivery = _Delivery()
        self._delivery.ready.connect(self._on_levels, Qt.ConnectionType.QueuedConnection)
        self._generation = 0
        self._steps = None
        self._target = None  # (patch, SliceParams, grass_type) being converted
        self._pending = False  # levels on the worker

    @property
    def busy(self) -> bool:
        return self._timer.isActive() or self._pending

    def schedule(self) -> None:
        """Start converting if the viewport's mode needs slices that do not exist yet."""
        pipeline = self.viewport.pipeline
        if pipeline is None or not pipeline.needs_slices:
            self._cancel()
            return
        grass_type, slices = pipeline.missing()[0]
        patch = pipeline.grass_types[grass_type].patch
        params = pipeline.slice_params.replace(slices=slices)
        if self.busy and self._target[0] is patch and self._target[1:] == (params, grass_type):
            return  # already on it
        self._generation += 1
        self._target = (patch, params, grass_type)
        self._pending = False
        self.viewport.makeCurrent()  # the converter's GL objects are made on first use
        try:
            converter = pipeline.converter
        finally:
            self.viewport.doneCurrent()
        self._steps = converter.steps(
            patch, params.slices, (params.width, params.height), params.top
        )
        self._timer.start()

    def _cancel(self) -> None:
        self._timer.stop()
        self._steps = None
        if self._pending or self._target is not None:
            self._generation += 1  # a result still on the worker is dropped
            self._pending = False
            self._target = None
            self.progress.emit(0, 0)

    def _step(self) -> None:
        if self._steps is None:
            self._timer.stop()
            return
        self.viewport.makeCurrent()
        try:
            done, total = next(self._steps)
        except StopIteration as finished:
            self._timer.stop()
            self._steps = None
            self._pending = True
            self._pool.start(_ComputeLevels(self._generation, finished.value, self._delivery))
            return
        finally:
            self.viewport.doneCurrent()
        self.progress.emit(done, total)

    def _on_levels(self, generation: int, levels: SliceLevels) -> None:
        pipeline = self.viewport.pipeline
        if generation != self._generation or pipeline is None:
            return  # outdated: a newer patch or other parameters were asked for meanwhile
        self.viewport.makeCurrent()
        try:
            textures = SliceTextures.from_levels(pipeline.ctx, levels)
            pipeline.set_slice_textures(textures, *self._target)
        finally:
            self.viewport.doneCurrent()
        self._pending = False
        self._target = None
        self.progress.emit(0, 0)
        self.finished.emit()
        self.viewport.update()
        self.schedule()  # the parameters may have moved on meanwhile

    def wait(self) -> None:
        self._timer.stop()
        self._steps = None
        self._pool.waitForDone()
