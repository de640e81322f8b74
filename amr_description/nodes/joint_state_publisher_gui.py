# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
joint_state_publisher_gui: joint_state_publisher with a slider per joint, in the browser.

The upstream tool's role (ROS 2 Jazzy ``joint_state_publisher_gui``) with its window replaced
by a web page (viser) so it runs where no desktop GUI can be installed:

- parameters of our ``joint_state_publisher`` (``robot_description``, ``rate`` 10 Hz,
  ``source_list``, ``zeros``) plus ``host`` (127.0.0.1: only this machine can open the page;
  use ``ssh -L`` from another one) and ``port`` (not set: 8081 or the next free port);
- one slider with a number box per moving, non-mimic joint of the description (continuous
  joints -pi..pi, revolute/prismatic their limits; logic in
  :mod:`amr_description.core.joint_sliders`), **Center** and **Randomize** buttons;
- publishes ``sensor_msgs/JointState`` on ``/joint_states`` at ``rate``, the slider values;
  a ``source_list`` message moves the sliders, as upstream;
- the page shows the robot posed by the sliders (forward kinematics from the URDF root);
- a description that does not parse is shown on the page and logged; the node keeps running
  with the previous model;
- a port set explicitly and in use: one line naming the port and the argument, exit code 1.

Prints ``joint_state_publisher_gui: open http://HOST:PORT/ in a browser`` once serving.
"""

import sys
import threading

from amr_description.core import joint_sliders
from amr_description.nodes.joint_state_publisher import JointStatePublisher
from amr_description.web.server import run_web_node
from amr_description.web.server import serve_page
from amr_description.web.server import stop_server
from rclpy.clock import Clock
from rclpy.clock import ClockType

NODE_NAME = 'joint_state_publisher_gui'
DEFAULT_PORT = 8081
"""TCP port of the page when ``port`` is not set (the next free one when it is taken)."""


class JointStatePublisherGui(JointStatePublisher):
    """Node ``joint_state_publisher_gui`` (see the module docstring)."""

    def __init__(self):
        """
        Declare parameters, start the web page, then the joint_state_publisher part.

        :raises PortInUse: when the port cannot be bound (one line).
        :raises ValueError: on a bad parameter (one line).
        """
        self._lock = threading.RLock()
        self._gui_ready = False
        self._pending_model = None
        self._sliders = []
        self._handles = {}
        self._robot = None
        self._pose_dirty = False
        self._server = None
        super().__init__(NODE_NAME)
        self._server, self.url = serve_page(self, DEFAULT_PORT)
        server = self._server
        server.scene.set_up_direction('+z')
        server.initial_camera.position = (0.8, -0.9, 0.6)
        server.initial_camera.look_at = (0.0, 0.0, 0.0)
        server.scene.add_grid('/grid', width=2.0, height=2.0, cell_size=0.1, section_size=0.5)
        self._status = server.gui.add_markdown('Waiting for `/robot_description`...')
        buttons = server.gui.add_button_group('Joints', ('Center', 'Randomize'))
        buttons.on_click(self._on_button)
        self._folder = server.gui.add_folder('Joint positions')
        self._gui_ready = True
        if self._pending_model is not None:
            self._build(self._pending_model)
        # the drawn robot follows the sliders on the wall clock, also when sim time stands still
        self.create_timer(0.1, self._update_scene, clock=Clock(clock_type=ClockType.STEADY_TIME))

    # -- model --------------------------------------------------------------------------------

    def _set_model(self, description):
        """Parse a new description; on success rebuild the sliders, else show the error."""
        from amr_description.core.description.urdf_model import parse_urdf
        try:
            model = parse_urdf(description, source='robot_description')
            sliders = joint_sliders.sliders(model.joints.values(), self._zeros)
        except ValueError as exc:
            self.get_logger().error(str(exc))
            if self._gui_ready:
                self._status.content = f'**Cannot use the robot description:** {exc}'
            return
        super()._set_model(description)
        if self._gui_ready:
            self._build((model, sliders))
        else:
            self._pending_model = (model, sliders)

    def _build(self, model_sliders):
        """Replace the sliders and the drawn robot with those of a new model."""
        from amr_description.web.robot_scene import RobotScene
        model, sliders = model_sliders
        with self._lock:
            for handle in self._handles.values():
                handle.remove()
            self._handles = {}
            if self._robot is not None:
                self._robot.remove()
            self._sliders = sliders
            for slider in sliders:
                self._positions[slider.joint] = slider.center
            with self._folder:
                for slider in sliders:
                    handle = self._server.gui.add_slider(
                        slider.joint, min=slider.lower, max=slider.upper,
                        step=(slider.upper - slider.lower) / 10000.0,
                        initial_value=slider.center)
                    handle.on_update(self._slider_callback(slider))
                    self._handles[slider.joint] = handle
            self._robot = RobotScene(self._server.scene, model, '/robot')
            self._model = model
            self._pose_dirty = True
        problems = ''.join(f'\n\n{p}' for p in self._robot.problems)
        self._status.content = (f'Robot **{model.name}**: {len(sliders)} joints, publishing '
                                f'`/joint_states`.{problems}')

    def _slider_callback(self, slider):
        def callback(event):
            with self._lock:
                self._positions[slider.joint] = slider.clamp(event.target.value)
                self._pose_dirty = True
        return callback

    def _on_button(self, event):
        """Center or Randomize every slider (upstream's buttons)."""
        with self._lock:
            if event.target.value == 'Center':
                values = joint_sliders.centered(self._sliders)
            else:
                values = joint_sliders.randomized(self._sliders)
            for joint, value in values.items():
                self._positions[joint] = value
                if joint in self._handles:
                    self._handles[joint].value = value
            self._pose_dirty = True

    def _on_source(self, msg):
        """Merge a source_list message and move the sliders to it (as upstream)."""
        with self._lock:
            super()._on_source(msg)
            for joint, handle in self._handles.items():
                value = self._positions.get(joint)
                if value is not None and handle.value != value:
                    handle.value = value
            self._pose_dirty = True

    def _update_scene(self):
        """Pose the drawn robot from the slider values (forward kinematics, root at 0)."""
        with self._lock:
            if not self._pose_dirty or self._robot is None:
                return
            self._pose_dirty = False
            positions = dict(self._positions)
            model, robot = self._model, self._robot
        for link in model.links:
            robot.set_pose(link, model.link_pose(link, positions))

    def stop_server(self):
        """Stop the web server (closes the port)."""
        if self._server is not None:
            stop_server(self._server)
            self._server = None


def main(args=None):
    """
    Run :class:`JointStatePublisherGui` until Ctrl-C or SIGTERM (:func:`run_web_node`).

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    :returns: 0 on a clean shutdown, 1 on a port in use or a bad parameter (one line).
    """
    return run_web_node(JointStatePublisherGui, NODE_NAME, args)


if __name__ == '__main__':
    sys.exit(main())
