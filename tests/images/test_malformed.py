"""Malformed database files (docs/reliability.md): every one is refused with one line naming the file and
what is wrong, before the images are decoded; a byte-order mark is read as the UTF-8 it marks."""

from __future__ import annotations

import shutil
import struct
import zlib
from pathlib import Path

import numpy as np
import pytest
import yaml

from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.images import _load
from delvjax.images._disk import ENTRIES, METADATA, POSITIONS, read_image, read_index
from tests.cases.images_io import error_line


@pytest.fixture
def bob(small_db, tmp_path) -> Path:
    return Path(shutil.copytree(small_db, tmp_path / "bob"))


def test_a_byte_order_mark_is_read_as_utf8(bob):
    text = (bob / ENTRIES).read_text()
    (bob / ENTRIES).write_text("\ufeff" + text, encoding="utf-8")
    assert len(read_index(bob).files) == len(text.splitlines()) - 1


@pytest.mark.parametrize(
    "edit, says",
    [
        (lambda lines: lines[:2] + [lines[2] + ",extra"] + lines[3:], "row 3 has 11 fields, the header 10"),
        (lambda lines: lines[:3] + [lines[2]] + lines[3:], "row 4 repeats row 3"),
        (  # a spreadsheet's export with ';' between fields and decimal commas (issue 53 point 8)
            lambda lines: [ln.replace(",", ";").replace(".", ",") for ln in lines],
            "separates its fields with ';'",
        ),
        (
            lambda lines: lines[:3] + [lines[2].replace(lines[2].split(",")[0], "12345", 1)] + lines[3:],
            "lists image_",
        ),  # the same file at another position
    ],
    ids=["extra field", "duplicated row", "semicolons", "file twice"],
)
def test_a_malformed_index_row_is_named(bob, edit, says):
    lines = (bob / ENTRIES).read_text().splitlines()
    (bob / ENTRIES).write_text("\n".join(edit(lines)) + "\n")
    with pytest.raises(InputError, match=says):
        read_index(bob)


@pytest.mark.parametrize(
    "field, value",
    [
        ("elevation_deg", 30),
        ("elevation_deg", [-30, 30]),
        ("camera_height_cm", "tall"),
        ("obstacles", {"cylinders": [[45.0, 135.0]], "boxes": []}),
        ("obstacles", {"cylinders": [], "boxes": [[1, 2, 3]]}),
        ("arena_cm", [0, 0, 180]),
        ("spacing_cm", -20),
        ("panorama", [12.5, 72]),
    ],
)
def test_a_malformed_metadata_value_is_named(bob, field, value):
    text = (bob / METADATA).read_text()
    data = yaml.safe_load(text.split("---", 1)[1])
    data["metadata"]["delvjax"][field] = value
    (bob / METADATA).write_text("%YAML:1.0\n---\n" + yaml.safe_dump(data))
    with pytest.raises(InputError) as exc:
        read_index(bob)
    assert f"delvjax.{field.split('.')[0]}" in str(exc.value) and METADATA in str(exc.value)


def png_claiming(path: Path, width: int, height: int) -> None:
    """A real PNG whose header claims width x height (a decompression bomb's header)."""
    from PIL import Image

    Image.new("RGB", (4, 4)).save(path)
    data = bytearray(path.read_bytes())
    data[16:24] = struct.pack(">II", width, height)  # IHDR: width, height ...
    data[29:33] = struct.pack(">I", zlib.crc32(bytes(data[12:29])))  # ... and its CRC
    path.write_bytes(bytes(data))


def test_a_huge_image_header_is_refused_before_decoding(tmp_path):
    png_claiming(tmp_path / "bomb.png", 20000, 20000)  # Pillow's own limit refuses this one
    with pytest.raises(InputError, match="more than 16777216 pixels"):
        read_image(tmp_path / "bomb.png")
    png_claiming(tmp_path / "big.png", 8000, 8000)  # under Pillow's limit, over ours: not decoded
    with pytest.raises(InputError, match="8000 x 8000 pixels, more than"):
        read_image(tmp_path / "big.png")


def test_settings_that_do_not_fit_the_images_are_refused_before_they_are_read(plain9, tmp_path, capsys, monkeypatch):
    """Images 8 pixels wide: warping's n_psi = 72 cannot divide the ring, refused from the first image."""
    from PIL import Image

    narrow = Path(shutil.copytree(plain9, tmp_path / "narrow"))
    for p in narrow.glob("*.png"):
        Image.open(p).convert("RGB").resize((8, 12)).save(p)
    read = []
    monkeypatch.setattr(_load, "read_images", lambda *a, **k: read.append(1) or np.zeros(0))
    out = tmp_path / "r.csv"
    assert (narrow / POSITIONS).is_file()
    assert main(["vector-map", "--images", str(narrow), "--method", "warping", "--out", str(out)]) == 2
    assert error_line(capsys).startswith("delvjax: error: --n-psi:") and read == [] and not out.exists()


def test_render_into_a_symlinked_empty_folder_writes_into_its_target(tmp_path):
    (tmp_path / "real").mkdir()
    (tmp_path / "link").symlink_to(tmp_path / "real")
    assert (
        main(
            [
                "images",
                "render-db",
                "robot",
                "--cols",
                "72",
                "--rows",
                "12",
                "--spacing",
                "40",
                "--out",
                str(tmp_path / "link"),
            ]
        )
        == 0
    )
    assert (tmp_path / "link").is_symlink() and (tmp_path / "real" / ENTRIES).is_file()
    assert oct((tmp_path / "real").stat().st_mode & 0o777) != "0o700"
    meta = yaml.safe_load((tmp_path / "real" / METADATA).read_text().split("---", 1)[1])
    assert meta["metadata"]["delvjax"]["light_deg"] == [45.0, 50.0]  # the light is recorded


@pytest.mark.parametrize("mode", ["I;16", "I"])
def test_a_16_bit_grayscale_image_keeps_its_grey_levels(tmp_path, mode):
    """Pillow's convert("RGB") clips a 16-bit grayscale PNG to white: every pixel 255, every point invalid
    (issue 53). It must read as its top 8 bits, the same grey in the three channels."""
    from PIL import Image

    levels = np.linspace(0, 65535, 60 * 360).reshape(60, 360).astype(np.uint16)
    im = Image.fromarray(levels) if mode == "I;16" else Image.fromarray(levels.astype(np.int32), mode="I")
    path = tmp_path / ("g.png" if mode == "I;16" else "g.tiff")  # Pillow writes mode I as TIFF, not PNG
    im.save(path)
    rgb = read_image(path)
    assert rgb.shape == (60, 360, 3) and rgb.dtype == np.uint8
    np.testing.assert_array_equal(rgb[..., 0], levels >> 8)
    np.testing.assert_array_equal(rgb[..., 0], rgb[..., 2])


def test_a_floating_point_image_is_refused(tmp_path):
    from PIL import Image

    Image.fromarray(np.ones((4, 4), np.float32)).save(tmp_path / "f.tiff")
    with pytest.raises(InputError, match="floating-point"):
        read_image(tmp_path / "f.tiff")
