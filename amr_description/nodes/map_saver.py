# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``map_saver_server`` and ``map_saver_cli``: nav2_map_server's map saver (Jazzy).

Node ``map_saver``, a managed (lifecycle) node. Parameters: ``save_map_timeout`` (2.0 s to
wait for a map message), ``free_thresh_default`` (0.25), ``occupied_thresh_default`` (0.65)
and ``map_subscribe_transient_local`` (true: the map subscription is reliable + transient
local, depth 1; false: reliable, volatile, depth 10). On configure it creates the service
``map_saver/save_map`` (``nav2_msgs/srv/SaveMap``: an empty ``map_topic`` is ``map``, an
unknown ``map_mode`` is trinary with a warning, a threshold of 0 is the node's default).
The files are written as map_saver writes them (:func:`amr_description.nav.map_io.save_map`).

``map_saver_cli [-t topic] [-f name] [--occ x] [--free x] [--fmt fmt] [--mode m]
[--ros-args ...]`` makes the same node, configures it, saves one map and exits 0 when the map
was saved, 1 when it was not (no map within ``save_map_timeout``, a file that cannot be
written), 255 (upstream's -1) for a bad argument. ``-h`` prints the usage and exits 0.
Source: ``nav2_map_server/src/map_saver/map_saver.cpp`` and ``main_cli.cpp``.
"""

import sys
import threading
import time

from amr_description.nav import map_io
from amr_description.nav.grid_message import grid_from_message
from amr_description.ros import shutdown
from amr_description.ros.managed_node import ManagedNode
from nav2_msgs.srv import SaveMap
from nav_msgs.msg import OccupancyGrid
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy

USAGE = """Usage:
  map_saver_cli [arguments] [--ros-args ROS remapping args]

Arguments:
  -h/--help
  -t <map_topic>
  -f <mapname>
  --occ <threshold_occupied>
  --free <threshold_free>
  --fmt <image_format>
  --mode trinary(default)/scale/raw

NOTE: --ros-args should be passed at the end of command line"""


class MapSaver(ManagedNode):
    """Node ``map_saver``; see the module docstring."""

    def __init__(self):
        """Declare the parameters; the node starts unconfigured."""
        super().__init__('map_saver')
        self.declare_parameter('save_map_timeout', 2.0)
        self.declare_parameter('free_thresh_default', 0.25)
        self.declare_parameter('occupied_thresh_default', 0.65)
        self.declare_parameter('map_subscribe_transient_local', True)
        self._save_service = None
        self._group = ReentrantCallbackGroup()

    def configure(self):
        """Read the parameters and create the ``save_map`` service."""
        self.get_logger().info('Configuring')
        self.timeout = float(self.get_parameter('save_map_timeout').value)
        self.free_default = float(self.get_parameter('free_thresh_default').value)
        self.occupied_default = float(self.get_parameter('occupied_thresh_default').value)
        self.transient_local = bool(self.get_parameter('map_subscribe_transient_local').value)
        self._save_service = self.create_service(
            SaveMap, self.get_name() + '/save_map', self._on_save_map,
            callback_group=self._group)

    def cleanup(self):
        """Remove the service."""
        if self._save_service is not None:
            self.destroy_service(self._save_service)
            self._save_service = None

    def _on_save_map(self, request, response):
        response.result = self.save(
            request.map_topic, request.map_url, request.image_format, request.map_mode,
            request.free_thresh, request.occupied_thresh)
        return response

    def save(self, topic, path, image_format='', mode='', free=0.0, occupied=0.0,
             wait=None):
        """
        Wait for one map on ``topic`` and write it to ``path``.

        :param topic: the map topic ('' for ``map``).
        :param path: the file name without extension ('' for ``map_<unix seconds>``).
        :param wait: callable ``wait(event, timeout)`` that waits for the map while the node
            is spun (default: ``event.wait``, for a node spun by an executor thread).
        :returns: True when the map was saved.
        """
        log = self.get_logger()
        topic = topic or 'map'
        path = path or f'map_{int(time.time())}'
        mode = (mode or 'trinary').lower()
        if mode not in map_io.MODES:
            log.warn(f'Map mode parameter not recognized: "{mode}", using default value '
                     '(trinary)')
            mode = 'trinary'
        log.info(f"Saving map from '{topic}' topic to '{path}' file")
        if not free:
            log.warn(f'Free threshold unspecified. Setting it to default value: '
                     f'{self.free_default:f}')
            free = self.free_default
        if not occupied:
            log.warn(f'Occupied threshold unspecified. Setting it to default value: '
                     f'{self.occupied_default:f}')
            occupied = self.occupied_default
        received = []
        event = threading.Event()

        def on_map(msg):
            if not received:
                received.append(msg)
                event.set()
        qos = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                         durability=DurabilityPolicy.TRANSIENT_LOCAL) \
            if self.transient_local else QoSProfile(depth=10)
        subscription = self.create_subscription(OccupancyGrid, topic, on_map, qos,
                                                callback_group=self._group)
        try:
            (wait or (lambda e, t: e.wait(t)))(event, self.timeout)
        finally:
            self.destroy_subscription(subscription)
        if not received:
            log.error(f'Failed to save the map: no map received on {topic} within '
                      f'{self.timeout:g} s (save_map_timeout)')
            return False
        try:
            grid = grid_from_message(received[0])
            log.info(f'Received a {grid.width} X {grid.height} map @ {grid.resolution:g} m/pix')
            image_path, yaml_path = map_io.save_map(path, grid, mode, free, occupied,
                                                    image_format)
        except (ValueError, map_io.MapError) as exc:
            log.error(f'Failed to save the map: {exc}')
            return False
        log.info(f'Writing map occupancy data to {image_path}')
        log.info(f'Writing map metadata to {yaml_path}')
        log.info('Map saved successfully')
        return True


def server_main(args=None):
    """
    Run ``map_saver_server`` until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(MapSaver, args, threads=2)


FLAGS = {'-t': 'topic', '-f': 'path', '--occ': 'occupied', '--free': 'free', '--fmt': 'fmt',
         '--mode': 'mode'}


def parse_cli(argv):
    """
    Parse ``map_saver_cli``'s arguments (before ``--ros-args``).

    :param argv: the arguments, program name excluded.
    :returns: a dict with ``topic``, ``path``, ``occupied``, ``free``, ``fmt``, ``mode`` and
        ``help`` (True for ``-h``).
    :raises ValueError: an unknown argument, a flag without its value, or a threshold that is
        not a number.
    """
    options = {'topic': '', 'path': '', 'occupied': 0.0, 'free': 0.0, 'fmt': '', 'mode': '',
               'help': False}
    words = list(argv)
    if '--ros-args' in words:
        words = words[:words.index('--ros-args')]
    i = 0
    while i < len(words):
        word = words[i]
        if word in ('-h', '--help'):
            options['help'] = True
        elif word in FLAGS:
            if i + 1 >= len(words):
                raise ValueError(f'Value expected after {word}')
            value = words[i + 1]
            if word in ('--occ', '--free'):
                try:
                    value = float(value)
                except ValueError:
                    raise ValueError(f'{word}: expected a number, found {value!r}') from None
            options[FLAGS[word]] = value
            i += 1
        else:
            raise ValueError(f'Wrong argument: {word} should be followed by a value.'
                             if word.startswith('-') else f'Wrong argument: {word}')
        i += 1
    return options


def cli_main(args=None):
    """
    ``map_saver_cli``: save one map and exit (codes in the module docstring).

    :param args: command line, program name first (default ``sys.argv``).
    """
    argv = sys.argv if args is None else list(args)
    try:
        options = parse_cli(argv[1:])
    except ValueError as exc:
        print(f'[ERROR] [map_saver_cli]: {exc}', file=sys.stderr)
        print(USAGE)
        sys.exit(255)
    if options['help']:
        print(USAGE)
        sys.exit(0)
    node = None
    saved = False
    try:
        shutdown.init(argv)
        node = shutdown.create(MapSaver)
        node.trigger_configure()
        if node._save_service is None:
            raise SystemExit(1)

        def wait(event, timeout):
            deadline = time.monotonic() + timeout
            shutdown.spin(node, until=lambda: event.is_set() or time.monotonic() >= deadline,
                          period=0.05)
        saved = node.save(options['topic'], options['path'], options['fmt'], options['mode'],
                          options['free'], options['occupied'], wait=wait)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown.shutdown(node)
    sys.exit(0 if saved else 1)


if __name__ == '__main__':
    cli_main()
