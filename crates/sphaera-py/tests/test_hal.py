"""HAL trees from Python: point inclusion over numpy arrays against references written
here (even-odd crossings in numpy, a ball's radius), intersection, bad input, pickling."""

import pickle

import numpy as np
import pytest

import sphaera
from conftest import uv_sphere


def even_odd(ring, points):
    """Inside (True) by the even-odd rule, points strictly off the edges."""
    x, y = points[:, 0][:, None], points[:, 1][:, None]
    a, b = ring, np.roll(ring, -1, axis=0)
    ax, ay, bx, by = a[:, 0], a[:, 1], b[:, 0], b[:, 1]
    straddles = (ay > y) != (by > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        cross_x = ax + (y - ay) * (bx - ax) / (by - ay)
    return (np.count_nonzero(straddles & (x < cross_x), axis=1) % 2) == 1


def star(n=40, seed=3):
    rng = np.random.default_rng(seed)
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False)
    radii = rng.uniform(0.3, 1.0, n)
    return np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])


def test_2d_inclusion_matches_even_odd_and_reports_the_boundary():
    ring = star()
    tree = sphaera.HalTree2(ring)
    assert tree.closed and len(tree) == len(ring) and tree.depth >= 1
    rng = np.random.default_rng(5)
    points = rng.uniform(-1.1, 1.1, (2000, 2))
    answers = tree.contains(points)
    assert answers.dtype == np.int8 and answers.shape == (2000,)
    assert set(np.unique(answers)) <= {-1, 1}
    np.testing.assert_array_equal(answers == 1, even_odd(ring, points))
    # Vertices and edge midpoints are on the boundary.
    on = np.vstack([ring, (ring + np.roll(ring, -1, axis=0)) / 2])
    assert (tree.contains(on[: len(ring)]) == 0).all()
    # A list of lists works too, and no point gives an empty answer.
    assert tree.contains([[0.0, 0.0]]).tolist() == [1]
    assert tree.contains(np.zeros((0, 2))).shape == (0,)


def test_2d_intersection_and_open_polylines():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    a = sphaera.HalTree2(square)
    assert a.intersects(sphaera.HalTree2(square + [0.5, 0.5]))
    assert not a.intersects(sphaera.HalTree2(square + [2.0, 0.0]))
    # Nested: one outline holds the other.
    assert a.intersects(sphaera.HalTree2(square * 0.2 + 0.4))
    line = sphaera.HalTree2([[-1.0, 0.5], [2.0, 0.5]], closed=False)
    assert not line.closed and line.intersects(a)
    with pytest.raises(ValueError, match="open polyline"):
        line.contains([[0.0, 0.0]])


def test_3d_inclusion_matches_a_ball_and_intersection():
    vertices, faces = uv_sphere(radius=1.0, rings=16, segments=32)
    ball = sphaera.Mesh(vertices, faces)
    tree = sphaera.HalTree3(ball)
    assert tree.depth >= 1 and tree.mesh.triangle_count == ball.triangle_count
    rng = np.random.default_rng(9)
    points = rng.uniform(-1.3, 1.3, (3000, 3))
    r = np.linalg.norm(points, axis=1)
    # The inscribed polyhedron lies between radius cos(π/16) and 1.
    clear = (r < 0.95) | (r > 1.0 + 1e-9)
    answers = tree.contains(points)
    assert answers.dtype == np.int8
    np.testing.assert_array_equal(answers[clear] == 1, r[clear] < 0.95)
    assert (tree.contains(vertices) == 0).all()
    far = sphaera.HalTree3(sphaera.Mesh(vertices + 5.0, faces))
    near = sphaera.HalTree3(sphaera.Mesh(vertices * 0.5 + 0.2, faces))
    assert not tree.intersects(far) and tree.intersects(near)


def test_bad_input_is_refused_by_name():
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        sphaera.HalTree2(np.zeros((4, 3)))
    with pytest.raises(ValueError, match="finite"):
        sphaera.HalTree2([[0.0, 0.0], [1.0, np.nan], [0.0, 1.0]])
    with pytest.raises(ValueError):
        sphaera.HalTree2([[0.0, 0.0], [1.0, 0.0]])
    tree = sphaera.HalTree2(star())
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        tree.contains(np.zeros((3, 3)))
    vertices, faces = uv_sphere()
    two = sphaera.Mesh(
        np.vstack([vertices, vertices + 5]), np.vstack([faces, faces + len(vertices)])
    )
    with pytest.raises(ValueError, match="component|piece|genus"):
        sphaera.HalTree3(two)


def test_trees_pickle_and_answer_the_same():
    ring = star()
    tree = sphaera.HalTree2(ring)
    copy = pickle.loads(pickle.dumps(tree))
    points = np.random.default_rng(1).uniform(-1, 1, (200, 2))
    np.testing.assert_array_equal(copy.contains(points), tree.contains(points))
    vertices, faces = uv_sphere()
    solid = sphaera.HalTree3(sphaera.Mesh(vertices, faces))
    again = pickle.loads(pickle.dumps(solid))
    queries = np.random.default_rng(2).uniform(-1.2, 1.2, (200, 3))
    np.testing.assert_array_equal(again.contains(queries), solid.contains(queries))
