"""The docstring Examples of the study and config modules run as written."""

from __future__ import annotations

import doctest

import pytest

import gyroshell.studies.parameter_study
import gyroshell.tape.config


@pytest.mark.parametrize("module", [gyroshell.studies.parameter_study, gyroshell.tape.config],
                         ids=lambda m: m.__name__)
def test_docstring_examples(module):
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0
