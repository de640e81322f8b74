# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A Nav2 costmap (``nav2_costmap_2d::Costmap2DROS``, Jazzy) that a server runs beside itself.

Modules: :mod:`.node` (:class:`~amr_description.nodes.costmap_2d.node.CostmapNode`: parameters,
layers, update and publication), :mod:`.services` (the clear and cost services, the
``footprint`` topic), :mod:`.parameters` (``ros2 param set`` while active).
"""

from amr_description.nodes.costmap_2d.node import CostmapNode

__all__ = ['CostmapNode']
