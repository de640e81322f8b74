# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``localization_slam_toolbox_node``: slam_toolbox's localization mode, node ``slam_toolbox``.

The mapper node of :mod:`.slam_toolbox` (parameters, lifecycle, topics, TF, services) on a
saved pose graph that it does not change
(:class:`~amr_description.nav.slam_localization.Localizer`): on configure, ``map_file_name``
is loaded and the first scan localized near ``map_start_pose`` (with ``map_start_at_dock``:
an error line, as upstream, and its first node); ``/initialpose``
(PoseWithCovarianceStamped, depth 1) localizes the next scan near the pose it gives (its
covariance is not used); ``slam_toolbox/deserialize_map`` takes only ``LOCALIZE_AT_POSE`` and
``slam_toolbox/serialize_map`` is refused with upstream's error line (and
``RESULT_FAILED_TO_WRITE_FILE``). ``/map`` is the loaded graph's map.

Source: slam_toolbox 2.8.3 ``src/slam_toolbox_localization.cpp``.
"""

import math

from amr_description.nav.slam_localization import Localizer
from amr_description.nodes.slam_toolbox import SlamToolbox
from amr_description.ros import shutdown
from amr_description.ros.transforms import yaw_of
from geometry_msgs.msg import PoseWithCovarianceStamped
from slam_toolbox import srv


class LocalizationSlamToolbox(SlamToolbox):
    """Node ``slam_toolbox`` in localization mode; see the module docstring."""

    def _new_mapper(self):
        return Localizer(self.params)

    def configure(self):
        """Configure as the mapper node; say so when there is no graph to localize on."""
        super().configure()
        if not self.p['map_file_name']:
            self.get_logger().warning(
                "No pose graph to localize on: set 'map_file_name' (a graph saved with "
                'slam_toolbox/serialize_map) or call slam_toolbox/deserialize_map with '
                'LOCALIZE_AT_POSE')

    def activate(self):
        """Create the mapper node's topics and services, and ``/initialpose``."""
        super().activate()
        self._active.append(self.create_subscription(
            PoseWithCovarianceStamped, '/initialpose', self._on_initial_pose, 1))

    def _load(self, stem, start_pose):
        if start_pose is None:
            self.get_logger().error('LocalizationSlamToolbox: Starting localization at first '
                                    'node (dock) is correctly not supported.')
        super()._load(stem, start_pose)

    def _start(self, mapper, pose):
        loc = Localizer.from_mapper(mapper)
        loc.localize_at(pose)
        self.mapper = loc
        return 'localizing near'

    def _on_initial_pose(self, msg):
        p = msg.pose.pose
        pose = (p.position.x, p.position.y, yaw_of(p.orientation))
        if not all(math.isfinite(v) for v in pose):
            self.get_logger().warning('/initialpose: NaN or infinite pose; ignored')
            return
        if self.mapper is None:
            return
        self.mapper.localize_at(pose)
        self.get_logger().info(f'LocalizePoseCallback: Localizing to: ({pose[0]:.2f} '
                               f'{pose[1]:.2f}), theta={pose[2]:.2f}')

    def _on_serialize(self, request, response):
        self.get_logger().fatal('LocalizationSlamToolbox: Cannot call serialize map in '
                                'localization mode!')
        response.result = srv.SerializePoseGraph.Response.RESULT_FAILED_TO_WRITE_FILE
        return response

    def _on_deserialize(self, request, response):
        if request.match_type != srv.DeserializePoseGraph.Request.LOCALIZE_AT_POSE:
            self.get_logger().error('Requested a non-localization deserialization in '
                                    'localization mode.')
            return response
        p = request.initial_pose
        try:
            self._load(request.filename, (p.x, p.y, p.theta))
        except ValueError as exc:
            self.get_logger().error(f'deserialize_map: {exc}')
        return response


def main(args=None):
    """
    Run the localization node until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(LocalizationSlamToolbox, args)


if __name__ == '__main__':
    main()
