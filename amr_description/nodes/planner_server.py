# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``planner_server``: nav2_planner's planner server (Jazzy), a managed (lifecycle) node.

It runs the global costmap beside itself (:class:`amr_description.nodes.costmap_2d.CostmapNode`
``global_costmap``, started and stopped with the server) and the planners named in
``planner_plugins`` (default ``[GridBased]``), each from ``<id>.plugin``:
``nav2_navfn_planner::NavfnPlanner`` (or ``nav2_navfn_planner/NavfnPlanner``) with
``<id>.tolerance`` (0.5 m), ``<id>.use_astar`` (false; the search is Dijkstra's either way,
said once), ``<id>.allow_unknown`` (true), ``<id>.use_final_approach_orientation`` (false);
another plugin, e.g. ``nav2_smac_planner::SmacPlanner2D``, is said in one line and runs as
NavFn with its ``tolerance`` and ``allow_unknown`` (:mod:`amr_description.nav.planner`).
``expected_planner_frequency`` (1.0 Hz) is read; a plan slower than its period is warned.
While active, ``ros2 param set`` changes ``expected_planner_frequency`` and each NavFn's
``tolerance``, ``use_astar``, ``allow_unknown`` and ``use_final_approach_orientation`` for the
next plan (upstream's ``dynamicParametersCallback`` of ``planner_server.cpp`` and
``navfn_planner.cpp``).

Action ``compute_path_to_pose`` (nav2_msgs/action/ComputePathToPose): the start is the
robot's pose in the costmap's global frame from TF unless ``use_start``; the goal is
transformed into that frame; an unknown ``planner_id`` fails with INVALID_PLANNER, an empty one
uses the only planner; an untransformable pose fails with TF_ERROR, a NaN goal with
GOAL_OUTSIDE_MAP; the result's path (frame = the costmap's) is also published on ``plan``
(nav_msgs/Path, depth 1). Action ``compute_path_through_poses``
(ComputePathThroughPoses) plans each leg from the previous goal and joins them; no goals is
NO_VIAPOINTS_GIVEN. Service ``is_path_valid`` (nav2_msgs/IsPathValid): the indices of the
path's poses, from the one nearest the robot on, whose cost in the global costmap is lethal or
inscribed (:func:`amr_description.nav.planner.invalid_poses`); an empty path is not valid.
Source: ``nav2_planner/src/planner_server.cpp``.
"""

import math
import time

from amr_description.core.tf_buffer import TransformBuffer
from amr_description.core.tf_buffer import TransformException
from amr_description.nav.planner import invalid_poses
from amr_description.nav.planner import make_plan
from amr_description.nav.planner import PlanError
from amr_description.nodes.costmap_2d import CostmapNode
from amr_description.ros import shutdown
from amr_description.ros.managed_node import ManagedNode
from amr_description.ros.transforms import planar_pose
from amr_description.ros.transforms import set_yaw
from amr_description.ros.transforms import transform_planar
from amr_description.ros.transforms import TransformListener
from geometry_msgs.msg import PoseStamped
from nav2_msgs.action import ComputePathThroughPoses
from nav2_msgs.action import ComputePathToPose
from nav2_msgs.srv import IsPathValid
from nav_msgs.msg import Path
import numpy as np
from rcl_interfaces.msg import SetParametersResult
from rclpy.action import ActionServer
from rclpy.duration import Duration

NAVFN = 'NavfnPlanner'
NAVFN_PARAMETERS = ('tolerance', 'use_astar', 'allow_unknown', 'use_final_approach_orientation')


class PlannerServer(ManagedNode):
    """Node ``planner_server``; see the module docstring."""

    def __init__(self, **kwargs):
        """Declare the parameters and make the global costmap node (``kwargs``: rclpy's)."""
        super().__init__('planner_server', **kwargs)
        self.ids = list(self.declare_parameter('planner_plugins', ['GridBased']).value)
        self.frequency = float(self.declare_parameter('expected_planner_frequency', 1.0).value)
        self.planners = {}
        for pid in self.ids:
            kind = str(self.declare_parameter(
                f'{pid}.plugin', 'nav2_navfn_planner::NavfnPlanner').value)
            default_tol = 0.125 if 'Smac' in kind else 0.5
            self.planners[pid] = {
                'plugin': kind,
                'tolerance': float(self.declare_parameter(f'{pid}.tolerance', default_tol).value),
                'allow_unknown': bool(self.declare_parameter(f'{pid}.allow_unknown', True).value),
                'use_astar': bool(self.declare_parameter(f'{pid}.use_astar', False).value),
                'use_final_approach_orientation': bool(self.declare_parameter(
                    f'{pid}.use_final_approach_orientation', False).value)}
        self.tf_buffer = TransformBuffer()
        ns = self.get_namespace()
        self.costmap = CostmapNode(
            'global_costmap', self.tf_buffer, ns if ns != '/' else '',
            use_sim_time=self.get_parameter('use_sim_time').value, **kwargs)
        self.companion_nodes = [self.costmap]
        self._listener = self._action = self._plan_pub = None

    def configure(self):
        """Say which planner runs for each id; listen to TF."""
        self.get_logger().info('Configuring')
        for pid, planner in self.planners.items():
            kind = planner['plugin'].replace('/', '::')
            if kind.split('::')[-1] != NAVFN:
                self.get_logger().info(
                    f"{pid}: plugin '{planner['plugin']}' runs as NavFn (GridBased) here, "
                    f"with tolerance {planner['tolerance']:g} and allow_unknown "
                    f"{str(planner['allow_unknown']).lower()}")
            elif planner['use_astar']:
                self.get_logger().info(f'{pid}: use_astar: the search runs as Dijkstra here')
            else:
                self.get_logger().info(f'Created global planner plugin {pid} of type {kind}')
        self._listener = TransformListener(self, self.tf_buffer, spin_thread=True)
        self._check_frequency(self.frequency)

    def _check_frequency(self, frequency):
        if frequency <= 0.0:
            self.get_logger().warning(
                f'The expected planner frequency parameter is {frequency:.4f} Hz. The value '
                'should to be greater than 0.0 to turn on duration overrrun warning messages')

    def activate(self):
        """Start the costmap, the action server and the plan publisher."""
        self.get_logger().info('Activating')
        self.costmap.start()
        self._plan_pub = self.create_publisher(Path, 'plan', 1)
        self._action = ActionServer(self, ComputePathToPose, 'compute_path_to_pose',
                                    self._execute)
        self._through = ActionServer(self, ComputePathThroughPoses,
                                     'compute_path_through_poses', self._execute_through)
        self._valid = self.create_service(IsPathValid, 'is_path_valid', self._on_is_path_valid)
        self.watch_parameters(self._on_set_parameters)

    def deactivate(self):
        """Stop the action server and the costmap."""
        self.get_logger().info('Deactivating')
        self.unwatch_parameters()
        if self._action is not None:
            self._action.destroy()
            self._through.destroy()
            self.destroy_service(self._valid)
            self._action = self._through = self._valid = None
        if self._plan_pub is not None:
            self.destroy_publisher(self._plan_pub)
            self._plan_pub = None
        self.costmap.stop()

    def cleanup(self):
        """Stop listening to TF."""
        self.get_logger().info('Cleaning up')
        if self._listener is not None:
            self._listener.destroy()
            self._listener = None

    def _on_set_parameters(self, parameters):
        """Take ``ros2 param set`` values for the next plan; see the module docstring."""
        for parameter in parameters:
            pid, _, key = parameter.name.partition('.')
            if parameter.name == 'expected_planner_frequency':
                self.frequency = float(parameter.value)
                self._check_frequency(self.frequency)
            elif pid in self.planners and key in NAVFN_PARAMETERS:
                self.planners[pid][key] = parameter.value
        return SetParametersResult(successful=True)

    def _on_is_path_valid(self, request, response):
        poses = request.path.poses
        if not poses:
            response.is_valid = False
            return response
        costmap = self.costmap
        frame = costmap.p['global_frame']
        try:
            T, _ = self.tf_buffer.lookup(frame, costmap.p['robot_base_frame'])
            robot = planar_pose(T)[:2]
        except TransformException:
            robot = None  # upstream checks nothing when getRobotPose fails
        try:
            path = [self._in_frame(p, frame) for p in poses]
        except (TransformException, ValueError) as exc:
            self.get_logger().warning(f'is_path_valid: {str(exc).strip()}; not valid')
            response.is_valid = False
            return response
        bad = invalid_poses(costmap.grid, path, robot,
                            None if costmap.use_radius else costmap.footprint)
        response.is_valid = not bad
        response.invalid_pose_indices = bad
        return response

    def _in_frame(self, pose_stamped, frame):
        """Return ``(x, y, yaw)`` of a PoseStamped in ``frame`` (latest TF)."""
        p = pose_stamped.pose
        values = (p.position.x, p.position.y, p.orientation.x, p.orientation.y,
                  p.orientation.z, p.orientation.w)
        if not all(math.isfinite(v) for v in values):
            raise ValueError('pose has a NaN or infinite value')
        source = pose_stamped.header.frame_id or frame
        T, _ = self.tf_buffer.lookup(frame, source)
        return transform_planar(T, p)

    def _execute(self, handle):
        return self._serve(handle, ComputePathToPose, [handle.request.goal])

    def _execute_through(self, handle):
        return self._serve(handle, ComputePathThroughPoses, list(handle.request.goals))

    def _serve(self, handle, action, goals):
        goal = handle.request
        result = action.Result()
        t0 = time.perf_counter()
        frame = self.costmap.p['global_frame']
        pid = goal.planner_id or (self.ids[0] if len(self.ids) == 1 else '')
        try:
            if pid not in self.planners:
                raise PlanError('INVALID_PLANNER',
                                f'planner id {goal.planner_id!r} is not one of {self.ids}')
            if not goals:
                raise PlanError('NO_VIAPOINTS_GIVEN', 'No viapoints given')
            try:
                targets = [self._in_frame(g, frame) for g in goals]
                if goal.use_start:
                    start = self._in_frame(goal.start, frame)
                else:
                    T, _ = self.tf_buffer.lookup(frame, self.costmap.p['robot_base_frame'])
                    start = tuple(planar_pose(T))
            except TransformException as exc:
                raise PlanError('TF_ERROR', f'Could not transform the pose: {str(exc).strip()}')
            except ValueError as exc:
                raise PlanError('GOAL_OUTSIDE_MAP', f'Invalid goal: {exc}')
            planner = self.planners[pid]
            pieces = []
            for target in targets:
                piece = make_plan(self.costmap.grid, start[:2], target, planner['tolerance'],
                                  planner['allow_unknown'],
                                  planner['use_final_approach_orientation'])
                pieces.append(piece if not pieces else piece[1:])
                start = target
            path = np.concatenate(pieces)
        except PlanError as exc:
            self.get_logger().warning(f'{pid or "GridBased"}: {exc}')
            result.error_code = getattr(action.Result, exc.code)
            result.error_msg = str(exc)
            handle.abort()
            return result
        elapsed = time.perf_counter() - t0
        if self.frequency > 0 and elapsed > 1.0 / self.frequency:
            self.get_logger().warning(
                f'Planner loop missed its desired rate of {self.frequency:.4f} Hz. '
                f'Current loop rate is {1.0 / elapsed:.4f} Hz')
        result.path = self.path_message(path, frame)
        result.planning_time = Duration(nanoseconds=int(elapsed * 1e9)).to_msg()
        self._plan_pub.publish(result.path)
        handle.succeed()
        return result

    def path_message(self, path, frame):
        """Return a nav_msgs/Path of ``(n, 3)`` poses; NaN yaws stay the identity."""
        msg = Path()
        msg.header.frame_id = frame
        msg.header.stamp = self.get_clock().now().to_msg()
        for x, y, yaw in np.asarray(path, float):
            pose = PoseStamped()
            pose.header = msg.header
            pose.pose.position.x, pose.pose.position.y = float(x), float(y)
            if math.isfinite(yaw):
                set_yaw(pose.pose.orientation, float(yaw))
            else:
                pose.pose.orientation.w = 1.0
            msg.poses.append(pose)
        return msg


def main(args=None):
    """
    Run the planner server and its global costmap until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(PlannerServer, args)


if __name__ == '__main__':
    main()
