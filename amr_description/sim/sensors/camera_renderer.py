# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The cameras' render thread: MuJoCo ``Renderer`` s fed with copies of the simulation's state.

At a due instant the simulation thread copies ``qpos``, ``mocap_pos`` and ``mocap_quat`` into
a job; :class:`CameraRenderer`'s thread renders every camera output wanted at that instant
and publishes it (:mod:`amr_description.sim.sensors.camera` makes the messages). The
simulation waits only while an earlier job has not been started, so every due frame is
rendered, at most one frame behind. No OpenGL context exists until a camera is rendered.
"""

import copy
import threading

import numpy as np


def depth_from_buffer(depth, near, far):
    """
    Return REP 117 depths (m) from MuJoCo's linearized depth buffer.

    :param depth: (H, W) float32, m along the optical axis; MuJoCo writes the far plane where
        nothing was drawn.
    :param near: m, closer hits are -inf.
    :param far: m, the far plane: hits at or beyond it are +inf.
    :returns: (H, W) float32.
    """
    out = depth.astype(np.float32, copy=True)
    out[depth >= far * (1.0 - 1e-5)] = np.inf
    out[depth < near] = -np.inf
    return out


class Frame:
    """
    What one render of a camera produced, before its messages are made.

    :ivar rgb: (H, W, 3) uint8 or None.
    :ivar depth: (H, W) float32 m (REP 117) or None.
    """

    def __init__(self, rgb=None, depth=None):
        """Keep the arrays."""
        self.rgb = rgb
        self.depth = depth


class _Job:
    """One instant's renders: the state copy and, per capture, its outputs and publishers."""

    __slots__ = ('model', 'qpos', 'mocap_pos', 'mocap_quat', 't', 'wanted')

    def __init__(self, t):
        self.t = t
        self.wanted = {}  # capture -> list of (output, publish)
        self.model = None


class CameraRenderer:
    """
    The render thread of a simulator's cameras (module docstring).

    Its OpenGL context (through ``mujoco.Renderer``, one per image size, reused; the
    offscreen buffer is sized for the largest registered camera) is made by the render
    thread at its first job, never when no camera renders. A model change (a spawn) makes
    new renderers over a private copy of the new model.

    :ivar frames: camera renders done (int).
    """

    def __init__(self):
        """Start nothing yet."""
        self._captures = []
        self._lock = threading.Condition()
        self._pending = None  # the _Job being filled by the simulation thread
        self._queue = []  # jobs submitted, not yet started
        self._busy = False
        self._thread = None
        self._closed = False
        self._model = None  # the simulation's model the renderers were made for
        self._copy = None  # its private copy (clip planes change per camera)
        self._data = None
        self._renderers = {}
        self.frames = 0
        self.errors = []

    @property
    def started(self):
        """Return True once the render thread (and so an OpenGL context) exists."""
        return self._thread is not None

    def register(self, capture):
        """Count a camera in (its size sizes the offscreen buffer)."""
        self._captures.append(capture)

    def want(self, capture, output, t, publish):
        """Add ``output`` of ``capture`` to the job of instant ``t`` (simulation thread)."""
        if self._pending is None or self._pending.t != t:
            self._pending = _Job(t)
        self._pending.wanted.setdefault(capture, []).append((output, publish))

    def flush(self, world, t):
        """
        Hand the job of instant ``t`` to the render thread with a copy of the state.

        Waits while an earlier job has not been started (module docstring).
        """
        job, self._pending = self._pending, None
        if job is None or job.t != t or self._closed:
            return
        data = world.data
        job.model = world.model
        job.qpos = data.qpos.copy()
        job.mocap_pos = data.mocap_pos.copy()
        job.mocap_quat = data.mocap_quat.copy()
        with self._lock:
            while self._queue and not self._closed:
                self._lock.wait(0.5)
            if self._closed:
                return
            self._queue.append(job)
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, name='camera_render',
                                                daemon=True)
                self._thread.start()
            self._lock.notify_all()

    def idle(self, timeout=10.0):
        """Wait until every submitted job is rendered and published; return True if so."""
        with self._lock:
            return self._lock.wait_for(lambda: not self._queue and not self._busy, timeout)

    def close(self):
        """
        Stop the render thread after its current job and free its renderers.

        Without a render thread the renderers were made by :meth:`render_now` on the caller's
        thread, which holds their OpenGL context: they are freed here, on that thread (freed
        later by the garbage collector on another thread, EGL refuses: EGL_BAD_ACCESS).
        """
        with self._lock:
            self._closed = True
            self._queue.clear()
            self._lock.notify_all()
        if self._thread is None:
            self._free()
        elif self._thread is not threading.current_thread():
            self._thread.join(timeout=10.0)

    def _run(self):
        try:
            while True:
                with self._lock:
                    self._lock.wait_for(lambda: self._queue or self._closed)
                    if self._closed:
                        return
                    job = self._queue.pop(0)
                    self._busy = True
                    self._lock.notify_all()
                try:
                    self._render_job(job)
                except Exception as exc:  # noqa: B902 - one bad frame must not end the thread
                    if len(self.errors) < 10:
                        self.errors.append(f'camera render failed: {exc!r}')
                finally:
                    with self._lock:
                        self._busy = False
                        self._lock.notify_all()
        finally:
            self._free()

    def _render_job(self, job):
        import mujoco
        self._bind(job.model)
        data = self._data
        data.qpos[:] = job.qpos
        data.mocap_pos[:] = job.mocap_pos
        data.mocap_quat[:] = job.mocap_quat
        mujoco.mj_kinematics(self._copy, data)
        mujoco.mj_camlight(self._copy, data)
        for capture, wanted in job.wanted.items():
            frame = self._render(capture, [output for output, _ in wanted])
            for output, publish in wanted:
                publish(output.message(frame, job.t))

    def render_now(self, world, capture, outputs):
        """
        Render ``capture`` for ``outputs`` on the calling thread, from ``world``'s state.

        For tools and tests that have no render thread (the caller's thread then holds the
        OpenGL context); not mixed with :meth:`flush` on one renderer.
        """
        import mujoco
        self._bind(world.model)
        self._data.qpos[:] = world.data.qpos
        self._data.mocap_pos[:] = world.data.mocap_pos
        self._data.mocap_quat[:] = world.data.mocap_quat
        mujoco.mj_kinematics(self._copy, self._data)
        mujoco.mj_camlight(self._copy, self._data)
        return self._render(capture, outputs)

    def _bind(self, model):
        """Make the renderers for ``model`` unless they exist (render thread)."""
        import mujoco
        if model is self._model:
            return
        self._free()
        self._copy = copy.deepcopy(model)
        sizes = [(c.spec.width, c.spec.height) for c in self._captures]
        visual = self._copy.vis.global_
        visual.offwidth = max([w for w, _ in sizes] + [1])
        visual.offheight = max([h for _, h in sizes] + [1])
        self._data = mujoco.MjData(self._copy)
        self._model = model

    def _renderer(self, width, height):
        import mujoco
        key = (width, height)
        if key not in self._renderers:
            self._renderers[key] = mujoco.Renderer(self._copy, height=height, width=width)
        return self._renderers[key]

    def _render(self, capture, outputs):
        """Render what ``outputs`` of ``capture`` need; return a :class:`Frame` with noise."""
        import mujoco
        spec = capture.spec
        need_rgb, need_depth = capture.needs(outputs)
        renderer = self._renderer(spec.width, spec.height)
        camera = self._copy.camera(capture.camera).id
        clip = self._copy.vis.map
        extent = float(self._copy.stat.extent)
        frame = Frame()
        if need_rgb:
            clip.znear, clip.zfar = spec.near / extent, spec.far / extent
            renderer.update_scene(self._data, camera=camera)
            flags = renderer.scene.flags
            flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = flags[mujoco.mjtRndFlag.mjRND_SHADOW] = 0
            frame.rgb = renderer.render().copy()
        if need_depth:
            # rendered from a tenth of the near clip, so that nearer hits show as -inf
            clip.znear, clip.zfar = 0.1 * spec.depth_near / extent, spec.depth_far / extent
            renderer.enable_depth_rendering()
            try:
                renderer.update_scene(self._data, camera=camera)
                frame.depth = depth_from_buffer(renderer.render(), spec.depth_near,
                                                spec.depth_far)
            finally:
                renderer.disable_depth_rendering()
        capture.add_noise(frame)
        self.frames += 1
        return frame

    def _free(self):
        for renderer in self._renderers.values():
            renderer.close()
        self._renderers = {}
        self._model = None
