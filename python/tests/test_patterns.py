"""Frame ranges and output patterns."""

import pytest

from snell_farm.patterns import fill, format_frames, outputs, parse_frames


@pytest.mark.parametrize("text, frames", [
    ("0..239", range(0, 240)),
    ("5", range(5, 6)),
    ("3..3", range(3, 4)),
    (" 2 .. 4 ", range(2, 5)),
    ("007..010", range(7, 11)),
])
def test_parse_frames(text, frames):
    assert parse_frames(text) == frames


@pytest.mark.parametrize("text", ["", "a", "1..", "..4", "-1", "1..-2", "1-4", "1...4", "1.5", "2..1"])
def test_parse_frames_refuses(text):
    with pytest.raises(ValueError):
        parse_frames(text)


def test_format_frames():
    assert format_frames(range(0, 240)) == "0..239"
    assert format_frames(range(7, 8)) == "7"


def test_fill_pads_every_run_of_hashes_in_the_file_name():
    assert fill("out/frame_####.png", 7) == "out/frame_0007.png"
    assert fill("f_#.exr", 12) == "f_12.exr"
    assert fill("f_##.png", 123) == "f_123.png"
    assert fill("a##_b###.png", 5) == "a05_b005.png"
    assert fill("shot##/f_####.png", 3) == "shot##/f_0003.png"  # folders as they are, as snell does
    assert fill("still.png", 3) == "still.png"


def test_outputs():
    assert outputs("f_###.png", [0, 1, 2]) == {0: "f_000.png", 1: "f_001.png", 2: "f_002.png"}
    assert outputs("still.png", [5]) == {5: "still.png"}


def test_outputs_refuse_many_frames_to_one_file():
    with pytest.raises(ValueError, match="#"):
        outputs("still.png", [0, 1])
    with pytest.raises(ValueError, match="#"):
        outputs("##/still.png", [0, 1])
