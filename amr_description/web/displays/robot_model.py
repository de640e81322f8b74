# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
RobotModel: every robot description topic as a robot posed from TF (RViz's RobotModel).

Every ``robot_description_topics`` entry (std_msgs/String, transient local; ``'*'``, the
default: every ``.../robot_description`` String topic with a publisher) builds a robot,
rebuilt when a new description arrives; a description under a namespace
(``/r1/robot_description``) uses frames ``r1/<link>``, as robot_state_publisher's
``frame_prefix``. A description that does not parse: the error in the log and the status,
the viewer keeps running.
"""

from amr_description.web.displays.base import Display
from amr_description.web.displays.base import moved
from amr_description.web.displays.base import POSE_TOLERANCE
from amr_description.web.displays.discovery import AUTO
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from std_msgs.msg import String


def frame_prefix(topic):
    """Return ``r1/`` for ``/r1/robot_description``, '' for ``/robot_description``."""
    namespace = topic.strip('/').rpartition('/')[0]
    return namespace + '/' if namespace else ''


class RobotModelDisplay(Display):
    """
    The robots of the description topics.

    :param topics: the description topics (list of str).
    :ivar robots: topic -> :class:`~amr_description.web.robot_scene.RobotScene`.
    :ivar errors: topic -> the one-line error of its last description.
    """

    order = 20
    parameters = (('robot_description_topics', [AUTO]),)
    topics_parameter = 'robot_description_topics'
    rviz_classes = {'rviz_default_plugins/RobotModel': 'robot_description_topics'}

    def __init__(self, node, server, frames, topics):
        """Subscribe every description topic (transient local, depth 1)."""
        super().__init__(node, server, frames)
        self.topics = []
        self.robots = {}
        self.errors = {}
        self.changed = False  # set when a robot or an error came (the status refreshes)
        self._link_poses = {}  # (topic, link) -> last pose sent
        for topic in self.take_topics(topics, [String], suffix='robot_description'):
            self.add_topic(topic)

    def add_topic(self, topic):
        """Subscribe a description topic (transient local, depth 1)."""
        self.topics.append(topic)
        self.changed = True
        latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.node.create_subscription(
            String, topic, lambda msg, topic=topic: self._on_description(topic, msg), latched)

    def _on_description(self, topic, msg):
        from amr_description.core.description.urdf_model import parse_urdf
        from amr_description.web.robot_scene import RobotScene
        log = self.node.get_logger()
        try:
            model = parse_urdf(msg.data, source=topic)
        except ValueError as exc:
            log.error(str(exc))
            self.errors[topic] = str(exc)
            self.changed = True
            return
        self.errors.pop(topic, None)
        old = self.robots.pop(topic, None)
        if old is not None:
            old.remove()
        name = topic.strip('/').replace('/', '_') or 'robot'
        robot = RobotScene(self.server.scene, model, f'/robots/{name}', frame_prefix(topic))
        for problem in robot.problems:
            log.warning(problem)
        self.robots[topic] = robot
        self._link_poses = {k: v for k, v in self._link_poses.items() if k[0] != topic}
        log.info(f"robot '{model.name}' from {topic}: {len(model.links)} links")
        self.changed = True

    def root_frame(self):
        """Return the root frame of the first robot, or None without a robot."""
        for robot in self.robots.values():
            return robot.frame_id(robot.model.root)
        return None

    def draw(self, context):
        """Pose every link in the fixed frame; hide (and report) the links without one."""
        for topic, robot in self.robots.items():
            for link in robot.model.links:
                T = context.pose(robot.frame_id(link))
                if T is None:
                    robot.hide(link)
                    self._link_poses.pop((topic, link), None)
                    context.missing.append(robot.frame_id(link))
                    continue
                last = self._link_poses.get((topic, link))
                if moved(last, T, POSE_TOLERANCE):
                    robot.set_pose(link, T)
                    self._link_poses[(topic, link)] = T
