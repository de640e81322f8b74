# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Display classes registered in the entry-point group ``amr_description.displays``.

As RViz finds its display plugins by their class names, the viewer finds its displays here: a
display is one module (a :class:`~amr_description.web.displays.base.Display` subclass that
says its ``order``, ``parameters``, ``topics_parameter`` and ``rviz_classes``) and one line in
setup.py's group (``'laser_scan = amr_description.web.displays.laser_scan:LaserScanDisplay'``).
The viewer declares the parameters of every registered display, hands the ``.rviz`` reader
their RViz classes, makes them in ``order`` and draws them in that order.
"""

import functools
from importlib.metadata import entry_points

DISPLAY_GROUP = 'amr_description.displays'


@functools.lru_cache(maxsize=None)
def _registered():
    found = {ep.name: ep.load() for ep in entry_points(group=DISPLAY_GROUP)}
    return tuple(sorted(found.items(), key=lambda item: (item[1].order, item[0])))


def display_classes():
    """Return the registered displays, dict entry-point name -> class, in drawing order."""
    return dict(_registered())


def display_parameters(classes=None):
    """
    Return the viewer parameters the displays read, dict name -> default, first one wins.

    :param classes: dict name -> display class (default: :func:`display_classes`).
    """
    parameters = {}
    for cls in (display_classes() if classes is None else classes).values():
        for name, default in cls.parameters:
            parameters.setdefault(name, default)
    return parameters


def rviz_topic_parameters(classes=None):
    """
    Return ``{RViz display class: viewer parameter}`` of every registered display.

    :param classes: dict name -> display class (default: :func:`display_classes`).
    """
    mapping = {}
    for cls in (display_classes() if classes is None else classes).values():
        mapping.update(cls.rviz_classes)
    return mapping
