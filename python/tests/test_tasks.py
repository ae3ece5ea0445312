"""Splitting frames into tiles: every pixel in exactly one tile."""

import itertools

import pytest

from snell_farm.tasks import Region, grid, parse_grid, regions_of_size, split


def coverage(width, height, regions):
    counts = [[0] * width for _ in range(height)]
    for r in regions:
        assert 0 <= r.x0 < r.x1 <= width and 0 <= r.y0 < r.y1 <= height, r
        for y in range(r.y0, r.y1):
            for x in range(r.x0, r.x1):
                counts[y][x] += 1
    return counts


@pytest.mark.parametrize("width, height, columns, rows", [
    (48, 32, 2, 2), (48, 32, 1, 1), (10, 7, 4, 3), (7, 5, 7, 5), (1, 1, 1, 1), (100, 3, 9, 2),
])
def test_grid_covers_every_pixel_once(width, height, columns, rows):
    regions = grid(width, height, columns, rows)
    assert len(regions) == columns * rows
    assert all(c == 1 for row in coverage(width, height, regions) for c in row)


def test_grid_last_row_and_column_take_the_remainder():
    regions = grid(10, 7, 4, 3)
    assert [r.width for r in regions[:4]] == [2, 2, 2, 4]
    assert [regions[i * 4].height for i in range(3)] == [2, 2, 3]
    assert regions[0] == Region(0, 0, 2, 2) and regions[-1] == Region(6, 4, 10, 7)


def test_grid_refuses_more_tiles_than_pixels():
    with pytest.raises(ValueError, match="does not fit"):
        grid(4, 4, 5, 1)


@pytest.mark.parametrize("width, height, size", [(48, 32, 20), (48, 32, 16), (48, 32, 100), (5, 3, 1)])
def test_regions_of_size_cover_every_pixel_once(width, height, size):
    regions = regions_of_size(width, height, size)
    assert all(c == 1 for row in coverage(width, height, regions) for c in row)
    assert all(r.width <= size and r.height <= size for r in regions)


def test_parse_grid():
    assert parse_grid("4x3") == (4, 3)
    assert parse_grid("2X2") == (2, 2)
    for bad in ("4", "0x2", "x3", "4x", "4*4", "-1x2"):
        with pytest.raises(ValueError):
            parse_grid(bad)


def test_split_is_frame_by_frame():
    regions = grid(8, 8, 2, 1)
    job = split(range(3, 5), regions)
    assert [(t.frame, t.tile) for t in job] == list(itertools.product([3, 4], [0, 1]))
    assert job[1].region.arg() == "4,0,8,8"
    assert len({t.key() for t in job}) == len(job)
