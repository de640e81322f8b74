# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Map files read and written as nav2_map_server does, against hand-computed cells."""

from amr_description.nav import map_io
from amr_description.nav.map_io import GridMap
from amr_description.nav.map_io import MapError
import numpy as np
import pytest


def write_pgm(path, rows, comment=None):
    """Write a binary PGM of ``rows`` (top row first), with an optional comment line."""
    rows = np.asarray(rows, dtype=np.uint8)
    header = b'P5\n' + (f'# {comment}\n'.encode() if comment else b'')
    header += f'{rows.shape[1]} {rows.shape[0]}\n255\n'.encode()
    path.write_bytes(header + rows.tobytes())


def write_yaml(path, image='map.pgm', **fields):
    values = {'resolution': 0.05, 'origin': '[-1.0, 2.0, 0.5]', 'negate': 0,
              'occupied_thresh': 0.65, 'free_thresh': 0.196}
    values.update(fields)
    text = ''.join(f'{key}: {value}\n' for key, value in values.items() if value is not None)
    path.write_text((f'image: {image}\n' if image is not None else '') + text)
    return str(path)


def test_trinary_cells_row_order_and_the_inclusive_thresholds(tmp_path):
    # occ = 1 - p / 255: 0 -> 1.0 occupied, 254 -> 0.0039 free, 205 -> 0.19608 unknown with
    # free_thresh 0.196; 51 -> 0.8 exactly in float32: occupied when occupied_thresh is 0.8
    # (Jazzy's >=, not the old >)
    write_pgm(tmp_path / 'map.pgm', [[0, 254, 205], [51, 254, 0]], comment='CREATOR: ros1')
    grid, meta = map_io.load_map(write_yaml(tmp_path / 'map.yaml', occupied_thresh=0.8))
    assert (grid.width, grid.height, grid.resolution) == (3, 2, 0.05)
    assert grid.origin == (-1.0, 2.0, 0.5) and meta.mode == 'trinary'
    # the image's top row is the grid's last row
    assert grid.data.tolist() == [[100, 0, 100], [100, 0, -1]]
    # the classic pitfall: free_thresh 0.25 reads the unknown grey 205 as free
    grid, _ = map_io.load_map(write_yaml(tmp_path / 'map.yaml', free_thresh=0.25))
    assert grid.data[1, 2] == 0


def test_negate_raw_scale_and_alpha(tmp_path):
    from PIL import Image
    write_pgm(tmp_path / 'map.pgm', [[0, 255, 128, 101]])
    grid, _ = map_io.load_map(write_yaml(tmp_path / 'map.yaml', negate=1))
    assert grid.data.tolist() == [[0, 100, -1, -1]]  # light is occupied
    grid, _ = map_io.load_map(write_yaml(tmp_path / 'map.yaml', mode='raw'))
    assert grid.data.tolist() == [[0, -1, -1, -1]]  # 0..100 kept, 101..255 unknown
    grid, _ = map_io.load_map(write_yaml(tmp_path / 'map.yaml', mode='Scale'))
    # 128: occ 0.49804, (0.49804 - 0.196) / (0.65 - 0.196) * 100 = 66.53 -> 67;
    # 101: occ 0.60392 -> 89.85 -> 90
    assert grid.data.tolist() == [[100, 0, 67, 90]]
    # an alpha below 255 is unknown in trinary and scale
    image = np.zeros((1, 2, 2), np.uint8)
    image[0, :, 0] = 254
    image[0, :, 1] = (255, 254)
    Image.fromarray(image, 'LA').save(tmp_path / 'alpha.png')
    grid, _ = map_io.load_map(write_yaml(tmp_path / 'a.yaml', image='alpha.png'))
    assert grid.data.tolist() == [[0, -1]]


def test_saved_trinary_map_files_are_map_savers(tmp_path):
    cells = np.array([[-1, 0, 25, 26], [64, 65, 100, 101]], np.int8)
    image, yaml_path = map_io.save_map(str(tmp_path / 'saved'),
                                       GridMap(cells, 0.05, (-10.0, -2.5, 0.0)))
    data = open(image, 'rb').read()
    assert data.startswith(b'P5\n4 2\n255\n')  # binary, no comment line
    # top row first: the grid's row 1, then row 0; 0..25 free, 65..100 occupied, else 205
    assert list(data[len(b'P5\n4 2\n255\n'):]) == [205, 0, 0, 205, 205, 254, 254, 205]
    assert open(yaml_path).read() == (
        'image: saved.pgm\nmode: trinary\nresolution: 0.050\norigin: [-10.000, -2.500, 0]\n'
        'negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n')
    grid, meta = map_io.load_map(yaml_path)  # and it reads back: 205 unknown with 0.196
    assert grid.data.tolist() == [[-1, 0, 0, -1], [-1, 100, 100, -1]]
    assert meta.origin == (-10.0, -2.5, 0.0)


def test_saved_scale_and_raw_pixels(tmp_path):
    cells = np.array([[64, 65, 50, 25, -1]], np.int8)
    rgba = map_io.image_from_occupancy(cells, 'scale')
    assert rgba[0, :, 0].tolist() == [91, 89, 127, 191, 127]
    assert rgba[0, :, 3].tolist() == [255, 255, 255, 255, 0]
    assert map_io.image_from_occupancy(cells, 'raw').tolist() == [[64, 65, 50, 25, 255]]
    image, yaml_path = map_io.save_map(str(tmp_path / 's'),
                                       GridMap(cells, 0.1, (1, 2, 1.5707963)), mode='scale',
                                       free_thresh=0.2, occupied_thresh=0.7)
    assert image.endswith('s.png')  # png by default in scale mode
    text = open(yaml_path).read()
    assert 'origin: [1.000, 2.000, 1.570796]\n' in text
    assert text.endswith('occupied_thresh: 0.700\nfree_thresh: 0.200\n')
    grid, _ = map_io.load_map(yaml_path)
    # transparent: unknown; 64 was written 91: occ 0.64314, (0.64314 - 0.2) / 0.5 * 100 = 88.6
    assert grid.data[0, 4] == -1 and grid.data[0, 0] == 89


@pytest.mark.parametrize('fields, image, words, code', [
    ({}, None, 'image: expected the image file name', 3),
    ({'mode': 'ternary'}, 'map.pgm',
     "mode: expected one of trinary, scale, raw, found 'ternary'", 3),
    ({'resolution': 0}, 'map.pgm', 'resolution: expected a number > 0', 3),
    ({'resolution': 'fast'}, 'map.pgm', "resolution: expected a number, found 'fast'", 3),
    ({'origin': '[0, 0]'}, 'map.pgm', 'origin: expected [x, y, yaw] (3 numbers)', 3),
    ({'free_thresh': 0.7}, 'map.pgm', 'expected free_thresh < occupied_thresh', 3),
    ({'negate': 2}, 'map.pgm', 'negate: expected 0 or 1', 3),
    ({'occupied_thresh': None}, 'map.pgm', 'occupied_thresh: expected a number', 3),
    ({}, 'missing.pgm', 'missing.pgm: map image not found', 2),
    ({}, 'broken.pgm', 'broken.pgm: cannot read the map image', 2),
])
def test_a_bad_map_file_is_one_line_naming_the_file_and_the_field(tmp_path, fields, image,
                                                                  words, code):
    write_pgm(tmp_path / 'map.pgm', [[0]])
    (tmp_path / 'broken.pgm').write_bytes(b'P5\n2 2\n255\n\x00')
    path = write_yaml(tmp_path / 'bad.yaml', image=image, **fields)
    with pytest.raises(MapError) as error:
        map_io.load_map(path)
    assert words in str(error.value) and '\n' not in str(error.value)
    assert str(tmp_path) in str(error.value) and error.value.code == code


def test_unreadable_yaml_and_missing_file_codes(tmp_path):
    (tmp_path / 'x.yaml').write_text('image: [unclosed\n')
    with pytest.raises(MapError, match=r'x.yaml: not a YAML map file \(line 2\)') as error:
        map_io.load_map(str(tmp_path / 'x.yaml'))
    assert error.value.code == map_io.RESULT_INVALID_MAP_METADATA
    with pytest.raises(MapError) as error:
        map_io.load_map(str(tmp_path / 'none.yaml'))
    assert error.value.code == map_io.RESULT_MAP_DOES_NOT_EXIST
    with pytest.raises(MapError) as error:
        map_io.load_map('')
    assert error.value.code == map_io.RESULT_MAP_DOES_NOT_EXIST


@pytest.mark.parametrize('mode', ['trinary', 'scale', 'raw'])
def test_every_mode_round_trips(tmp_path, mode):
    rng = np.random.default_rng(7)
    if mode == 'raw':  # every value
        cells = rng.integers(-1, 101, size=(7, 5)).astype(np.int8)
    else:  # what trinary holds, and the ends and unknowns of scale
        cells = rng.choice([-1, 0, 100], size=(7, 5)).astype(np.int8)
    _, yaml_path = map_io.save_map(str(tmp_path / 'm'), GridMap(cells, 0.025, (0.5, -0.5, 0.0)),
                                   mode=mode)
    grid, meta = map_io.load_map(yaml_path)
    assert meta.mode == mode and grid.resolution == 0.025
    assert np.array_equal(grid.data, cells)
