# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
A small transform buffer composing ``/tf`` and ``/tf_static`` like tf2 (pure numpy, no rclpy).

tf2_ros is not on PyPI, so the viewer keeps its own buffer. Behaviour reproduced from tf2's
``BufferCore`` (ROS 2 Jazzy), as documented in the tf2 design notes:

- every frame has at most one parent; a transform names ``parent -> child`` and maps child
  coordinates to parent coordinates (``p_parent = T @ [p_child, 1]``, 4x4 matrices, metres);
- dynamic transforms are kept for ``cache_time`` seconds (10 s, tf2's default) behind the
  newest one of their frame; static transforms (``/tf_static``) are timeless: one value,
  valid at every time, replaced by a newer static message;
- :meth:`TransformBuffer.lookup` with ``time=0`` uses the *latest common time* of the chain
  between the two frames: the oldest of the newest stamps of the dynamic transforms on the
  chain (static ones do not constrain it); a chain of static transforms only has time 0;
- at a given time a dynamic transform is linearly interpolated in translation and spherically
  (slerp) in rotation between the two stamps around it; a time outside the stored stamps is
  an extrapolation error (tf2's ``ExtrapolationException``); a frame that is not known is a
  lookup error, two frames in different trees a connectivity error;
- a frame id's leading ``/`` is dropped (tf2 warns and strips it).

The parent of a frame is the one of its latest transform (tf2 keeps a parent per stamp; a
re-parented frame is rare enough that the viewer does not need that). Times are seconds
(float), e.g. ``stamp.sec + stamp.nanosec * 1e-9``.
"""

import math

from amr_description.core.kinematics import quaternion_to_matrix
import numpy as np

DEFAULT_CACHE_TIME = 10.0
"""Seconds of dynamic transforms kept per frame (tf2's default buffer length)."""


class TransformException(Exception):
    """Base class of the lookup errors (tf2's ``TransformException``)."""


class LookupException(TransformException):
    """A frame does not exist in the buffer (tf2's ``LookupException``)."""


class ConnectivityException(TransformException):
    """The two frames are in different trees (tf2's ``ConnectivityException``)."""


class ExtrapolationException(TransformException):
    """The requested time is outside the stored stamps (tf2's ``ExtrapolationException``)."""


def strip_frame(frame_id):
    """Return ``frame_id`` without a leading ``/`` (tf2 strips it with a warning)."""
    return frame_id[1:] if frame_id.startswith('/') else frame_id


def slerp(q0, q1, fraction):
    """
    Interpolate two unit quaternions (x, y, z, w) along the shorter arc.

    :param q0: quaternion at ``fraction`` 0, length 4.
    :param q1: quaternion at ``fraction`` 1, length 4.
    :param fraction: 0..1.
    :returns: unit quaternion, numpy array of 4.
    """
    q0 = np.asarray(q0, dtype=float)
    q1 = np.asarray(q1, dtype=float)
    dot = float(np.dot(q0, q1))
    if dot < 0.0:
        q1 = -q1
        dot = -dot
    if dot > 0.9995:  # nearly parallel: normalized linear interpolation
        q = q0 + fraction * (q1 - q0)
        return q / np.linalg.norm(q)
    theta = math.acos(min(dot, 1.0))
    s = math.sin(theta)
    return (math.sin((1.0 - fraction) * theta) * q0 + math.sin(fraction * theta) * q1) / s


def pose_matrix(translation, rotation):
    """
    Return the 4x4 pose of a translation and a quaternion.

    :param translation: (x, y, z) in metres.
    :param rotation: quaternion (x, y, z, w), normalized here.
    :returns: numpy array, shape (4, 4).
    """
    T = np.eye(4)
    T[:3, :3] = quaternion_to_matrix(rotation)
    T[:3, 3] = np.asarray(translation, dtype=float)
    return T


class _Frame:
    """The transforms from one frame's parent to it: a static value or stamped samples."""

    def __init__(self, parent):
        self.parent = parent
        self.static = None  # (translation, rotation) when static
        self.static_T = None  # its 4x4 matrix, built once
        self.samples = []  # [(time, translation, rotation)], ascending time
        self.newest_T = None  # (time, 4x4 matrix) of the newest sample, built on demand

    def newest(self):
        return self.samples[-1][0] if self.samples else None

    def oldest(self):
        return self.samples[0][0] if self.samples else None

    def at(self, time, frame):
        """Return the 4x4 transform parent -> frame at ``time`` (0: the newest)."""
        if self.static is not None:
            if self.static_T is None:
                self.static_T = pose_matrix(*self.static)
            return self.static_T
        samples = self.samples
        if time == 0.0 or time == samples[-1][0]:  # the newest: built once per sample
            if self.newest_T is None or self.newest_T[0] != samples[-1][0]:
                self.newest_T = (samples[-1][0], pose_matrix(samples[-1][1], samples[-1][2]))
            return self.newest_T[1]
        if len(samples) == 1:
            if time == samples[0][0]:
                return pose_matrix(samples[0][1], samples[0][2])
            raise ExtrapolationException(
                f'Lookup would require extrapolation at time {time:.6f}, but only time '
                f'{samples[0][0]:.6f} is in the buffer, when looking up transform from frame '
                f'[{frame}] to frame [{self.parent}]')
        if time < samples[0][0]:
            raise ExtrapolationException(
                f'Lookup would require extrapolation into the past. Requested time '
                f'{time:.6f} but the earliest data is at time {samples[0][0]:.6f}, when '
                f'looking up transform from frame [{frame}] to frame [{self.parent}]')
        if time > samples[-1][0]:
            raise ExtrapolationException(
                f'Lookup would require extrapolation into the future. Requested time '
                f'{time:.6f} but the latest data is at time {samples[-1][0]:.6f}, when '
                f'looking up transform from frame [{frame}] to frame [{self.parent}]')
        # binary search for the first sample at or after ``time``
        lo, hi = 0, len(samples) - 1
        while lo < hi:
            mid = (lo + hi) // 2
            if samples[mid][0] < time:
                lo = mid + 1
            else:
                hi = mid
        t1, p1, q1 = samples[lo]
        if t1 == time or lo == 0:
            return pose_matrix(p1, q1)
        t0, p0, q0 = samples[lo - 1]
        fraction = (time - t0) / (t1 - t0)
        p = np.asarray(p0) + fraction * (np.asarray(p1) - np.asarray(p0))
        return pose_matrix(p, slerp(q0, q1, fraction))


def _latest_common(edges):
    """Return the latest time every dynamic edge ``(child, _Frame)`` has (0.0: none dynamic)."""
    dynamic = [frame.newest() for _, frame in edges if frame.static is None]
    return min(dynamic) if dynamic else 0.0


def _compose(edges, time):
    """Return the transform up ``edges`` (child first) at ``time``: a new 4x4 array."""
    T = np.eye(4)
    for child, frame in edges:
        T = frame.at(time, child) @ T
    return T


class TransformBuffer:
    """
    Transforms of ``/tf`` and ``/tf_static`` composed like tf2 (see the module docstring).

    :param cache_time: seconds of dynamic transforms kept behind each frame's newest stamp.
    """

    def __init__(self, cache_time=DEFAULT_CACHE_TIME):
        """Create an empty buffer."""
        self.cache_time = float(cache_time)
        self._frames = {}  # child frame -> _Frame
        self._known = None  # every frame id (children and parents), rebuilt when one is added

    def clear(self):
        """
        Forget every dynamic transform; keep the static ones (``/tf_static``).

        As tf2's ``BufferCore::clear``, which empties each frame's time cache while tf2's
        ``StaticCache::clearList`` does nothing: ``/tf_static`` is latched and published
        once, so a buffer cleared on a backward jump of the clock (a reset simulation,
        ``ros2 bag play --clock``) would otherwise lose the fixed links for good.
        """
        self._frames = {child: frame for child, frame in self._frames.items()
                        if frame.static is not None}
        self._known = None

    def set_transform(self, parent, child, time, translation, rotation, static=False):
        """
        Store the transform ``parent -> child``.

        :param parent: parent frame id (``header.frame_id``).
        :param child: child frame id (``child_frame_id``).
        :param time: stamp in seconds (ignored for static transforms).
        :param translation: (x, y, z) in metres, child origin in the parent frame.
        :param rotation: quaternion (x, y, z, w) of the child axes in the parent frame.
        :param static: True for ``/tf_static`` (timeless).
        :raises ValueError: on an empty frame id, a frame that is its own parent, or a
            non-finite or zero-norm value (the transform is not stored; tf2 rejects these too).
        """
        parent = strip_frame(parent)
        child = strip_frame(child)
        if not parent or not child:
            raise ValueError(f"transform '{parent}' -> '{child}': empty frame id")
        if parent == child:
            raise ValueError(f"transform '{parent}' -> '{child}': a frame cannot be its own "
                             'parent')
        # plain floats, not numpy: this runs for every transform of every /tf message
        translation = tuple(float(v) for v in translation)
        rotation = tuple(float(v) for v in rotation)
        norm = math.sqrt(sum(v * v for v in rotation))
        if not all(math.isfinite(v) for v in translation) or not math.isfinite(norm) or \
                norm == 0.0:
            raise ValueError(f"transform '{parent}' -> '{child}': non-finite translation or "
                             'rotation, or a zero quaternion')
        rotation = np.array([v / norm for v in rotation])
        frame = self._frames.get(child)
        fresh = frame is None or frame.parent != parent or (frame.static is not None) != static
        if fresh:
            # filled before it is stored: a lookup on another thread never sees it empty
            frame = _Frame(parent)
        if static:
            frame.static = (translation, rotation)
            frame.static_T = None
            if fresh:
                self._store_frame(child, frame)
            return
        time = float(time)
        samples = frame.samples
        if samples and time < samples[-1][0] - self.cache_time:
            return  # older than the cache: dropped, as tf2 does (TF_OLD_DATA)
        entry = (time, translation, rotation)
        frame.newest_T = None
        if not samples or time > samples[-1][0]:
            samples.append(entry)
        else:
            index = len(samples)
            while index > 0 and samples[index - 1][0] > time:
                index -= 1
            if index > 0 and samples[index - 1][0] == time:
                samples[index - 1] = entry
            else:
                samples.insert(index, entry)
        horizon = samples[-1][0] - self.cache_time
        while len(samples) > 1 and samples[0][0] < horizon:
            samples.pop(0)
        if fresh:
            self._store_frame(child, frame)

    def _store_frame(self, child, frame):
        self._frames[child] = frame
        self._known = None

    def frames(self):
        """Return every known frame id, parents included (a set)."""
        return set(self._known_frames())

    def _known_frames(self):
        if self._known is None:
            self._known = frozenset(self._frames).union(f.parent for f in self._frames.values())
        return self._known

    def parent(self, frame):
        """Return the parent of ``frame`` or None for a root or an unknown frame."""
        entry = self._frames.get(strip_frame(frame))
        return entry.parent if entry is not None else None

    def root(self, frame):
        """Return the root of the tree that holds ``frame`` (``frame`` itself for a root)."""
        frame = strip_frame(frame)
        seen = set()
        while frame in self._frames and frame not in seen:
            seen.add(frame)
            frame = self._frames[frame].parent
        return frame

    def _chain(self, frame):
        """Return [frame, parent, grandparent, ..., root]."""
        chain = [frame]
        while chain[-1] in self._frames:
            chain.append(self._frames[chain[-1]].parent)
            if len(chain) > len(self._frames) + 1:
                raise ConnectivityException(f'the transforms above frame [{frame}] form a loop')
        return chain

    def _path(self, target, source):
        """Return (frames from source up to the common ancestor, from target up to it)."""
        known = self._known_frames()
        for name, argument in ((target, 'target_frame'), (source, 'source_frame')):
            if name not in known:
                raise LookupException(
                    f'"{name}" passed to lookupTransform argument {argument} does not exist. ')
        up_source = self._chain(source)
        up_target = self._chain(target)
        common = set(up_target)
        for index, name in enumerate(up_source):
            if name in common:
                return up_source[:index + 1], up_target[:up_target.index(name) + 1]
        raise ConnectivityException(
            f"Could not find a connection between '{target}' and '{source}' because they "
            'are not part of the same tree. Tf has two or more unconnected trees.')

    def latest_common_time(self, target, source):
        """
        Return the latest time at which ``target <- source`` can be computed.

        :param target: frame id.
        :param source: frame id.
        :returns: seconds; 0.0 when the chain has only static transforms (or no transform).
        :raises TransformException: when a frame is unknown or the frames are not connected.
        """
        target = strip_frame(target)
        source = strip_frame(source)
        if target == source:
            return 0.0
        return self._common_time(*self._path(target, source))

    def _edges(self, chain):
        """Return ``[(child, its _Frame)]`` along ``chain`` (one read of each frame)."""
        return [(f, self._frames[f]) for f in chain[:-1]]

    def _common_time(self, up_source, up_target):
        return _latest_common(self._edges(up_source) + self._edges(up_target))

    def lookup(self, target, source, time=0.0):
        """
        Return the pose of ``source`` in ``target`` (tf2's ``lookupTransform(target, source)``).

        :param target: frame the result is expressed in.
        :param source: frame whose pose is wanted.
        :param time: seconds; 0.0 means the latest common time of the chain.
        :returns: ``(T, time)``: T maps ``source`` coordinates to ``target`` coordinates,
            shape (4, 4); time is the time used (0.0 for an all-static chain).
        :raises LookupException: when a frame is unknown.
        :raises ConnectivityException: when the frames are in different trees.
        :raises ExtrapolationException: when ``time`` is outside a dynamic transform's stamps.
        """
        target = strip_frame(target)
        source = strip_frame(source)
        if target == source:
            if target not in self._known_frames():
                raise LookupException(
                    f'"{target}" passed to lookupTransform argument target_frame does not '
                    'exist. ')
            return np.eye(4), float(time)
        up_source, up_target = self._path(target, source)
        # the frames are read once: a listener thread replacing one (a new parent) between
        # the common time and the composition cannot make them disagree
        edges_source, edges_target = self._edges(up_source), self._edges(up_target)
        time = float(time)
        if time == 0.0:
            time = _latest_common(edges_source + edges_target)
        T_anc_source = _compose(edges_source, time)  # common ancestor <- source
        T_anc_target = _compose(edges_target, time)
        # the inverse of a rigid transform: [R^T | -R^T t]
        T_target_anc = np.eye(4)
        T_target_anc[:3, :3] = T_anc_target[:3, :3].T
        T_target_anc[:3, 3] = -T_anc_target[:3, :3].T @ T_anc_target[:3, 3]
        return T_target_anc @ T_anc_source, time

    def can_transform(self, target, source, time=0.0):
        """Return True when :meth:`lookup` would succeed."""
        try:
            self.lookup(target, source, time)
        except TransformException:
            return False
        return True
