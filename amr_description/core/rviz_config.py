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

from amr_description.core.ros_names import topic_name_problem
from amr_description.core.yaml_text import safe_load

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
    :param problems: one line per value left out (a display whose topic is not a valid ROS
        topic name, a ``Fixed Frame`` that is not text), naming the file and the display.
    """

    path: str
    fixed_frame: str = ''
    topics: dict = field(default_factory=dict)
    tf: bool = False
    not_shown: list = field(default_factory=list)
    problems: list = field(default_factory=list)


MAX_DISPLAYS = 10000
"""More displays than this (groups counted) is refused: a YAML alias bomb, not a config."""

MAX_DEPTH = 64
"""Groups nested deeper than this are refused (RViz's own configs nest a few levels)."""


def _topic(display, cls):
    key = 'Description Topic' if cls.endswith('/RobotModel') else 'Topic'
    value = display.get(key)
    if isinstance(value, dict):
        value = value.get('Value')
    if cls.endswith('/RobotModel') and display.get('Description Source', 'Topic') != 'Topic':
        return None  # a file source: the viewer takes descriptions from topics only
    return value.strip() if isinstance(value, str) and value.strip() else None


def _walk(displays, config, where, topic_parameters, depth=0, seen=None):
    seen = [0] if seen is None else seen
    if not isinstance(displays, list):
        raise ValueError(f'{where}: expected a list of displays')
    if depth > MAX_DEPTH:
        raise ValueError(f'{where}: groups nested more than {MAX_DEPTH} deep')
    for display in displays:
        seen[0] += 1
        if seen[0] > MAX_DISPLAYS:
            raise ValueError(f'{config.path}: more than {MAX_DISPLAYS} displays (a YAML alias '
                             'bomb?)')
        if not isinstance(display, dict):
            raise ValueError(f'{where}: expected a display (a mapping), found '
                             f'{str(display)[:80]!r}')
        cls = str(display.get('Class', ''))
        name = str(display.get('Name', cls.rsplit('/', 1)[-1]))
        if display.get('Enabled', True) is False:
            continue
        if cls == 'rviz_common/Group':
            _walk(display.get('Displays', []), config, f'{where} {name!r}', topic_parameters,
                  depth + 1, seen)
        elif cls == 'rviz_default_plugins/TF':
            config.tf = True
        elif cls in topic_parameters:
            topic = _topic(display, cls)
            topics = config.topics[topic_parameters[cls]]
            problem = topic_name_problem(topic) if topic is not None else ''
            if topic is None:
                config.not_shown.append(f'{name} ({cls}, no topic)')
            elif problem:
                config.problems.append(f'{where} {name!r} ({cls}): topic {topic!r} is not a '
                                       f'valid ROS topic name: {problem}; display skipped')
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
            document = safe_load(stream, aliases=True)
    except OSError as exc:
        raise ValueError(f'{path}: cannot read the RViz config: {exc.strerror}') from None
    except UnicodeDecodeError as exc:
        raise ValueError(f'{path}: not UTF-8 text (byte {exc.object[exc.start]:#04x} at offset '
                         f'{exc.start}): not an RViz config') from None
    except RecursionError:
        raise ValueError(f'{path}: YAML nested too deeply to be an RViz config') from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, 'problem_mark', None)
        where = f' (line {mark.line + 1})' if mark is not None else ''
        problem = f': {exc.problem}' if getattr(exc, 'problem', None) else ''
        raise ValueError(f'{path}: not a YAML RViz config{where}{problem}') from None
    manager = document.get('Visualization Manager') if isinstance(document, dict) else None
    if not isinstance(manager, dict):
        raise ValueError(f'{path}: no "Visualization Manager" mapping: not an RViz 2 config')
    config = RvizConfig(path, topics={p: [] for p in sorted(set(topic_parameters.values()))})
    options = manager.get('Global Options') or {}
    if isinstance(options, dict):
        frame = options.get('Fixed Frame', '')
        if isinstance(frame, str):
            config.fixed_frame = frame.strip()
        elif frame is not None:
            config.problems.append(f'{path}: Global Options: Fixed Frame: expected a frame name '
                                   f"(text), found {str(frame)[:80]!r}; the viewer's default "
                                   'is used')
    try:
        _walk(manager.get('Displays', []) or [], config, f'{path}: Displays', topic_parameters)
    except (ValueError, RecursionError) as exc:
        raise ValueError(str(exc) if isinstance(exc, ValueError) else
                         f'{path}: displays nested too deeply') from None
    return config
