"""Shared fixtures: meshes built here (no files), the shared data folder, the CLI."""

import importlib
import json
import os
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import sphaera

REPOSITORY = Path(__file__).resolve().parents[3]


def uv_sphere(radius=1.0, rings=12, segments=24, centre=(0.0, 0.0, 0.0)):
    """A closed genus-0 sphere of triangles, as (vertices, faces) arrays."""
    vertices = [(0.0, 0.0, radius)]
    for i in range(1, rings):
        theta = np.pi * i / rings
        for j in range(segments):
            phi = 2 * np.pi * j / segments
            vertices.append(
                (
                    radius * np.sin(theta) * np.cos(phi),
                    radius * np.sin(theta) * np.sin(phi),
                    radius * np.cos(theta),
                )
            )
    vertices.append((0.0, 0.0, -radius))
    south = len(vertices) - 1
    faces = []
    ring = lambda i, j: 1 + (i - 1) * segments + (j % segments)  # noqa: E731
    for j in range(segments):
        faces.append((0, ring(1, j), ring(1, j + 1)))
        faces.append((south, ring(rings - 1, j + 1), ring(rings - 1, j)))
    for i in range(1, rings - 1):
        for j in range(segments):
            a, b = ring(i, j), ring(i, j + 1)
            c, d = ring(i + 1, j), ring(i + 1, j + 1)
            faces.append((a, c, b))
            faces.append((b, c, d))
    return np.asarray(vertices) + np.asarray(centre), np.asarray(faces, dtype=np.int64)


@pytest.fixture
def ball():
    vertices, faces = uv_sphere()
    return sphaera.Mesh(vertices, faces)


def required(module):
    """`module` imported; a test needing it is skipped when it is missing, unless
    SPHAERA_REQUIRE_DATA=1 (CI, which installs it from requirements-test.txt) fails it."""
    if os.environ.get("SPHAERA_REQUIRE_DATA") == "1":
        return importlib.import_module(module)
    return pytest.importorskip(module)


@pytest.fixture
def data_dir():
    """`$SPHAERA_DATA`, or `../shared/data` beside the repository (as the Rust tests find
    it); skipped when absent, unless SPHAERA_REQUIRE_DATA=1 (CI), which fails instead."""
    path = Path(os.environ.get("SPHAERA_DATA") or REPOSITORY.parent / "shared" / "data")
    if not path.is_dir():
        if os.environ.get("SPHAERA_REQUIRE_DATA") == "1":
            pytest.fail(f"the shared meshes are required (SPHAERA_REQUIRE_DATA=1) but {path} is missing")
        pytest.skip(f"{path} is missing")
    return path


@pytest.fixture
def cli():
    """Runs the `sphaera` binary (SPHAERA_CLI, set by `cargo xtask test`) with --json."""
    binary = os.environ.get("SPHAERA_CLI")
    if not binary or not Path(binary).is_file():
        if os.environ.get("SPHAERA_REQUIRE_DATA") == "1":
            pytest.fail("SPHAERA_CLI must name the built `sphaera` binary")
        pytest.skip("SPHAERA_CLI is not set")

    def run(*args):
        out = subprocess.run([binary, *map(str, args), "--json", "-q"], capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        return json.loads(out.stdout)

    return run


def share_kept_by_python(call, points):
    """While `call(points)` runs, another Python thread counts; returns the share of its
    idle rate it kept (near 0 when the call holds the GIL). `points` doubles until a call
    lasts long enough to measure, whatever the machine's speed."""
    ticks = 0
    done = threading.Event()

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1

    counter = threading.Thread(target=count)
    counter.start()
    before, started = ticks, time.perf_counter()
    time.sleep(0.1)
    idle_rate = (ticks - before) / (time.perf_counter() - started)
    for _ in range(10):
        before, started = ticks, time.perf_counter()
        call(points)
        seconds = time.perf_counter() - started
        during = ticks - before
        if seconds >= 0.1:
            break
        points = np.concatenate([points, points])
    done.set()
    counter.join()
    assert idle_rate > 0
    return (during / seconds) / idle_rate
