"""The pip command a missing optional package's refusal names really installs it: an extra
of pyproject.toml that lists the package, or the package itself."""

import re
from pathlib import Path

import pytest

from gyroshell.core.errors import ParameterError
from gyroshell.linalg import factorization as fz
from gyroshell.tape.config import _tomllib

ROOT = Path(__file__).resolve().parents[2]
EXTRAS = _tomllib().loads((ROOT / "pyproject.toml").read_text())["project"][
    "optional-dependencies"]


def _installs(command: str, package: str) -> bool:
    """Whether ``command`` (``pip install 'gyroshell[X]'`` or ``pip install P``) installs
    ``package``."""
    extra = re.fullmatch(r"pip install 'gyroshell\[(\w+)\]'", command)
    if extra:
        listed = [re.split(r"[<>=\[; ]", item)[0] for item in EXTRAS.get(extra[1], [])]
        return package in listed
    return command == f"pip install {package}"


@pytest.mark.parametrize("choice, package", [("metis", "pymetis"), ("pardiso", "pypardiso")])
def test_a_missing_package_names_a_command_that_installs_it(monkeypatch, choice, package):
    entry = fz._PATTERN_LU_PACKAGES[choice]
    monkeypatch.setitem(fz._PATTERN_LU_PACKAGES, choice, (entry[0], lambda: False, entry[2]))
    with pytest.raises(ParameterError, match=package) as caught:
        fz.check_pattern_lu(choice)
    command = re.search(r"\((pip install [^)]*)\)", str(caught.value))
    assert command is not None, str(caught.value)
    assert _installs(command[1], package), str(caught.value)


def test_the_hint_checker_tells_a_wrong_extra():
    """pypardiso is in no extra: the previous message's command does not install it."""
    assert not _installs("pip install 'gyroshell[fast]'", "pypardiso")
    assert _installs("pip install 'gyroshell[fast]'", "pymetis")
