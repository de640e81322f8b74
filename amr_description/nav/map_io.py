# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Map files as nav2_map_server reads and writes them: a YAML file and an image (no rclpy).

Reading (``nav2_map_server/src/map_io.cpp``, ``loadMapYaml`` and ``loadMapFromFile``, Jazzy
1.3.7 and later): the YAML's ``image`` (relative to the YAML's folder), ``resolution`` (m per
cell), ``origin`` (exactly ``[x, y, yaw]``: the pose of the lower-left pixel's lower-left
corner in the map frame), ``negate`` (0/1 or a boolean), ``occupied_thresh``, ``free_thresh``
and ``mode`` (``trinary`` by default, ``scale`` or ``raw``, any case). The image is made
8-bit grey (ITU-R 601 luma for a colour image, as GraphicsMagick's grey conversion); with
``p`` that grey value, ``occ = 1 - p/255`` (``p/255`` when negated), compared in float32:

- ``trinary``: ``occ >= occupied_thresh`` is 100, else ``occ <= free_thresh`` is 0, else -1;
- ``scale``: the same ends, and between them ``round((occ - free) / (occupied - free) * 100)``;
- ``raw``: the grey value itself when 0..100, else -1;
- in ``trinary`` and ``scale``, a pixel whose alpha is below 255 is -1.

The image's top row is the grid's last row (grid cell ``(x, y)`` is pixel column ``x``, row
``height - 1 - y``). PGM files with ``#`` comment lines (ROS 1's map_saver wrote one) read.

Writing (``tryWriteMapToFile``, Jazzy 1.3.8 and later): ``trinary`` grey 8-bit, unknown (or
outside 0..100) 205, ``v <= rint(free * 100)`` 254, ``v >= rint(occupied * 100)`` 0, else 205;
``scale`` RGBA, unknown ``(127, 127, 127, 0)``, else grey ``floor((100 - v) * 255 / 100)`` (as
measured of GraphicsMagick); ``raw`` grey ``v`` (unknown 255). PGM is binary ``P5`` without a
comment; the default format is ``png`` for ``scale``, ``pgm`` otherwise. The YAML beside it
holds, in this order, ``image`` (the file name), ``mode``, ``resolution`` (3 decimals),
``origin`` (``[x, y, yaw]``, x and y with 3 decimals, yaw with 7 significant digits),
``negate: 0`` and the thresholds: ``0.65`` and ``0.196`` in ``trinary`` (whatever thresholded
the data), those used with 3 decimals otherwise.

Errors are :class:`MapError` with nav2_msgs/srv/LoadMap's result code and one line naming the
file and the field.
"""

from dataclasses import dataclass
import math
import os

from amr_description.core.yaml_text import safe_load
import numpy as np

MODES = ('trinary', 'scale', 'raw')
"""nav2_map_server's map modes."""

RESULT_MAP_DOES_NOT_EXIST = 1
RESULT_INVALID_MAP_DATA = 2
RESULT_INVALID_MAP_METADATA = 3
"""nav2_msgs/srv/LoadMap result codes of a map that cannot be loaded."""

FREE, OCCUPIED, UNKNOWN = 0, 100, -1
"""OccupancyGrid cell values."""

DEFAULT_OCCUPIED_THRESH = 0.65
DEFAULT_FREE_THRESH = 0.25
"""map_saver's thresholds when none (0) is given (``*_thresh_default`` parameters)."""

TRINARY_WRITTEN_THRESHOLDS = (0.65, 0.196)
"""What map_saver writes as ``occupied_thresh``, ``free_thresh`` of a trinary map (PR #5278):
with them the grey 205 it writes for unknown cells reads back as unknown."""

IMAGE_FORMATS = ('pgm', 'png', 'bmp')
"""Image formats written."""


class MapError(ValueError):
    """
    A map file that cannot be read or written: one line naming the file and the field.

    :ivar code: the LoadMap result code (:data:`RESULT_MAP_DOES_NOT_EXIST`,
        :data:`RESULT_INVALID_MAP_DATA`, :data:`RESULT_INVALID_MAP_METADATA`).
    """

    def __init__(self, message, code=RESULT_INVALID_MAP_METADATA):
        """Keep the message and the result code."""
        super().__init__(message)
        self.code = code


@dataclass
class MapMetadata:
    """
    What a map YAML file says.

    :param image: the image file (absolute, or as written when it has no folder to join).
    :param resolution: m per cell (> 0).
    :param origin: ``(x, y, yaw)``, m and rad, of the lower-left corner in the map frame.
    :param negate: True when light is occupied.
    :param occupied_thresh: occupancy at or above which a cell is occupied (0..1).
    :param free_thresh: occupancy at or below which a cell is free (0..1).
    :param mode: ``trinary``, ``scale`` or ``raw``.
    """

    image: str
    resolution: float
    origin: tuple
    negate: bool = False
    occupied_thresh: float = DEFAULT_OCCUPIED_THRESH
    free_thresh: float = DEFAULT_FREE_THRESH
    mode: str = 'trinary'


@dataclass
class GridMap:
    """
    An occupancy grid, as nav_msgs/OccupancyGrid holds it (REP 103, the map frame).

    :param data: (height, width) int8 cells, row 0 at the bottom (``y`` = 0): -1 unknown,
        0..100 occupancy.
    :param resolution: m per cell.
    :param origin: ``(x, y, yaw)`` of cell (0, 0)'s lower-left corner in the map frame.
    """

    data: np.ndarray
    resolution: float
    origin: tuple = (0.0, 0.0, 0.0)

    @property
    def width(self):
        """Return the number of columns (cells along x)."""
        return int(self.data.shape[1])

    @property
    def height(self):
        """Return the number of rows (cells along y)."""
        return int(self.data.shape[0])


def _number(document, key, path):
    value = document.get(key)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or \
            not math.isfinite(value):
        raise MapError(f'{path}: {key}: expected a number, found {value!r}')
    return float(value)


def read_map_yaml(path):
    """
    Read a map YAML file (``~/`` expanded).

    :param path: the YAML file.
    :returns: :class:`MapMetadata`, its image path joined to the YAML's folder.
    :raises MapError: an empty path (:data:`RESULT_MAP_DOES_NOT_EXIST`), a file that cannot
        be read or is not YAML, a missing or bad field, an unknown mode, a resolution <= 0,
        thresholds outside 0..1 or out of order (:data:`RESULT_INVALID_MAP_METADATA`).
    """
    import yaml
    if not path:
        raise MapError('map file name is empty', RESULT_MAP_DOES_NOT_EXIST)
    path = os.path.expanduser(path)
    try:
        with open(path, encoding='utf-8') as stream:
            document = safe_load(stream)
    except OSError as exc:
        raise MapError(f'{path}: cannot read the map YAML: {exc.strerror}',
                       RESULT_MAP_DOES_NOT_EXIST if isinstance(exc, FileNotFoundError)
                       else RESULT_INVALID_MAP_METADATA) from None
    except (yaml.YAMLError, UnicodeDecodeError) as exc:
        mark = getattr(exc, 'problem_mark', None)
        where = f' (line {mark.line + 1})' if mark is not None else ''
        raise MapError(f'{path}: not a YAML map file{where}') from None
    if not isinstance(document, dict):
        raise MapError(f'{path}: expected a mapping of map fields, found '
                       f'{type(document).__name__}')
    image = document.get('image')
    if not isinstance(image, str) or not image.strip():
        raise MapError(f'{path}: image: expected the image file name, found {image!r}')
    image = image.strip()
    if not os.path.isabs(image):
        image = os.path.join(os.path.dirname(os.path.abspath(path)), image)
    resolution = _number(document, 'resolution', path)
    if not resolution > 0.0:
        raise MapError(f'{path}: resolution: expected a number > 0 (m per cell), found '
                       f'{document["resolution"]!r}')
    origin = document.get('origin')
    if not isinstance(origin, list) or len(origin) != 3 or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
            for v in origin):
        raise MapError(f'{path}: origin: expected [x, y, yaw] (3 numbers), found {origin!r}')
    negate = document.get('negate')
    if negate not in (0, 1) or (not isinstance(negate, (bool, int))):
        raise MapError(f'{path}: negate: expected 0 or 1, found {negate!r}')
    occupied = _number(document, 'occupied_thresh', path)
    free = _number(document, 'free_thresh', path)
    if not 0.0 <= free <= 1.0 or not 0.0 <= occupied <= 1.0:
        raise MapError(f'{path}: thresholds: expected 0..1, found free_thresh {free:g} and '
                       f'occupied_thresh {occupied:g}')
    if not free < occupied:
        raise MapError(f'{path}: thresholds: expected free_thresh < occupied_thresh, found '
                       f'{free:g} and {occupied:g}')
    mode = document.get('mode', 'trinary')
    if not isinstance(mode, str) or mode.strip().lower() not in MODES:
        raise MapError(f'{path}: mode: expected one of {", ".join(MODES)}, found {mode!r}')
    return MapMetadata(image, resolution, tuple(float(v) for v in origin), bool(negate),
                       occupied, free, mode.strip().lower())


def read_image(path):
    """
    Read a map image as 8-bit grey and its alpha.

    :param path: PGM, PNG, BMP or any format Pillow reads.
    :returns: ``(grey, alpha)``: (H, W) uint8 arrays, top row first; ``alpha`` is None for
        an image without an alpha channel.
    :raises MapError: :data:`RESULT_INVALID_MAP_DATA`, one line naming the file.
    """
    from PIL import Image
    from PIL import UnidentifiedImageError
    try:
        with Image.open(path) as image:
            image.load()
            alpha = None
            if image.mode in ('RGBA', 'LA', 'PA') or (
                    image.mode == 'P' and 'transparency' in image.info):
                rgba = image.convert('RGBA')
                alpha = np.asarray(rgba)[:, :, 3].copy()
                grey = np.asarray(rgba.convert('L')).copy()
            elif image.mode in ('I;16', 'I;16B', 'I', 'F'):
                values = np.asarray(image, dtype=np.float64)
                top = 65535.0 if image.mode.startswith('I;16') or values.max() > 255 else 255.0
                grey = np.clip(np.rint(values * 255.0 / top), 0, 255).astype(np.uint8)
            else:
                grey = np.asarray(image.convert('L')).copy()
    except FileNotFoundError:
        raise MapError(f'{path}: map image not found', RESULT_INVALID_MAP_DATA) from None
    except (OSError, UnidentifiedImageError, ValueError) as exc:
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise MapError(f'{path}: cannot read the map image ({reason})',
                       RESULT_INVALID_MAP_DATA) from None
    if grey.ndim != 2 or not grey.size:
        raise MapError(f'{path}: the map image is empty', RESULT_INVALID_MAP_DATA)
    return grey, alpha


def occupancy_from_image(grey, alpha, metadata):
    """
    Return the grid cells of a map image (module docstring; nav2_map_server Jazzy >= 1.3.7).

    :param grey: (H, W) uint8, top row first.
    :param alpha: (H, W) uint8 or None.
    :param metadata: :class:`MapMetadata` (mode, negate, thresholds).
    :returns: (H, W) int8, row 0 at the bottom.
    """
    grey = np.asarray(grey, dtype=np.uint8)
    if metadata.mode == 'raw':
        cells = np.where(grey <= 100, grey, UNKNOWN).astype(np.int8)
    else:
        shade = grey.astype(np.float32) / np.float32(255.0)
        occ = shade if metadata.negate else np.float32(1.0) - shade
        occupied = np.float32(metadata.occupied_thresh)
        free = np.float32(metadata.free_thresh)
        cells = np.full(grey.shape, UNKNOWN, dtype=np.int8)
        if metadata.mode == 'scale':
            between = (occ > free) & (occ < occupied)
            # std::round (half away from zero) of a positive value
            value = np.floor((occ - free) / (occupied - free) * np.float32(100.0) + 0.5)
            cells[between] = value[between].astype(np.int8)
        cells[occ >= occupied] = OCCUPIED
        cells[occ <= free] = FREE  # set last: free wins, as upstream's order
        if alpha is not None:
            cells[np.asarray(alpha) < 255] = UNKNOWN
    return cells[::-1].copy()


def load_map(path):
    """
    Read a map YAML file and its image.

    :param path: the YAML file.
    :returns: ``(GridMap, MapMetadata)``.
    :raises MapError: see :func:`read_map_yaml` and :func:`read_image`.
    """
    metadata = read_map_yaml(path)
    grey, alpha = read_image(metadata.image)
    grid = GridMap(occupancy_from_image(grey, alpha, metadata), metadata.resolution,
                   metadata.origin)
    return grid, metadata


def image_from_occupancy(data, mode='trinary', free_thresh=DEFAULT_FREE_THRESH,
                         occupied_thresh=DEFAULT_OCCUPIED_THRESH):
    """
    Return the image map_saver writes for grid cells (module docstring).

    :param data: (H, W) int cells, row 0 at the bottom.
    :param mode: ``trinary``, ``scale`` or ``raw``.
    :returns: (H, W) uint8 grey, or (H, W, 4) uint8 RGBA for ``scale``; top row first.
    """
    cells = np.asarray(data, dtype=np.int16)[::-1]
    unknown = (cells < 0) | (cells > 100)
    if mode == 'scale':
        grey = ((100 - np.clip(cells, 0, 100)) * 255 // 100).astype(np.uint8)
        image = np.empty(cells.shape + (4,), dtype=np.uint8)
        image[:, :, :3] = grey[:, :, None]
        image[:, :, 3] = 255
        image[unknown] = (127, 127, 127, 0)
        return image
    if mode == 'raw':
        return np.where(unknown, 255, cells).astype(np.uint8)
    free_i = int(round(free_thresh * 100.0))
    occupied_i = int(round(occupied_thresh * 100.0))
    image = np.full(cells.shape, 205, dtype=np.uint8)
    image[~unknown & (cells >= occupied_i)] = 0
    image[~unknown & (cells <= free_i)] = 254
    return image


def _check_save(mode, free_thresh, occupied_thresh, image_format):
    mode = (mode or 'trinary').lower()
    if mode not in MODES:
        raise MapError(f'map mode: expected one of {", ".join(MODES)}, found {mode!r}')
    occupied = occupied_thresh or DEFAULT_OCCUPIED_THRESH
    free = free_thresh or DEFAULT_FREE_THRESH
    if occupied > 1.0 or free < 0.0 or occupied <= free:
        raise MapError(f'thresholds: expected 0 <= free_thresh < occupied_thresh <= 1, found '
                       f'free_thresh {free:g} and occupied_thresh {occupied:g}')
    image_format = (image_format or ('png' if mode == 'scale' else 'pgm')).lower()
    if image_format not in IMAGE_FORMATS:
        raise MapError(f'image format: expected one of {", ".join(IMAGE_FORMATS)}, found '
                       f'{image_format!r}')
    return mode, free, occupied, image_format


def format_map_yaml(image_name, grid, mode, free_thresh, occupied_thresh):
    """
    Return the map YAML text map_saver writes (Jazzy >= 1.3.8, module docstring).

    :param image_name: the image's file name (no folder).
    :param grid: :class:`GridMap` (resolution, origin).
    :param mode: the mode the image was written in.
    :param free_thresh: the free threshold used (written in ``scale`` and ``raw``).
    :param occupied_thresh: the occupied threshold used.
    """
    x, y, yaw = grid.origin
    if mode == 'trinary':
        occupied_text, free_text = (f'{v:g}' for v in TRINARY_WRITTEN_THRESHOLDS)
    else:
        occupied_text, free_text = f'{occupied_thresh:.3f}', f'{free_thresh:.3f}'
    return (f'image: {image_name}\n'
            f'mode: {mode}\n'
            f'resolution: {grid.resolution:.3f}\n'
            f'origin: [{x:.3f}, {y:.3f}, {yaw:.7g}]\n'
            'negate: 0\n'
            f'occupied_thresh: {occupied_text}\n'
            f'free_thresh: {free_text}\n')


def save_map(path, grid, mode='trinary', free_thresh=0.0, occupied_thresh=0.0,
             image_format=''):
    """
    Write a map as map_saver does: ``<path>.<format>`` and ``<path>.yaml``.

    :param path: the file name without extension (map_saver's ``-f``; ``~/`` expanded).
    :param grid: :class:`GridMap`.
    :param mode: ``trinary``, ``scale`` or ``raw`` (any case).
    :param free_thresh: 0 for :data:`DEFAULT_FREE_THRESH`.
    :param occupied_thresh: 0 for :data:`DEFAULT_OCCUPIED_THRESH`.
    :param image_format: ``pgm``, ``png`` or ``bmp``; '' for map_saver's default.
    :returns: ``(image path, yaml path)``.
    :raises MapError: bad mode, thresholds or format; a file that cannot be written.
    """
    from PIL import Image
    mode, free, occupied, image_format = _check_save(mode, free_thresh, occupied_thresh,
                                                     image_format)
    path = os.path.expanduser(path)
    image_path, yaml_path = f'{path}.{image_format}', f'{path}.yaml'
    pixels = image_from_occupancy(grid.data, mode, free, occupied)
    picture = Image.fromarray(pixels, 'RGBA' if pixels.ndim == 3 else 'L')
    try:
        picture.save(image_path, format='PPM' if image_format == 'pgm' else image_format.upper())
        with open(yaml_path, 'w', encoding='utf-8') as stream:
            stream.write(format_map_yaml(os.path.basename(image_path), grid, mode, free,
                                         occupied))
    except OSError as exc:
        raise MapError(f'{exc.filename or path}: cannot write the map: {exc.strerror or exc}',
                       RESULT_INVALID_MAP_DATA) from None
    return image_path, yaml_path
