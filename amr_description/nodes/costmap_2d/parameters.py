# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2 param set`` on a costmap while active, as Costmap2DROS's and its layers' callbacks.

:class:`CostmapParameters` is mixed into :class:`amr_description.nodes.costmap_2d.node.CostmapNode`
(its ``p``, ``layers``, ``_lock`` and grid). Sources: ``dynamicParametersCallback`` of
``nav2_costmap_2d/src/costmap_2d_ros.cpp`` and of ``nav2_costmap_2d/plugins/``.
"""

import time

from amr_description.core.tf_buffer import TransformException
from amr_description.nav import costmap as cm
from rcl_interfaces.msg import SetParametersResult

DYNAMIC = ('robot_radius footprint_padding transform_tolerance publish_frequency resolution '
           'origin_x origin_y width height footprint robot_base_frame').split()
"""Costmap2DROS's parameters its callback takes."""


class CostmapParameters:
    """The costmap node's parameter callback (a mixin of the node)."""

    def _on_set_parameters(self, parameters):
        """
        Take ``ros2 param set`` values while active, as upstream's dynamic parameter callbacks.

        Costmap2DROS's ``robot_radius`` (the footprint, if made from the radius at start-up),
        ``footprint`` (kept when it does not parse, with one error line), ``footprint_padding``,
        ``transform_tolerance``, ``publish_frequency`` (0 or less: not published),
        ``resolution``, ``origin_x``, ``origin_y``, ``width`` and ``height`` (a new empty grid,
        unless the static layer's map fixed the size) and ``robot_base_frame`` (refused when TF
        cannot join it to ``global_frame`` within 1 s); each layer's ``enabled``; the inflation
        layer's ``inflation_radius``, ``cost_scaling_factor``, ``inflate_unknown`` and
        ``inflate_around_unknown``; the obstacle layer's ``footprint_clearing_enabled``. A
        ``width`` or ``height`` of 0 or less is refused with upstream's line, a ``resolution`` of 0
        or less with ours. Sources:
        ``dynamicParametersCallback`` of ``nav2_costmap_2d/src/costmap_2d_ros.cpp`` and
        ``nav2_costmap_2d/plugins/``.
        """
        for parameter in parameters:
            name, value, line = parameter.name, parameter.value, None
            if name in ('width', 'height') and value <= 0:
                line = (f"You try to set {name} of map to be negative or zero, this isn't "
                        'allowed, please give a positive value.')
            elif name == 'resolution' and not value > 0.0:  # upstream divides by it
                line = f'resolution must be above 0 m, got {value}; not changed'
            elif name == 'robot_base_frame' and not self._joins(value):
                return SetParametersResult(successful=False, reason=f'no transform to {value}')
            if line is not None:
                self.get_logger().error(line)
                return SetParametersResult(successful=False, reason=line)
        with self._lock:
            resize = False
            for parameter in parameters:
                resize |= self._apply_parameter(parameter.name, parameter.value)
            locked = self.static is not None and not self.p['rolling_window']
            if resize and not locked:
                self.grid = self._empty_grid()
                self.obstacles = self._blank()
                self._update()
        return SetParametersResult(successful=True)

    def _joins(self, base, wait=1.0):
        """Return True when TF joins ``base`` to ``global_frame`` within ``wait`` s (wall)."""
        self.get_logger().info('Checking transform')
        deadline = time.monotonic() + wait
        while True:
            try:
                self.tf.lookup(self.p['global_frame'], base)
                return True
            except TransformException as exc:
                if time.monotonic() >= deadline:
                    self.get_logger().warning(
                        f'Timed out waiting for transform from {base} to {self.p["global_frame"]}'
                        f' to become available, tf error: {str(exc).strip()}')
                    self.get_logger().warning(
                        f'Rejecting robot_base_frame change to {base} , leaving it to its '
                        f"original value of {self.p['robot_base_frame']}")
                    return False
            time.sleep(0.05)

    def _apply_parameter(self, name, value):
        """Apply one checked value; return True when the grid's geometry changed."""
        layer, _, key = name.partition('.')
        for _kind, layer_name, params in self.layers:
            if layer_name == layer and key in params and key not in (
                    'map_topic', 'map_subscribe_transient_local', 'sources'):
                params[key] = value
                return False
        if name not in DYNAMIC:
            return False
        if name == 'footprint':
            self.p['footprint'] = value
            try:
                self._set_footprint(cm.parse_footprint(value))
            except ValueError as exc:
                self.get_logger().error(f'{exc}; the footprint is unchanged')
            return False
        self.p[name] = value
        if name == 'robot_radius' and self.use_radius:
            self._set_footprint(cm.footprint_from_radius(value))
        elif name == 'footprint_padding':
            self._set_footprint(self.unpadded)
        elif name == 'publish_frequency' and value > 0.0 and self._entities:
            self._publish_timer.timer_period_ns = int(1e9 / value)
            self._publish_timer.reset()
        return name in ('resolution', 'origin_x', 'origin_y', 'width', 'height')
