# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
An RViz 2 display configuration (``.rviz``, YAML) as the viewer can show it.

``rviz2 -d FILE`` reads ``Visualization Manager``: ``Global Options`` ``Fixed Frame`` and the
``Displays`` list (``rviz_common/Group`` entries hold their own ``Displays``), each with
``Class``, ``Name``, ``Enabled`` and, per class, its topic (``Topic: {Value: ...}``;
RobotModel's ``Description Topic``). The viewer shows the displays it has (the
``topic_parameters`` it passes: the viewer parameter each class's topic goes to, from its
registered displays; Grid, TF and Axes need none); an enabled display of any other class is
listed as not shown. A disabled
display subscribes nothing, as in RViz.
"""

from dataclasses import dataclass
from dataclasses import field

WITHOUT_TOPIC = ('rviz_default_plugins/Grid', 'rviz_default_plugins/TF',
                 'rviz_default_plugins/Axes', 'rviz_common/Group')
"""Classes shown (or walked) without a topic."""


@dataclass
class RvizConfig:
    """
    What the viewer takes from an RViz configuration.

    :param path: the file.
    :param fixed_frame: ``Global Options`` ``Fixed Frame`` ('' when absent).
    :param topics: dict viewer parameter -> list of topics, for every parameter of the
        ``topic_parameters`` read with (an empty list when the file has no such display: RViz
        would show none).
    :param tf: True when an enabled TF display is present.
    :param not_shown: ``'Name (Class)'`` of each enabled display the viewer does not have.
    """

    path: str
    fixed_frame: str = ''
    topics: dict = field(default_factory=dict)
    tf: bool = False
    not_shown: list = field(default_factory=list)


def _topic(display, cls):
    key = 'Description Topic' if cls.endswith('/RobotModel') else 'Topic'
    value = display.get(key)
    if isinstance(value, dict):
        value = value.get('Value')
    if cls.endswith('/RobotModel') and display.get('Description Source', 'Topic') != 'Topic':
        return None  # a file source: the viewer takes descriptions from topics only
    return value.strip() if isinstance(value, str) and value.strip() else None


def _walk(displays, config, where, topic_parameters):
    if not isinstance(displays, list):
        raise ValueError(f'{where}: expected a list of displays')
    for display in displays:
        if not isinstance(display, dict):
            raise ValueError(f'{where}: expected a display (a mapping), found {display!r}')
        cls = str(display.get('Class', ''))
        name = str(display.get('Name', cls.rsplit('/', 1)[-1]))
        if display.get('Enabled', True) is False:
            continue
        if cls == 'rviz_common/Group':
            _walk(display.get('Displays', []), config, f'{where} {name!r}', topic_parameters)
        elif cls == 'rviz_default_plugins/TF':
            config.tf = True
        elif cls in topic_parameters:
            topic = _topic(display, cls)
            topics = config.topics[topic_parameters[cls]]
            if topic is None:
                config.not_shown.append(f'{name} ({cls}, no topic)')
            elif topic not in topics:
                topics.append(topic)
        elif cls not in WITHOUT_TOPIC:
            config.not_shown.append(f'{name} ({cls})')


def read_rviz_config(path, topic_parameters):
    """
    Return the :class:`RvizConfig` of an ``.rviz`` file.

    :param path: the file.
    :param topic_parameters: dict RViz display class -> viewer parameter (a topic list) that
        its topic sets: the classes the viewer shows (its registered displays').
    :raises ValueError: one line naming the file and what is wrong (missing, not YAML, no
        ``Visualization Manager``, a malformed display list).
    """
    import yaml
    try:
        with open(path, encoding='utf-8') as stream:
            document = yaml.safe_load(stream)
    except OSError as exc:
        raise ValueError(f'{path}: cannot read the RViz config: {exc.strerror}') from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, 'problem_mark', None)
        where = f' (line {mark.line + 1})' if mark is not None else ''
        raise ValueError(f'{path}: not a YAML RViz config{where}') from None
    manager = document.get('Visualization Manager') if isinstance(document, dict) else None
    if not isinstance(manager, dict):
        raise ValueError(f'{path}: no "Visualization Manager" mapping: not an RViz 2 config')
    config = RvizConfig(path, topics={p: [] for p in sorted(set(topic_parameters.values()))})
    options = manager.get('Global Options') or {}
    if isinstance(options, dict):
        config.fixed_frame = str(options.get('Fixed Frame', '') or '').strip()
    try:
        _walk(manager.get('Displays', []) or [], config, f'{path}: Displays', topic_parameters)
    except ValueError as exc:
        raise ValueError(str(exc)) from None
    return config
