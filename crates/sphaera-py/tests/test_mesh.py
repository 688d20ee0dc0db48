"""Meshes in and out: arrays of any dtype, files, topology, every bad input."""

import numpy as np
import pytest

import sphaera
from conftest import uv_sphere


def test_arrays_of_any_dtype_give_the_same_mesh():
    vertices, faces = uv_sphere()
    reference = sphaera.Mesh(vertices, faces)
    for v, f in [
        (vertices, faces.astype(np.int32)),
        (vertices, faces.astype(np.uint32)),
        (vertices.tolist(), faces.tolist()),
    ]:
        assert sphaera.Mesh(v, f) == reference
    single = vertices.astype(np.float32)
    assert sphaera.Mesh(single, faces) == sphaera.Mesh(single.astype(np.float64), faces)
    assert reference.vertices.dtype == np.float64 and reference.vertices.shape == vertices.shape
    assert reference.faces.dtype == np.uint32
    np.testing.assert_array_equal(reference.vertices, vertices)
    np.testing.assert_array_equal(reference.faces, faces)
    assert reference.vertex_count == len(vertices) and reference.triangle_count == len(faces)
    assert "Mesh(" in repr(reference) and str(len(faces)) in repr(reference)


def test_info_reports_the_topology(ball):
    info = ball.info()
    assert info["closed"] and info["manifold"] and info["oriented"]
    assert info["genus"] == 0 and info["components"] == 1 and info["euler_characteristic"] == 2
    (low, high) = ball.bounding_box()
    assert np.allclose(low, (-1, -1, -1), atol=0.05) and np.allclose(high, (1, 1, 1), atol=0.05)
    assert ball.diagonal == pytest.approx(np.linalg.norm(np.subtract(high, low)))


def test_files_round_trip(tmp_path, ball):
    for extension in ["obj", "ply"]:
        path = tmp_path / f"ball.{extension}"
        ball.save(path)
        loaded = sphaera.load(path)
        assert loaded.triangle_count == ball.triangle_count
        if extension == "ply":  # binary doubles: exact
            assert loaded == ball


def test_the_real_bunny(data_dir):
    bunny = sphaera.load(data_dir / "bunny_lowres.obj")
    assert bunny.triangle_count == 3674 and bunny.info()["genus"] == 0


@pytest.mark.parametrize(
    "vertices, faces, message",
    [
        (np.zeros((4, 2)), [[0, 1, 2]], "shape (n, 3)"),
        (np.zeros(12), [[0, 1, 2]], "shape (n, 3)"),
        ([[0, 0, 0], [1, 0, float("nan")], [0, 1, 0]], [[0, 1, 2]], "not finite"),
        ([[0, 0, 0], [1, 0, float("inf")], [0, 1, 0]], [[0, 1, 2]], "not finite"),
        (np.eye(3), [[0, 1, 3]], "outside 0..3"),
        (np.eye(3), [[0, 1, -1]], "outside 0..3"),
        (np.eye(3), [[0.0, 1.0, 2.0]], "integers"),
        (np.eye(3), [[0, 1]], "shape (m, 3)"),
        ([["a", "b", "c"]], [[0, 0, 0]], "numbers"),
    ],
)
def test_bad_arrays_raise_value_errors_that_say_what(vertices, faces, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        sphaera.Mesh(vertices, faces)


def test_writing_an_unknown_format_is_a_value_error(tmp_path, ball):
    with pytest.raises(ValueError, match="OFF"):
        ball.save(tmp_path / "ball.off")


def test_files_that_cannot_be_read_raise_os_errors(tmp_path):
    missing = tmp_path / "missing.obj"
    with pytest.raises(OSError, match="missing.obj"):
        sphaera.load(missing)
    with pytest.raises(OSError):
        sphaera.Mesh(np.eye(3), [[0, 1, 2]]).save(tmp_path / "no-such-folder" / "x.obj")


def test_malformed_files_raise_value_errors(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nf 1 2 9\n")
    with pytest.raises(ValueError, match="bad.obj|9"):
        sphaera.load(bad)
    unknown = tmp_path / "mesh.xyz"
    unknown.write_text("0 0 0\n")
    with pytest.raises(ValueError):
        sphaera.load(unknown)
