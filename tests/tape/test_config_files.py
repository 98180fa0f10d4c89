"""--config given files that are not UTF-8 TOML text: one line naming the file and what is
wrong (issue 18, causes 3 and 6), from Python and from the command line."""

from __future__ import annotations

import os

import pytest
from conftest import WIDTH

from gyroshell import ParameterError
from gyroshell.core.errors import InputFileError, MissingFileError
from gyroshell.tape.config import load_config

TEXT = "[tape]\ntension = 75\n"
COARSE = ["--spacing", WIDTH / 8, "--length-ratio", 2]

#: (case, how to make the file, what the message must say)
BROKEN = [
    ("UTF-16 with BOM", lambda p: p.write_bytes(TEXT.encode("utf-16")),
     "not UTF-8 text (UTF-16, by its byte order mark): TOML files are UTF-8"),
    ("UTF-16 big-endian", lambda p: p.write_bytes(TEXT.encode("utf-16-be")),
     "a NUL byte at offset 0"),
    ("UTF-32", lambda p: p.write_bytes(TEXT.encode("utf-32")), "UTF-32"),
    ("binary", lambda p: p.write_bytes(bytes(range(1, 256)) * 4),
     "not UTF-8 text (byte 0x80 at offset 127): TOML files are UTF-8"),
    ("Latin-1", lambda p: p.write_bytes("name = 'Müller'\n".encode("latin-1")),
     "not UTF-8 text (byte 0xfc at offset 9)"),
    ("NUL bytes", lambda p: p.write_bytes(b"tension = 75\n\x00\x00"),
     "a NUL byte at offset 13"),
    ("folder", lambda p: p.mkdir(), "is a directory, not a config file"),
]


@pytest.mark.parametrize("case, make, match", BROKEN, ids=[c[0] for c in BROKEN])
def test_python_refuses_naming_the_file(tmp_path, case, make, match):
    path = tmp_path / "tape.toml"
    make(path)
    with pytest.raises(InputFileError) as info:
        load_config(path)
    assert match in str(info.value) and str(path) in str(info.value)
    assert isinstance(info.value, ParameterError)


@pytest.mark.parametrize("case, make, match", BROKEN, ids=[c[0] for c in BROKEN])
def test_cli_refuses_in_one_line_with_exit_2(cli, tmp_path, case, make, match):
    path = tmp_path / "tape.toml"
    make(path)
    saved = tmp_path / "static.nc"
    run = cli(["static", *COARSE, "--config", path, "--velocity", 10, "--save", saved])
    assert run.code == 2
    assert len(run.error_lines) == 1 and "Traceback" not in run.err
    assert run.error_lines[0].startswith("gyroshell: error: ")
    assert match in run.error_lines[0] and str(path) in run.error_lines[0]
    assert sorted(os.listdir(tmp_path)) == ["tape.toml"]


def test_a_missing_file_is_still_a_file_not_found_error(tmp_path):
    with pytest.raises(MissingFileError, match="no such config file") as info:
        load_config(tmp_path / "none.toml")
    assert isinstance(info.value, FileNotFoundError)
    assert isinstance(info.value, ParameterError)


def test_a_utf8_byte_order_mark_is_accepted(tmp_path):
    # Decided: a BOM-prefixed file is UTF-8 text (Windows editors write one); tomllib alone
    # would call its first line an invalid statement, so the mark is skipped.
    path = tmp_path / "tape.toml"
    path.write_bytes(b"\xef\xbb\xbf" + TEXT.encode())
    assert load_config(path).params.tension == 75.0


def test_cli_accepts_a_utf8_byte_order_mark(cli, tmp_path):
    path = tmp_path / "tape.toml"
    path.write_bytes(b"\xef\xbb\xbf" + TEXT.encode())
    run = cli(["static", *COARSE, "--config", path, "--velocity", 10, "--json"])
    assert run.code == 0, run.err


def test_unreadable_file_is_refused_naming_it(tmp_path):
    if os.geteuid() == 0:
        pytest.skip("the superuser reads every file")
    path = tmp_path / "tape.toml"
    path.write_text(TEXT)
    path.chmod(0)
    with pytest.raises(InputFileError, match="cannot read the config file"):
        load_config(path)
