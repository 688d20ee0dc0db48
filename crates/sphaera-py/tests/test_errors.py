"""Every error path raises the right exception with the library's message."""

import numpy as np
import pytest

import sphaera


def open_square():
    return sphaera.Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]])


def test_simplify_arguments(ball):
    with pytest.raises(ValueError, match=r"\(0, 1\]"):
        sphaera.simplify(ball, ratio=0)
    with pytest.raises(ValueError, match=r"\(0, 1\]"):
        sphaera.simplify(ball, ratio=1.5)
    with pytest.raises(ValueError, match="not a length"):
        sphaera.simplify(ball, max_error="a lot")
    with pytest.raises(ValueError, match="not negative"):
        sphaera.simplify(ball, max_error=-1.0)
    bounded = sphaera.simplify(ball, max_error="2%")
    assert bounded.error_bound <= 0.02 * ball.diagonal
    assert bounded.mesh.triangle_count < ball.triangle_count


def test_distance_arguments(ball):
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        sphaera.distance(ball, np.zeros((4, 2)))
    with pytest.raises(ValueError, match="row 1 is not finite"):
        sphaera.distance(ball, [[0, 0, 0], [np.nan, 0, 0]])
    with pytest.raises(ValueError, match="not a length"):
        sphaera.distance(ball, [[0, 0, 0]], tolerance="close")
    assert len(sphaera.distance(ball, np.zeros((0, 3)))) == 0
    empty = sphaera.Mesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=int))
    with pytest.raises(ValueError):
        sphaera.distance(empty, [[0, 0, 0]])


def test_hausdorff_arguments(ball):
    with pytest.raises(ValueError, match="not a length"):
        sphaera.hausdorff(ball, ball, tolerance="tight")
    same = sphaera.hausdorff(ball, ball)
    assert same.lower == 0 and same.upper <= 1e-5 * ball.diagonal
    one_sided = sphaera.hausdorff(ball, open_square(), symmetric=False)
    assert one_sided.b_to_a is None and one_sided.dominating == "a_to_b"
    capped = sphaera.hausdorff(ball, open_square(), tolerance=0, max_samples=10)
    assert not capped.converged and capped.lower <= capped.upper


def test_spheretree_arguments(ball):
    with pytest.raises(ValueError, match='unknown method "best".*expand'):
        sphaera.spheretree(ball, method="best")
    # A flat sheet has no inside: minimax (auto) covers it, the paper's methods refuse it.
    assert sphaera.spheretree(open_square(), depth=1, branch=2).surface == "shell"
    with pytest.raises(ValueError, match="needs a solid"):
        sphaera.spheretree(open_square(), method="expand")
    inward = sphaera.Mesh(ball.vertices, ball.faces[:, ::-1])
    with pytest.raises(ValueError, match="inward"):
        sphaera.spheretree(inward)
    with pytest.raises(ValueError):
        sphaera.spheretree(ball, branch=0)
    octree = sphaera.spheretree(ball, depth=2, method="octree", evaluate=False)
    assert octree.method == "octree" and octree.errors == [None, None, None]
