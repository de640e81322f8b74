# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
NavSatFix as text: the newest fix of every ``navsat_topics`` entry in the panel.

RViz has no NavSatFix display (mapviz and rviz_satellite draw it on a map); the viewer shows
each fix as one line, ``latitude, longitude`` in degrees (7 decimals: about 1 cm) and the
altitude in m, with the topic's rate in the status. The line appears with the first fix.
"""

import threading
import time

from amr_description.web.displays.base import Display
from amr_description.web.displays.base import Rate
from amr_description.web.displays.discovery import AUTO
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import NavSatFix

RATE = 2.0
"""Text updates per second at most."""


def fix_text(topic, msg):
    """Return the markdown line of one ``sensor_msgs/NavSatFix``."""
    lat, lon = msg.latitude, msg.longitude
    where = (f'{abs(lat):.7f}° {"N" if lat >= 0 else "S"}, '
             f'{abs(lon):.7f}° {"E" if lon >= 0 else "W"}, {msg.altitude:.2f} m')
    status = ' (no fix)' if msg.status.status == -1 else ''  # STATUS_NO_FIX
    return f'`{topic}` {where}{status}'


class NavSatDisplay(Display):
    """The fixes of ``topics`` as text (module docstring)."""

    order = 54
    parameters = (('navsat_topics', [AUTO]),)
    topics_parameter = 'navsat_topics'

    def __init__(self, node, server, frames, topics):
        """Subscribe every topic (sensor-data QoS)."""
        super().__init__(node, server, frames)
        self._lock = threading.Lock()
        self._fixes = {}
        self._rates = {}
        self._text = None
        self._next = 0.0
        for topic in self.take_topics(topics, [NavSatFix]):
            self.add_topic(topic)

    def add_topic(self, topic):
        """Subscribe ``topic`` (sensor-data QoS)."""
        self._rates[topic] = Rate()
        self.node.create_subscription(NavSatFix, topic,
                                      lambda msg, topic=topic: self._on_fix(topic, msg),
                                      qos_profile_sensor_data)

    def _on_fix(self, topic, msg):
        self._rates[topic].tick(time.monotonic())
        with self._lock:
            self._fixes[topic] = msg

    def rates(self):
        """Return ``[(topic, Rate)]`` of the topics that have had a fix (for the status)."""
        return [(topic, rate) for topic, rate in list(self._rates.items())
                if topic in self._fixes]

    def build_panel(self, gui):
        """Add the (hidden) text."""
        self._text = gui.add_markdown('', visible=False)

    def draw(self, context):
        """Show the newest fixes, at most :data:`RATE` times a second."""
        now = time.monotonic()
        if now < self._next or self._text is None:
            return
        self._next = now + 1.0 / RATE
        with self._lock:
            lines = [fix_text(topic, msg) for topic, msg in self._fixes.items()]
        if lines:
            self._text.content = '  \n'.join(lines)
            self._text.visible = True
