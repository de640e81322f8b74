# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
RViz's "2D Pose Estimate" and "2D Goal Pose" tools: set a pose by dragging on the ground.

Press a tool's button, then press on the ground where the robot is (or should go) and drag
the way it faces (or should face); the pose is published on release, and the tool hands the
mouse back to the camera, as RViz's tools do. A click without a drag faces +x. The ground is
the plane z = 0 of the fixed frame, and the pose is published in the fixed frame, stamped
with the node's clock (``use_sim_time`` aware), as RViz's ``InitialPoseTool`` and
``GoalTool`` (rviz_default_plugins) do:

- **2D Pose Estimate**: ``geometry_msgs/PoseWithCovarianceStamped`` on
  ``initial_pose_topic`` (``/initialpose``, where AMCL listens) with RViz's covariance:
  x and y variances 0.25 m^2 (standard deviation 0.5 m) and yaw variance (pi/12)^2 =
  0.0685 rad^2, the rest 0;
- **2D Goal Pose**: ``geometry_msgs/PoseStamped`` on ``goal_pose_topic`` (``/goal_pose``,
  where Nav2's bt_navigator listens).

AMCL takes initial poses only in its global frame (``map``): set the Fixed Frame to ``map``
first (the Map display makes it available before AMCL publishes ``map -> odom``).
"""

import math
import threading

from amr_description.web.displays.base import Display
from geometry_msgs.msg import PoseStamped
from geometry_msgs.msg import PoseWithCovarianceStamped
import numpy as np

X_STD = 0.5
"""m, RViz's InitialPoseTool ``X std deviation``."""
Y_STD = 0.5
"""m, its ``Y std deviation``."""
YAW_STD = math.pi / 12.0
"""rad, its ``Theta std deviation``."""
PLANE_HALF = 200.0
"""m, half the side of the ground the tool catches the mouse on while it is active."""
PLANE_HEIGHT = 0.005
"""m above z 0, over the map's picture (the tool's plane must be hit first)."""
ARROW_RGB = (40, 200, 40)
"""The colour of the arrow drawn while dragging."""
MIN_DRAG = 1e-3
"""m, a shorter drag keeps the heading +x."""


def ground_point(camera, through, height=0.0):
    """
    Return where the ray from ``camera`` through ``through`` meets the plane z = ``height``.

    :param camera: (3,) the ray's origin (the camera's position), m.
    :param through: (3,) a point on the ray beyond the origin, m.
    :returns: (3,) array, or None when the ray is parallel to the plane or points away.
    """
    camera = np.asarray(camera, float)
    direction = np.asarray(through, float) - camera
    if abs(direction[2]) < 1e-12:
        return None
    t = (height - camera[2]) / direction[2]
    return camera + t * direction if t > 0.0 else None


def pose_from_drag(start, end):
    """
    Return ``(x, y, yaw)`` of a drag from ``start`` to ``end`` on the ground (m, rad).

    The position is the press; the heading points at the release (0 for a drag shorter than
    :data:`MIN_DRAG`), as RViz's pose tools.
    """
    dx, dy = end[0] - start[0], end[1] - start[1]
    yaw = math.atan2(dy, dx) if math.hypot(dx, dy) >= MIN_DRAG else 0.0
    return float(start[0]), float(start[1]), yaw


def initial_pose_message(x, y, yaw, frame_id, stamp):
    """
    Return RViz's 2D Pose Estimate message for a pose in ``frame_id``.

    :param stamp: ``builtin_interfaces/Time``.
    :returns: ``geometry_msgs/PoseWithCovarianceStamped`` with RViz's covariance.
    """
    msg = PoseWithCovarianceStamped()
    msg.header.frame_id, msg.header.stamp = frame_id, stamp
    _set_pose(msg.pose.pose, x, y, yaw)
    covariance = [0.0] * 36
    covariance[0], covariance[7], covariance[35] = X_STD ** 2, Y_STD ** 2, YAW_STD ** 2
    msg.pose.covariance = covariance
    return msg


def goal_pose_message(x, y, yaw, frame_id, stamp):
    """Return RViz's 2D Goal Pose message (``geometry_msgs/PoseStamped``)."""
    msg = PoseStamped()
    msg.header.frame_id, msg.header.stamp = frame_id, stamp
    _set_pose(msg.pose, x, y, yaw)
    return msg


def _set_pose(pose, x, y, yaw):
    pose.position.x, pose.position.y = x, y
    pose.orientation.z, pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)


class PoseToolDisplay(Display):
    """The two tools' buttons and the ground they catch the mouse on (module docstring)."""

    order = 96
    panel_order = 5
    parameters = (('initial_pose_topic', '/initialpose'), ('goal_pose_topic', '/goal_pose'))

    @classmethod
    def create(cls, viewer, settings):
        """Make the tools publishing on the viewer's two topic parameters."""
        return cls(viewer, viewer.server, viewer.frames, str(settings['initial_pose_topic']),
                   str(settings['goal_pose_topic']))

    def __init__(self, node, server, frames, initial_pose_topic, goal_pose_topic):
        """Create the two publishers (reliable, volatile, as RViz's tools)."""
        super().__init__(node, server, frames)
        self._lock = threading.Lock()
        self._publishers = {
            'initial': (node.create_publisher(PoseWithCovarianceStamped, initial_pose_topic, 1),
                        initial_pose_message),
            'goal': (node.create_publisher(PoseStamped, goal_pose_topic, 1),
                     goal_pose_message)}
        self._fixed = ''
        self._tool = None
        self._plane = None
        self._end = None
        self._arrow = None

    def build_panel(self, gui):
        """Add the tools' buttons."""
        self._buttons = {'initial': gui.add_button('2D Pose Estimate'),
                         'goal': gui.add_button('2D Goal Pose')}
        for tool, button in self._buttons.items():
            button.on_click(lambda _, tool=tool: self._activate(tool))

    def draw(self, context):
        """Remember the fixed frame the poses are given in."""
        self._fixed = context.fixed

    def _activate(self, tool):
        with self._lock:
            self._tool = tool
            self._end = None
            h = PLANE_HALF
            vertices = np.array([[-h, -h, PLANE_HEIGHT], [h, -h, PLANE_HEIGHT],
                                 [h, h, PLANE_HEIGHT], [-h, h, PLANE_HEIGHT]], np.float32)
            faces = np.array([[0, 1, 2], [0, 2, 3]], np.uint32)
            # shown only once its drag and click bindings are sent (the page takes messages
            # in order): a press on a plane drawn before its bindings orbited the camera
            self._plane = self.server.scene.add_mesh_simple(
                '/pose_tool/ground', vertices, faces, color=ARROW_RGB, opacity=0.06,
                side='double', cast_shadow=False, receive_shadow=False, visible=False)
            self._plane.on_drag(self._on_drag)
            self._plane.on_click(self._on_click)
            self._plane.visible = True

    def _on_click(self, event):
        point = ground_point(event.ray_origin, np.add(event.ray_origin, event.ray_direction))
        if point is not None:
            self._finish(point, point)

    async def _on_drag(self, event):
        # async: viser awaits async callbacks in order on its event loop; a plain function
        # runs in its thread pool, where a drag's "end" may run before its "start". Each
        # event carries the press point too, so the pose does not hang on the order either.
        start = np.array([event.start_position[0], event.start_position[1], 0.0])
        end = ground_point(event.client.camera.position, event.end_position)
        with self._lock:
            if self._tool is None:  # already published (or no tool): nothing to draw
                return
            if end is not None:
                self._end = end
            end = self._end if self._end is not None else start
            if event.phase != 'end':
                self._arrow = self.server.scene.add_arrows(
                    '/pose_tool/arrow', np.array([[start, end]], np.float32), ARROW_RGB,
                    shaft_radius=0.03, head_radius=0.08, head_length=0.2)
                return
        self._finish(start, end)

    def _finish(self, start, end):
        with self._lock:
            tool, self._tool = self._tool, None
            plane, self._plane = self._plane, None
            arrow, self._arrow = self._arrow, None
        for node in (plane, arrow):
            if node is not None:
                node.remove()
        if tool is None:
            return
        x, y, yaw = pose_from_drag(start, end)
        publisher, make = self._publishers[tool]
        msg = make(x, y, yaw, self._fixed, self.node.get_clock().now().to_msg())
        publisher.publish(msg)
        self.node.get_logger().info(
            f'Setting {"estimate" if tool == "initial" else "goal"} pose: Frame:{self._fixed}, '
            f'Position({x:.3f}, {y:.3f}, 0), Angle: {yaw:.3f} (on {publisher.topic_name})')
