# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The package's one XML reader (lxml), for URDF, SDF, ``<ros2_control>`` and package.xml.

Comments and processing instructions are dropped, as Python's ElementTree and sdformat do,
so every child is an element; entities are not expanded and nothing is fetched from the
network (an XML bomb or an external entity in a user's file cannot cost memory or leak).
"""

from lxml import etree


class XMLError(ValueError):
    """
    A document that is not well-formed XML; the message is one line.

    :ivar line: 1-based line of the fault, or 0 when unknown.
    :ivar column: 1-based column, or 0 when unknown.
    :ivar reason: lxml's (libxml2's) words for it, one line without the position.
    """

    def __init__(self, reason, line=0, column=0):
        """Keep the reason and position; the message is ``reason (line L, column C)``."""
        self.reason, self.line, self.column = reason, line, column
        where = f' (line {line}, column {column})' if line else ''
        super().__init__(f'{reason}{where}')


def _parser(remove_blank_text=False):
    return etree.XMLParser(remove_comments=True, remove_pis=True, resolve_entities=False,
                           no_network=True, remove_blank_text=remove_blank_text)


def _error(exc):
    reason = (getattr(exc, 'msg', '') or str(exc)).splitlines()[0].strip()
    line, column = getattr(exc, 'position', (0, 0)) or (0, 0)
    # libxml2 ends some reasons with its own ', line L, column C': keep the words only
    reason = reason.split(', line ')[0].rstrip(' ,')
    return XMLError(reason or 'not well-formed', int(line or 0), int(column or 0))


def parse_text(text, remove_blank_text=False):
    """
    Parse an XML document held in memory.

    :param text: the document, str or bytes (a str may carry an encoding declaration).
    :param remove_blank_text: drop whitespace-only text between elements (yourdfpy's parser).
    :returns: the root element (lxml).
    :raises XMLError: one line with the reason, line and column.
    """
    if isinstance(text, str):
        text = text.encode('utf-8')
    try:
        root = etree.fromstring(text, _parser(remove_blank_text))
    except etree.XMLSyntaxError as exc:
        raise _error(exc) from None
    if root is None:
        raise XMLError('empty document')
    return root


def parse_file(path):
    """
    Parse an XML file.

    :param path: file path.
    :returns: the root element (lxml).
    :raises OSError: when the file cannot be read.
    :raises XMLError: one line with the reason, line and column.
    """
    with open(path, 'rb') as f:
        data = f.read()
    return parse_text(data)
