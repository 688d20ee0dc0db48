"""Sphere-trees to a tolerance, of exactly N spheres, on shells: every claim checked here
without the library (brute-force distances to the triangles, point samples on the spheres
and on the surface)."""

import pickle

import numpy as np
import pytest

import sphaera
from conftest import uv_sphere


def fibonacci_directions(k):
    """`k` unit vectors spread evenly over the sphere."""
    i = np.arange(k) + 0.5
    z = 1 - 2 * i / k
    phi = np.pi * (1 + 5**0.5) * i
    r = np.sqrt(1 - z * z)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def on_spheres(spheres, k=200):
    """Points on the boundary of each sphere (where a sphere reaches farthest from a convex
    solid or a flat sheet): `(len(spheres) * k, 3)`, sphere by sphere."""
    directions = fibonacci_directions(k)
    return (spheres[:, None, :3] + spheres[:, None, 3:] * directions[None, :, :]).reshape(-1, 3)


def surface_samples(vertices, faces, n, seed=5):
    """The vertices and `n` uniformly random points on the triangles."""
    rng = np.random.default_rng(seed)
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    area = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    t = rng.choice(len(faces), size=n, p=area / area.sum())
    u, v = rng.random(n), rng.random(n)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    points = a[t] + u[:, None] * (b[t] - a[t]) + v[:, None] * (c[t] - a[t])
    return np.concatenate([vertices, points])


def brute_distance(vertices, faces, points):
    """Each point's distance to the nearest triangle, triangle by triangle over all points
    (corners and edges as segments, the interior where the projection falls inside)."""
    best = np.full(len(points), np.inf)
    for f in faces:
        a, b, c = vertices[f]
        for u, v in [(a, b), (b, c), (c, a)]:
            d = v - u
            t = np.clip((points - u) @ d / (d @ d), 0, 1)
            best = np.minimum(best, np.linalg.norm(u + t[:, None] * d - points, axis=1))
        n = np.cross(b - a, c - a)
        n /= np.linalg.norm(n)
        h = (points - a) @ n
        q = points - h[:, None] * n
        inside = np.ones(len(points), dtype=bool)
        for u, v in [(a, b), (b, c), (c, a)]:
            inside &= np.cross(v - u, q - u) @ n >= 0
        best = np.where(inside, np.minimum(best, np.abs(h)), best)
    return best


def convex_protrusion(vertices, faces, points):
    """How far each point lies outside a convex closed mesh around the origin: 0 inside
    (behind every face's plane), else its distance to the triangles."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    offset = np.einsum("ij,ij->i", n, a)
    n[offset < 0] *= -1
    offset = np.abs(offset)
    outside = (points @ n.T - offset[None, :]).max(axis=1) > 0
    out = np.zeros(len(points))
    out[outside] = brute_distance(vertices, faces, points[outside])
    return out


def square_sheet(cells=4):
    """The unit square in the plane z = 0 as a flat open grid of triangles (no inside)."""
    x, y = np.meshgrid(np.linspace(0, 1, cells + 1), np.linspace(0, 1, cells + 1))
    vertices = np.stack([x.ravel(), y.ravel(), np.zeros(x.size)], axis=1)
    faces = []
    for i in range(cells):
        for j in range(cells):
            k = i * (cells + 1) + j
            faces += [(k, k + 1, k + cells + 2), (k, k + cells + 2, k + cells + 1)]
    return vertices, np.asarray(faces)


def sheet_distance(points):
    """Each point's distance to the unit square in z = 0 (exact)."""
    dx = np.maximum(0, np.maximum(-points[:, 0], points[:, 0] - 1))
    dy = np.maximum(0, np.maximum(-points[:, 1], points[:, 1] - 1))
    return np.sqrt(dx * dx + dy * dy + points[:, 2] ** 2)


def covered(points, spheres, slack):
    """Whether every point lies in some sphere (to `slack`)."""
    gaps = np.linalg.norm(points[:, None, :] - spheres[None, :, :3], axis=2) - spheres[None, :, 3]
    return gaps.min(axis=1) <= slack


def per_sphere_max(values, count):
    """The largest of each sphere's `k` samples (values laid out sphere by sphere)."""
    return values.reshape(count, -1).max(axis=1)


@pytest.fixture(scope="module")
def ellipsoid_arrays():
    """A convex ellipsoid (semi-axes 2, 1, ½) around the origin: one sphere is far from it,
    so tolerances and budgets have work to do."""
    vertices, faces = uv_sphere()
    return vertices * [2.0, 1.0, 0.5], faces


def test_exactly_n_spheres_for_several_n(ellipsoid_arrays):
    vertices, faces = ellipsoid_arrays
    mesh = sphaera.Mesh(vertices, faces)
    samples = surface_samples(vertices, faces, 3000)
    for n in [1, 2, 3, 5, 8, 13, 24]:
        tree = sphaera.spheretree(mesh, spheres=n)
        assert tree.goal == "spheres" and tree.surface == "solid" and tree.depth == 2
        assert tree.levels[1].shape == (n, 4) and tree.leaves.shape == (n, 4)
        np.testing.assert_array_equal(tree.cut(1), tree.levels[1])
        np.testing.assert_array_equal(tree.leaves, tree.levels[1])
        assert tree.tolerance is None and tree.met is None
        spheres = tree.leaves
        # The n spheres cover the surface, and none reaches out of the ball farther than
        # its certified error, nor farther than the level's certified worst.
        assert np.all(covered(samples, spheres, 1e-9 * mesh.diagonal))
        measured = per_sphere_max(convex_protrusion(vertices, faces, on_spheres(spheres, 100)), n)
        assert np.all(measured <= tree.leaf_errors + 1e-9)
        # Samples find a lower bound of the true worst, which lies in [lower, upper].
        lower, upper = tree.errors[1]
        assert measured.max() <= upper + 1e-9 and lower <= upper <= tree.leaf_errors.max() + 1e-12


def test_a_tolerance_is_met_as_measured_without_the_library(ellipsoid_arrays):
    vertices, faces = ellipsoid_arrays
    mesh = sphaera.Mesh(vertices, faces)
    tree = sphaera.spheretree(mesh, tolerance="4%", branch=4)
    assert tree.goal == "tolerance" and tree.met is True
    assert tree.tolerance == pytest.approx(0.04 * mesh.diagonal, rel=1e-12)
    leaves, errors = tree.leaves, tree.leaf_errors
    assert len(leaves) == len(errors) > 1 and np.all(errors <= tree.tolerance)
    measured = per_sphere_max(convex_protrusion(vertices, faces, on_spheres(leaves)), len(leaves))
    assert np.all(measured <= errors + 1e-9), (measured - errors).max()
    # Every cut covers the surface; each level's certified worst error is its cut's.
    samples = surface_samples(vertices, faces, 3000)
    slack = 1e-9 * mesh.diagonal
    for level in range(tree.depth):
        cut = tree.cut(level)
        assert np.all(covered(samples, cut, slack)), level
        assert len(cut) >= len(tree.levels[level])
        assert len(tree.cut_errors(level)) == len(cut)
        lower, upper = tree.errors[level]
        assert 0 <= lower <= upper <= tree.cut_errors(level).max() + 1e-12
    np.testing.assert_array_equal(tree.cut(tree.depth - 1), leaves)
    np.testing.assert_array_equal(tree.cut(tree.depth + 5), leaves)
    np.testing.assert_array_equal(tree.cut(0), tree.levels[0])
    assert tree.errors[-1][1] <= tree.tolerance
    # An absolute tolerance is taken as it is.
    absolute = sphaera.spheretree(mesh, tolerance=0.1, evaluate=False)
    assert absolute.tolerance == 0.1 and absolute.met and absolute.leaf_errors.max() <= 0.1


def test_a_flat_sheet_is_a_shell_and_gets_spheres():
    vertices, faces = square_sheet()
    sheet = sphaera.Mesh(vertices, faces)
    samples = surface_samples(vertices, faces, 2000)
    for tree in [
        sphaera.spheretree(sheet, tolerance="5%"),
        sphaera.spheretree(sheet, spheres=6),
        sphaera.spheretree(sheet, depth=2, branch=4),
    ]:
        assert tree.surface == "shell"
        leaves = tree.leaves
        assert len(leaves) > 0 and np.all(leaves[:, 3] > 0)
        assert np.all(covered(samples, leaves, 1e-9))
        # On a shell a sphere's error is how far it reaches away from the sheet.
        measured = per_sphere_max(sheet_distance(on_spheres(leaves)), len(leaves))
        assert np.all(measured <= tree.leaf_errors + 1e-9)
        lower, upper = tree.errors[-1]
        assert lower <= upper and measured.max() <= upper + 1e-9
        if tree.goal == "tolerance":
            assert tree.met and tree.leaf_errors.max() <= 0.05 * sheet.diagonal
        if tree.goal == "spheres":
            assert len(leaves) == 6
    with pytest.raises(ValueError, match="needs a solid"):
        sphaera.spheretree(sheet, method="merge")


def test_effort_levels_all_build(ball):
    for effort in ["quick", "default", "thorough"]:
        tree = sphaera.spheretree(ball, spheres=6, effort=effort, evaluate=False)
        assert tree.effort == effort and len(tree.leaves) == 6


@pytest.mark.parametrize(
    "arguments, message",
    [
        ({"tolerance": float("nan")}, "tolerance.*finite"),
        ({"tolerance": -0.01}, "tolerance.*not negative"),
        ({"tolerance": "-2%"}, "tolerance.*not a length"),
        ({"tolerance": "nan%"}, "tolerance.*not a length"),
        ({"tolerance": float("inf")}, "tolerance.*finite"),
        ({"tolerance": 0}, "tolerance must be positive"),
        ({"tolerance": "0%"}, "tolerance must be positive"),
        ({"tolerance": "close"}, "tolerance.*not a length"),
        ({"spheres": 0}, "between 1 and 10000"),
        ({"spheres": 10_001}, "between 1 and 10000"),
        ({"spheres": -3}, "spheres must not be negative"),
        ({"spheres": 2.5}, "spheres must be a whole number"),
        ({"depth": -1}, "depth must not be negative"),
        ({"effort": "fast"}, 'unknown effort "fast".*quick, default, thorough'),
        ({"spheres": 8, "tolerance": "1%"}, "not both"),
        ({"spheres": 8, "depth": 2}, "depth and branch do not apply"),
        ({"spheres": 8, "branch": 4}, "depth and branch do not apply"),
        ({"tolerance": "1%", "depth": 2}, "depth does not apply"),
        ({"tolerance": "1%", "method": "merge"}, "only the minimax method"),
        ({"spheres": 8, "method": "octree"}, "only the minimax method"),
        ({"effort": "quick", "method": "hubbard"}, "effort applies to the minimax method"),
        ({"method": "best"}, 'unknown method "best"'),
        ({"max_nodes": 100}, "max_nodes bounds a tree built to a tolerance"),
        ({"max_nodes": 100, "spheres": 8}, "max_nodes bounds a tree built to a tolerance"),
        ({"tolerance": "1%", "max_nodes": 0}, "max_nodes must be between 1 and 2097152"),
        ({"tolerance": "1%", "max_nodes": 2**22}, "max_nodes must be between 1 and 2097152"),
        ({"tolerance": "1%", "max_nodes": -1}, "max_nodes must not be negative"),
    ],
)
def test_bad_parameters_raise_value_error(ball, arguments, message):
    with pytest.raises(ValueError, match=message):
        sphaera.spheretree(ball, **arguments)


def test_a_tolerance_that_cannot_be_met_raises_with_the_figures(ellipsoid_arrays):
    ellipsoid = sphaera.Mesh(*ellipsoid_arrays)
    # One child a node never gets tighter: the depth limit is reached.
    with pytest.raises(sphaera.ToleranceUnreachableError) as caught:
        sphaera.spheretree(ellipsoid, tolerance="1%", branch=1, effort="quick", evaluate=False)
    error = caught.value
    assert isinstance(error, ValueError)
    assert error.tolerance == pytest.approx(0.01 * ellipsoid.diagonal, rel=1e-12)
    assert error.worst > error.tolerance and error.spheres >= 1 and error.levels >= 1
    text = str(error)
    assert "cannot meet the tolerance" in text and str(error.spheres) in text
    assert str(error.levels) in text and "larger tolerance" in text


def test_cut_arguments(ball):
    tree = sphaera.spheretree(ball, spheres=4, evaluate=False)
    with pytest.raises(ValueError, match="level must not be negative"):
        tree.cut(-1)
    with pytest.raises(ValueError, match="level must not be negative"):
        tree.cut_errors(-2)
    assert tree.errors == [None, None]


@pytest.mark.parametrize(
    "arguments",
    [{"spheres": 8}, {"tolerance": "4%", "branch": 4}, {"depth": 2, "branch": 4}],
)
def test_scaling_by_two_scales_the_answer_exactly(ellipsoid_arrays, arguments):
    vertices, faces = ellipsoid_arrays
    one = sphaera.spheretree(sphaera.Mesh(vertices, faces), **arguments)
    two = sphaera.spheretree(sphaera.Mesh(2 * vertices, faces), **arguments)
    assert len(one.levels) == len(two.levels)
    for a, b in zip(one.levels, two.levels, strict=True):
        np.testing.assert_array_equal(2 * a, b)
    for a, b in zip(one.parents, two.parents, strict=True):
        np.testing.assert_array_equal(a, b)
    for a, b in zip(one.node_errors, two.node_errors, strict=True):
        np.testing.assert_array_equal(2 * a, b)
    for a, b in zip(one.errors, two.errors, strict=True):
        assert (2 * a[0], 2 * a[1]) == b
    np.testing.assert_array_equal(2 * one.leaf_errors, two.leaf_errors)
    if one.tolerance is not None:
        assert two.tolerance == 2 * one.tolerance and one.met and two.met


def test_tolerance_trees_pickle_and_old_pickles_still_load(ellipsoid_arrays):
    tree = sphaera.spheretree(sphaera.Mesh(*ellipsoid_arrays), tolerance="5%")
    assert tree.depth > 2
    copy = pickle.loads(pickle.dumps(tree))
    assert repr(copy) == repr(tree) and "tolerance=" in repr(tree) and "met" in repr(tree)
    np.testing.assert_array_equal(copy.leaves, tree.leaves)
    np.testing.assert_array_equal(copy.leaf_errors, tree.leaf_errors)
    assert (copy.tolerance, copy.met, copy.surface, copy.goal) == (
        tree.tolerance,
        True,
        "solid",
        "tolerance",
    )
    # A tree made from the five parts of earlier versions: spheres and cuts, no errors.
    old = sphaera.SphereTree(tree.levels, tree.parents, tree.errors, "auto", tree.branch)
    np.testing.assert_array_equal(old.cut(1), tree.cut(1))
    assert old.node_errors is None
    with pytest.raises(ValueError, match="no node errors"):
        old.leaf_errors


def test_tolerance_and_budget_trees_match_the_cli(cli, data_dir):
    path = data_dir / "bunny_lowres.obj"
    bunny = sphaera.load(path)
    for arguments, flags in [
        ({"tolerance": "2%"}, ["--tolerance", "2%"]),
        ({"spheres": 12}, ["--spheres", "12"]),
    ]:
        tree = sphaera.spheretree(bunny, **arguments)
        report = cli("spheretree", path, *flags)
        assert report["surface"] == tree.surface and report["goal"] == tree.goal
        assert report["leaves"] == len(tree.leaves)
        assert report["worst_leaf_error"] == tree.leaf_errors.max()
        assert report["tolerance_met"] == tree.met
        assert report["tolerance"] == tree.tolerance
        for level, row in enumerate(report["levels"]):
            assert row["spheres"] == len(tree.cut(level))
            assert (row["worst_error_lower"], row["worst_error_upper"]) == tree.errors[level]
            assert row["construction_error"] == tree.cut_errors(level).max()


def test_a_node_budget_is_met_or_refused_never_exceeded(ellipsoid_arrays):
    ellipsoid = sphaera.Mesh(*ellipsoid_arrays)
    tree = sphaera.spheretree(
        ellipsoid, tolerance="3%", max_nodes=400, effort="quick", evaluate=False
    )
    assert tree.met
    assert sum(len(level) for level in tree.levels) <= 400
    with pytest.raises(sphaera.ToleranceUnreachableError) as caught:
        sphaera.spheretree(
            ellipsoid, tolerance="0.2%", max_nodes=20, effort="quick", evaluate=False
        )
    assert "20 nodes" in str(caught.value)
