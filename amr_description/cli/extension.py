# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
How a ``ros2`` command and its verbs plug in, as ros2cli's extensions do.

ros2cli finds its commands in the entry-point group ``ros2cli.command`` and each command's
verbs in a group of their own (``ros2topic.verb``, ...). Here a command is a :class:`Command`
registered in :data:`COMMAND_GROUP` (``amr_description.command``) under its name, and a verb
is a :class:`Verb` registered in the group ``amr_description.<command>.verb``
(:func:`verb_group`) under its name: adding one is one object beside its code and one line in
setup.py. ``ros2`` (:mod:`amr_description.cli.main`) builds its parser from what is
registered; verbs are listed in name order, as ros2cli lists them.
"""

from dataclasses import dataclass
from importlib.metadata import entry_points

COMMAND_GROUP = 'amr_description.command'
"""Entry-point group of the ``ros2`` commands (ros2cli's ``ros2cli.command``)."""


def verb_group(command):
    """Return the entry-point group of a command's verbs: ``amr_description.<command>.verb``."""
    return f'amr_description.{command}.verb'


@dataclass(frozen=True)
class Verb:
    """
    A verb of a ``ros2`` command (ros2cli's ``VerbExtension``).

    :param help: the one-line help shown in the command's verb list.
    :param main: ``main(args) -> int`` (exit code); a :class:`~amr_description.cli.common.
        CliError` it raises is one line on stderr and exit code 1.
    :param add_arguments: ``add_arguments(parser)`` adding the verb's arguments, or None.
    :param description: the verb's own ``-h`` description (None: none).
    """

    help: str  # noqa: A003 - argparse's word
    main: object
    add_arguments: object = None
    description: str = None


@dataclass(frozen=True)
class Command:
    """
    A ``ros2`` command (ros2cli's ``CommandExtension``).

    A command with ``main`` runs it (``ros2 run``, ``ros2 launch``); one without has verbs,
    found in :func:`verb_group` of its name, and prints its help when none is given.

    :param help: the one-line help shown in ``ros2 -h``.
    :param add_arguments: ``add_arguments(parser)`` of a command without verbs, or None.
    :param main: ``main(args) -> int`` of a command without verbs, or None.
    :param verb_arguments: ``add_arguments(parser)`` applied to every verb's parser (the
        ``-c``/``--controller-manager`` options of ``ros2 control``), or None.
    :param verbs_metavar: the verb list's placeholder in the usage line (None: argparse's).
    :param description: the command's own ``-h`` description (None: none).
    """

    help: str  # noqa: A003 - argparse's word
    add_arguments: object = None
    main: object = None
    verb_arguments: object = None
    verbs_metavar: str = None
    description: str = None


def registered(group, found=None):
    """
    Return the entry points of ``group``, dict name -> entry point, in name order.

    :param group: the entry-point group.
    :param found: ``importlib.metadata.entry_points()`` already read (one scan per ``ros2``
        call), or None to read it.
    """
    found = entry_points() if found is None else found
    return {ep.name: ep for ep in sorted(found.select(group=group), key=lambda ep: ep.name)}


def add_commands(subparsers):
    """
    Add every registered command and its registered verbs to the ``ros2`` parser.

    :param subparsers: the top-level ``add_subparsers()`` object.
    """
    found = entry_points()
    for name, entry in registered(COMMAND_GROUP, found).items():
        command = entry.load()
        parser = subparsers.add_parser(name, help=command.help,
                                       description=command.description)
        parser.set_defaults(_command_parser=parser)
        if command.main is not None:
            if command.add_arguments is not None:
                command.add_arguments(parser)
            parser.set_defaults(main=command.main)
            continue
        verbs = parser.add_subparsers(title='Commands', dest='verb',
                                      metavar=command.verbs_metavar)
        for verb_name, verb_entry in registered(verb_group(name), found).items():
            verb = verb_entry.load()
            verb_parser = verbs.add_parser(verb_name, help=verb.help,
                                           description=verb.description)
            if verb.add_arguments is not None:
                verb.add_arguments(verb_parser)
            if command.verb_arguments is not None:
                command.verb_arguments(verb_parser)
            verb_parser.set_defaults(main=verb.main)
