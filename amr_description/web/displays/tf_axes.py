# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""TF: the axes of every frame with a pose in the fixed frame (RViz's TF display)."""

from amr_description.web.displays.base import Display
from amr_description.web.displays.base import moved
from amr_description.web.displays.base import POSE_TOLERANCE
from amr_description.web.robot_scene import wxyzs_positions
import numpy as np


class TfAxesDisplay(Display):
    """
    Axes of every TF frame, drawn as one batched-axes scene node.

    One node (instanced on the page) holds every frame's axes, so an update sends at most two
    arrays instead of two messages per frame; the node is rebuilt only when the set of frames
    drawn changes. A checkbox shows or hides it.
    """

    order = 30

    @classmethod
    def create(cls, viewer, settings):
        """Make the display, enabled unless an ``.rviz`` file (``settings['rviz']``) has no TF."""
        display = cls(viewer, viewer.server, viewer.frames)
        rviz = settings.get('rviz')
        display.enabled = rviz is None or rviz.tf
        return display

    def __init__(self, node, server, frames):
        """Start with no axes drawn."""
        super().__init__(node, server, frames)
        self.enabled = True  # the checkbox's first state (an RViz config may say False)
        self._node = None
        self._frames = []  # the frames drawn, in order
        self._last = None  # their poses sent last, shape (N, 4, 4)

    def build(self, gui):
        """Add the ``TF axes`` checkbox."""
        self._show = gui.add_checkbox('TF axes', self.enabled)

    def draw(self, context):
        """Draw the axes of every frame that has a pose in the fixed frame."""
        frames, stack = [], []
        if self._show.value:
            for frame in sorted(self.frames.buffer.frames()):
                T = context.pose(frame)
                if T is not None:
                    frames.append(frame)
                    stack.append(T)
        node = self._node
        if not frames:
            if node is not None and node.visible:
                node.visible = False
            return
        stack = np.stack(stack)
        if node is not None and frames == self._frames:
            if moved(self._last, stack, POSE_TOLERANCE):
                node.batched_wxyzs, node.batched_positions = wxyzs_positions(stack)
                self._last = stack
            if not node.visible:
                node.visible = True
            return
        if node is not None:
            node.remove()
        wxyzs, positions = wxyzs_positions(stack)
        self._node = self.server.scene.add_batched_axes(
            '/tf', wxyzs, positions, axes_length=0.12, axes_radius=0.006)
        self._frames, self._last = frames, stack
