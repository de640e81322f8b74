# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Status: what RViz's status panel and time panel say, as one text on the page.

Description errors, the fixed frame (and why another is shown), frames without a transform,
a backward jump of ``/clock`` (for :data:`JUMP_SHOWN` s), sim time and real-time factor from
``/clock``, and the rates of ``/clock``, ``/joint_states`` (as remapped), the first odometry
topic, the sensor topics and ``/tf``.
Refreshed every :data:`PERIOD` s, and at once when a robot description arrives.
"""

import os
import time

from amr_description.web.displays.base import Display
from amr_description.web.displays.base import Rate
from amr_description.web.displays.base import RATE_WINDOW
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import JointState

PERIOD = 0.5
"""Seconds (wall) between two refreshes of the text."""
JUMP_SHOWN = 10.0
"""Seconds (wall) a backward jump of ``/clock`` stays in the text."""


class StatusDisplay(Display):
    """
    The status text.

    :param robot_model: the :class:`~amr_description.web.displays.robot_model.
        RobotModelDisplay` (its robots, errors and topics).
    :param trails: the :class:`~amr_description.web.displays.trails.TrailsDisplay` (the rate
        of its first topic).
    :param sensors: displays with ``rates()`` -> ``[(topic, Rate)]`` of their sensor topics.
    """

    order = 100
    panel_order = 0  # its text tops the panel; drawn last: it reports what others saw

    @classmethod
    def create(cls, viewer, settings):
        """
        Make the status of the displays made before it.

        The robot model, the odometry trails and every display with ``rates()``; an
        ``.rviz`` file (``settings['rviz']``) is named with the displays it has that no
        registered display shows.
        """
        from amr_description.web.displays.robot_model import RobotModelDisplay
        from amr_description.web.displays.trails import TrailsDisplay
        made = list(viewer.displays)
        robot_model = next((d for d in made if isinstance(d, RobotModelDisplay)), None)
        trails = next((d for d in made if isinstance(d, TrailsDisplay)), None)
        sensors = [d for d in made if callable(getattr(d, 'rates', None))]
        display = cls(viewer, viewer.server, viewer.frames, robot_model, trails, *sensors)
        rviz = settings.get('rviz')
        if rviz is not None:
            display.notes.append(
                f'RViz config `{os.path.basename(rviz.path)}`'
                + (f': not shown: {", ".join(rviz.not_shown)}' if rviz.not_shown
                   else ': every display shown'))
        return display

    def __init__(self, node, server, frames, robot_model, trails, *sensors):
        """Count ``/joint_states`` (taken raw, never converted to a Python message)."""
        super().__init__(node, server, frames)
        self._robot_model = robot_model
        self._trails = trails
        self._sensors = sensors
        self._joint_states_rate = Rate()
        subscription = node.create_subscription(
            JointState, '/joint_states',
            lambda msg: self._joint_states_rate.tick(time.monotonic()),
            qos_profile_sensor_data, raw=True)
        self.joint_states = subscription.topic_name  # as remapped
        self.notes = []  # lines shown under the rates (the RViz config's displays not shown)
        self._next = 0.0

    def build_panel(self, gui):
        """Add the status text (at the top of the panel)."""
        self._text = gui.add_markdown('Waiting for data...')

    def rates(self):
        """Return ``[(topic, Rate)]`` in the order shown."""
        rates = [('/clock', self.frames.rates['/clock']),
                 (self.joint_states, self._joint_states_rate)]
        if self._trails.rated_topic is not None:
            rates.append((self._trails.rated_topic, self._trails.rate))
        for display in self._sensors:
            rates += display.rates()
        return rates + [('/tf', self.frames.rates['/tf'])]

    def draw(self, context):
        """Refresh the text every :data:`PERIOD` s, or at once after a description came."""
        now = time.monotonic()
        if now < self._next and not self._robot_model.changed:
            return
        self._robot_model.changed = False
        self._next = now + PERIOD
        self._text.content = '\n\n'.join(self._lines(context, now))

    def _lines(self, context, now):
        robot_model, frames = self._robot_model, self.frames
        lines = [f'**Robot description error** ({topic}): {error}'
                 for topic, error in robot_model.errors.items()]
        if not robot_model.robots:
            lines.append('Waiting for ' + (', '.join(f'`{t}`' for t in robot_model.topics)
                                           or 'a `robot_description` topic') + '...')
        lines.append(f'Fixed Frame: **{context.fixed}**'
                     + (f' ({context.note})' if context.note else ''))
        missing = sorted(set(context.missing))
        if missing and robot_model.robots:
            lines.append(f'No transform to {", ".join(missing[:4])}'
                         + (' ...' if len(missing) > 4 else ''))
        if frames.last_jump is not None and now - frames.last_jump[0] < JUMP_SHOWN:
            _, before, after = frames.last_jump
            lines.append(f'/clock jumped back in time ({before:.2f} s -> {after:.2f} s'
                         + (f', {frames.jumps} jumps' if frames.jumps > 1 else '')
                         + '): transforms cleared')
        samples = frames.clock_samples
        running = bool(samples) and now - samples[-1][0] < RATE_WINDOW
        if frames.sim_time is not None and running:
            rtf = ''
            if len(samples) >= 2:
                (w0, s0), (w1, s1) = samples[0], samples[-1]
                if w1 > w0:
                    rtf = f', real-time factor **{(s1 - s0) / (w1 - w0):.2f}**'
            lines.append(f'Sim time **{frames.sim_time:.2f} s**{rtf}')
        elif frames.sim_time is not None:
            lines.append(f'Sim time **{frames.sim_time:.2f} s** (paused or stopped)')
        else:
            lines.append('No `/clock`: wall time')
        lines.append(' · '.join(f'`{name}` {rate.hz(now):.1f} Hz' for name, rate in self.rates()))
        return lines + self.notes
