# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A ray-cast lidar: ``gpu_lidar``, ``lidar``, ``ray`` and ``gpu_ray`` sensor blocks.

Every type is cast on the CPU with MuJoCo's ``mj_multiRay`` (one call per scan, all rays from
the sensor site; the geoms of the sensor's own link are not seen). What reaches ROS is what
ros_gz_bridge makes of gz-sensors 8's messages:

- ``sensor_msgs/LaserScan`` on ``<topic>``: ``angle_min``/``angle_max`` the horizontal
  ``min_angle``/``max_angle``, ``angle_increment`` (max - min) / (count - 1) (gz-sensors
  ``Lidar::AngleResolution``), ``time_increment`` and ``scan_time`` 0 (the bridge's
  ``convert_gz_to_ros``), ``range_min``/``range_max`` from ``<range>``, the middle row of a
  multi-row lidar, intensities 0 (no ``laser_retro``);
- ``sensor_msgs/PointCloud2`` on ``<topic>/points``: one row per vertical ray, fields ``x``,
  ``y``, ``z`` (float32, offsets 0, 4, 8), ``intensity`` (float32, 16), ``ring`` (uint16, 24),
  ``point_step`` 32 (gz-msgs ``InitPointCloudPacked`` with memory alignment), points in the
  sensor frame ``depth * (cos v cos h, cos v sin h, sin v)`` (``GpuLidarSensor.cc``
  ``FillPointCloudMsg``), ``is_dense`` false when a range is not finite.

Ranges (REP 117, gz-sensors 8 ``SetClamp(false)``): no hit within ``range_max`` is +inf, a hit
closer than ``range_min`` is -inf; gaussian noise is added to finite ranges, which are then
clamped to [``range_min``, ``range_max``] (``Lidar.cc``). The frame id is ``<gz_frame_id>``,
else the URDF link of ``reference`` (Gazebo would say ``model/link/sensor`` after lumping),
with the entity's frame prefix. Rays are cast on the poses of the measured instant
(:meth:`~amr_description.sim.world.World.update_kinematics`).
"""

import array

from amr_description.ros.stamps import set_stamp
from amr_description.sim.sensors.base import Sensor
from amr_description.sim.sensors.base import sensor_frame
from amr_description.sim.sensors.base import sensor_rate
from amr_description.sim.sensors.base import sensor_topic
from amr_description.sim.sensors.mount import site_name
from amr_description.sim.sensors.noise import generator
from amr_description.sim.sensors.noise import NoiseModel
import mujoco
import numpy as np
from sensor_msgs.msg import LaserScan
from sensor_msgs.msg import PointCloud2
from sensor_msgs.msg import PointField

POINT_FIELDS = (('x', 0, PointField.FLOAT32), ('y', 4, PointField.FLOAT32),
                ('z', 8, PointField.FLOAT32), ('intensity', 16, PointField.FLOAT32),
                ('ring', 24, PointField.UINT16))
"""PointCloud2 fields of a gz-sensors lidar: (name, offset, datatype), ``point_step`` 32."""

POINT_DTYPE = np.dtype({'names': ['x', 'y', 'z', 'intensity', 'ring'],
                        'formats': ['<f4', '<f4', '<f4', '<f4', '<u2'],
                        'offsets': [0, 4, 8, 16, 24], 'itemsize': 32})


class LidarCast:
    """
    The rays of one lidar and its last scan (no rclpy).

    :param prefix: the entity's name prefix in the world (``<entity>/``).
    :param block: the :class:`~amr_description.core.gazebo.sensors.SensorBlock`.
    :param rng: numpy ``Generator`` of its noise.
    :ivar ranges: (rows, columns) float64, m, the last scan after REP 117 and noise.
    :ivar directions: (rows * columns, 3) unit ray directions in the sensor frame.
    """

    def __init__(self, prefix, block, rng):
        """Precompute the ray directions (see the class docstring)."""
        lidar = block.lidar
        self.spec = lidar
        self.site = prefix + site_name(block)
        self.horizontal = np.array(lidar.horizontal.angles())
        self.vertical = np.array(lidar.vertical.angles())
        v, h = np.meshgrid(self.vertical, self.horizontal, indexing='ij')
        self.directions = np.stack([np.cos(v) * np.cos(h), np.cos(v) * np.sin(h), np.sin(v)],
                                   axis=-1).reshape(-1, 3)
        self.noise = NoiseModel(lidar.noise, rng)
        n = len(self.directions)
        self._geomid = np.zeros(n, dtype=np.int32)
        self._dist = np.zeros(n)
        self._vec = np.zeros(3 * n)
        self.ranges = np.full((len(self.vertical), len(self.horizontal)), np.inf)
        self.time = None
        self._model = None
        self._owed = None  # the instant of a scan accounted for but not cast (advance)

    def cast(self, world, t):
        """
        Cast the scan of sim time ``t`` (s) once; return :attr:`ranges`.

        :raises KeyError: when the sensor's site is not in the world's model.
        """
        if self.time == t and self._model is world.model:
            return self.ranges
        if self._owed != t:
            self._settle()
        self._owed = None
        model, data = world.model, world.data
        if self._model is not model:
            site = model.site(self.site)
            self._site_id = site.id
            self._body = int(model.site_bodyid[site.id])
            self._model = model
        world.update_kinematics()
        rotation = data.site_xmat[self._site_id].reshape(3, 3)
        self._vec[:] = (self.directions @ rotation.T).ravel()
        mujoco.mj_multiRay(model, data, data.site_xpos[self._site_id], self._vec, None, 1,
                           self._body, self._geomid, self._dist, None, len(self._dist),
                           self.spec.range_max)
        self.ranges = self.ranges_from_distances(self._dist).reshape(self.ranges.shape)
        self.time = t
        return self.ranges

    def advance(self, t):
        """
        Account for the scan of sim time ``t`` (s) that nobody hears, without casting it.

        The scan is owed: a :meth:`cast` at the same ``t`` (another output of this lidar is
        heard) casts it as usual; otherwise its noise is drawn and discarded before the next
        instant's, so the generator's sequence is the same as if every scan had been cast.
        """
        if self.time == t or self._owed == t:
            return
        self._settle()
        self._owed = t

    def _settle(self):
        """Draw and discard the noise of an owed scan (one number per ray)."""
        if self._owed is not None:
            self.noise.skip(len(self._dist))
            self._owed = None

    def ranges_from_distances(self, dist):
        """
        Return REP 117 ranges with noise from ray distances (m, -1 for no hit).

        :param dist: (n,) m from ``mj_multiRay``.
        :returns: (n,) m: +inf no hit within ``range_max``, -inf a hit before ``range_min``,
            else the distance with noise clamped to [``range_min``, ``range_max``].
        """
        lidar = self.spec
        ranges = np.where((dist < 0) | (dist > lidar.range_max), np.inf, dist)
        ranges = np.where(ranges < lidar.range_min, -np.inf, ranges)
        if self.noise.active:
            noisy = self.noise.apply(ranges)
            ranges = np.where(np.isfinite(ranges),
                              np.clip(noisy, lidar.range_min, lidar.range_max), ranges)
        return ranges


class _LidarOutput(Sensor):
    """
    One message of a lidar, made from its shared :class:`LidarCast`.

    :param cast: the :class:`LidarCast`.
    :param name: sensor name (unique within the entity).
    :param topics: ``(ROS topic, gz topic)``.
    :param frame_id: ``header.frame_id``.
    :param rate: Hz of sim time.
    """

    def __init__(self, cast, name, topics, frame_id, rate):
        """Keep the fields (see the class docstring)."""
        self.cast = cast
        self.name = name
        self.topic, self.gz_name = topics
        self.frame_id = frame_id
        self.rate = float(rate)


class LidarScan(_LidarOutput):
    """
    The LaserScan of one lidar (module docstring); measured at every due instant.

    Not ``costly``: its noise sequence must not depend on who listens.
    """

    message_type = LaserScan

    def __init__(self, cast, name, topics, frame_id, rate):
        """Prepare the reused message (see the module docstring)."""
        super().__init__(cast, name, topics, frame_id, rate)
        lidar = cast.spec
        msg = LaserScan()
        msg.header.frame_id = frame_id
        msg.angle_min = float(lidar.horizontal.min_angle)
        msg.angle_max = float(lidar.horizontal.max_angle)
        count = len(cast.horizontal)
        msg.angle_increment = float((lidar.horizontal.max_angle - lidar.horizontal.min_angle)
                                    / (count - 1)) if count > 1 else 0.0
        msg.time_increment = 0.0
        msg.scan_time = 0.0
        msg.range_min = float(lidar.range_min)
        msg.range_max = float(lidar.range_max)
        msg.intensities = array.array('f', bytes(4 * count))
        self._row = len(cast.vertical) // 2
        self._msg = msg

    def measure(self, world, t):
        """Return the LaserScan of sim time ``t`` (s): the middle row of the scan."""
        ranges = self.cast.cast(world, t)
        set_stamp(self._msg.header.stamp, t)
        self._msg.ranges = array.array('f', ranges[self._row].astype(np.float32).tobytes())
        return self._msg

    def advance(self, world, t):
        """Owe the cast of ``t`` (s) to the lidar (:meth:`LidarCast.advance`): no rays."""
        self.cast.advance(t)


class LidarPoints(_LidarOutput):
    """The PointCloud2 of one lidar (module docstring); skipped while nobody listens."""

    message_type = PointCloud2
    costly = True

    def __init__(self, cast, name, topics, frame_id, rate):
        """Prepare the reused message (see the module docstring)."""
        super().__init__(cast, name, topics, frame_id, rate)
        msg = PointCloud2()
        msg.header.frame_id = frame_id
        msg.height = len(cast.vertical)
        msg.width = len(cast.horizontal)
        msg.fields = [PointField(name=n, offset=o, datatype=d, count=1)
                      for n, o, d in POINT_FIELDS]
        msg.is_bigendian = False
        msg.point_step = POINT_DTYPE.itemsize
        msg.row_step = msg.point_step * msg.width
        self._points = np.zeros(msg.height * msg.width, dtype=POINT_DTYPE)
        self._points['ring'] = np.repeat(np.arange(msg.height, dtype=np.uint16), msg.width)
        self._msg = msg

    def measure(self, world, t):
        """Return the PointCloud2 of sim time ``t`` (s) (module docstring)."""
        ranges = self.cast.cast(world, t).ravel()
        with np.errstate(invalid='ignore'):
            xyz = self.cast.directions * ranges[:, None]
        points = self._points
        points['x'], points['y'], points['z'] = xyz[:, 0], xyz[:, 1], xyz[:, 2]
        msg = self._msg
        set_stamp(msg.header.stamp, t)
        msg.is_dense = bool(np.isfinite(ranges).all())
        msg.data = array.array('B', points.tobytes())
        return msg


def create(entity, settings):
    """
    Return the LaserScan and PointCloud2 sensors of every lidar block of ``entity``.

    :param entity: the spawned entity (``description.sensors``, ``robot.prefix``).
    :param settings: dict; ``seed`` (int, default 0), ``physics_step`` (s, default 0.001),
        ``world`` (the world's name, for gz's default topics, default ``empty``).
    """
    sensors = []
    step = float(settings.get('physics_step', 0.001))
    for block in entity.description.sensors.sensors:
        if block.kind != 'lidar':
            continue
        cast = LidarCast(entity.robot.prefix, block,
                         generator(settings.get('seed', 0), entity.name, block.name))
        topic, gz_name = sensor_topic(entity, block, settings.get('world', 'empty'))
        frame = sensor_frame(entity, block)
        rate = sensor_rate(block, step)
        sensors.append(LidarScan(cast, block.name, (topic, gz_name), frame, rate))
        sensors.append(LidarPoints(cast, f'{block.name}/points',
                                   (f'{topic}/points', f'{gz_name}/points'), frame, rate))
    return sensors
