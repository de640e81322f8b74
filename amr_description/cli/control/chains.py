# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The ``ros2 control`` verb ``view_controller_chains`` (the diagram: :mod:`.chains_diagram`)."""

from amr_description.cli.control.api import run
from amr_description.cli.extension import Verb
from amr_description.control import controller_manager_services as cms


def _args_view_controller_chains(p):
    p.add_argument('--save', action='store_true',
                   help='Save the diagram as controller_diagram.pdf in the current directory '
                   'instead of opening it in a viewer')


def _view_controller_chains(args):
    from amr_description.cli.control import chains_diagram

    def body(node, cm):
        controllers = cms.list_controllers(node, cm)
        hardware = cms.list_hardware_components(node, cm)
        return chains_diagram.write_diagram(controllers, hardware, view=not args.save)
    return run(args, body)


VERB_VIEW_CONTROLLER_CHAINS = Verb(
    'Generates a diagram of the loaded chained controllers',
    _view_controller_chains, _args_view_controller_chains,
    description='Generates a diagram of the loaded chained controllers')
"""``ros2 control view_controller_chains``."""
