"""Fixtures shared by several test files."""
from __future__ import annotations

import contextlib
import gc
import io
import warnings
from dataclasses import dataclass
from pathlib import Path

import pytest


@dataclass(frozen=True)
class RegeneratedCorpus:
    """One run of ``python -m drywall_lab corpus generate --out DIR``: where it wrote, and what it said."""

    out_dir: Path
    exit_code: int
    stdout: str
    resource_warnings: list[str]  #: files left open, reported by Python when they were collected


@pytest.fixture(scope="session")
def regenerated_corpus(tmp_path_factory) -> RegeneratedCorpus:
    """The whole corpus generated afresh with the project's seed, once for the session.

    ``tests/test_corpus.py`` compares its files byte for byte with ``data/corpus/``; ``tests/test_cli.py``
    checks the command's exit code and what it printed. One full generation serves both.
    """
    from drywall_lab.__main__ import main

    out = tmp_path_factory.mktemp("corpus")
    stdout = io.StringIO()
    with warnings.catch_warnings(record=True) as caught, contextlib.redirect_stdout(stdout):
        warnings.simplefilter("always", ResourceWarning)
        code = main(["corpus", "generate", "--out", str(out)])
        gc.collect()  # an unclosed file is reported when it is collected
    return RegeneratedCorpus(out_dir=out, exit_code=code, stdout=stdout.getvalue(),
                             resource_warnings=[str(w.message) for w in caught if issubclass(w.category, ResourceWarning)])


def load_benchmark(name: str):
    """A script of ``benchmarks/`` loaded as a module (its folder on the path, as when it runs)."""
    import importlib.util
    import sys

    folder = Path(__file__).resolve().parent.parent / "benchmarks"
    if str(folder) not in sys.path:
        sys.path.insert(0, str(folder))
    spec = importlib.util.spec_from_file_location(f"benchmark_{name}", folder / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="session")
def benchmark_script():
    """``load_benchmark``, for the tests of the benchmark scripts."""
    return load_benchmark
