# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
YAML from users' files, read safely: no aliases where ROS reads none, no unbounded nesting.

PyYAML's ``safe_load`` shares an aliased node instead of copying it, so a "billion laughs"
file loads in microseconds, then costs minutes and gigabytes to whoever walks or prints it;
and it recurses once per nesting level, so thousands of ``[`` end in ``RecursionError``.
ROS 2's parameter files are read by rcl's YAML parser, which refuses aliases (an
``ALIAS`` event is an error in ``rcl_yaml_param_parser``): parameter, controller and bridge
files are read here the same way.
"""

import yaml

MAX_DEPTH = 100
"""Nesting deeper than this is refused (ROS files nest a few levels)."""


class _Loader(yaml.SafeLoader):
    """PyYAML's safe loader that refuses aliases and nesting over :data:`MAX_DEPTH`."""

    allow_aliases = False
    _depth = 0

    def compose_node(self, parent, index):
        """Compose one node, refusing an alias or one nested too deeply (PyYAML API)."""
        if not self.allow_aliases and self.check_event(yaml.AliasEvent):
            event = self.peek_event()
            raise yaml.composer.ComposerError(
                None, None, 'aliases (*name) are not allowed in this file', event.start_mark)
        self._depth += 1
        try:
            if self._depth > MAX_DEPTH:
                raise yaml.composer.ComposerError(
                    None, None, f'nested more than {MAX_DEPTH} levels deep',
                    self.peek_event().start_mark)
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1


class _AliasLoader(_Loader):
    allow_aliases = True


def safe_load(stream, aliases=False):
    """
    Parse YAML as ``yaml.safe_load`` does, refusing aliases and deep nesting.

    :param stream: text, bytes or an open file.
    :param aliases: allow ``&anchor`` / ``*alias`` (a file format that has them: ``.rviz``).
    :returns: the document (dict, list, scalar or None).
    :raises yaml.YAMLError: as ``yaml.safe_load``; a refused alias or nesting is a
        ``ComposerError`` with the line (``problem_mark``); a file that is not UTF-8 a
        ``MarkedYAMLError`` whose ``problem`` names the byte and its offset.
    """
    try:
        return yaml.load(stream, Loader=_AliasLoader if aliases else _Loader)  # noqa: S506
    except UnicodeDecodeError as exc:  # a text file opened as UTF-8 that is not
        raise yaml.MarkedYAMLError(problem=f'not UTF-8 text (byte {exc.object[exc.start]:#04x} '
                                   f'at offset {exc.start})') from None
