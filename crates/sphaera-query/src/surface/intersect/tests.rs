//! The contact predicates against two exact references on small integer coordinates
//! (where coplanar, collinear and touching configurations are frequent): the intersection
//! of the two closed triangles computed by clipping with rational arithmetic, and, for
//! triangles sharing no vertex, the separating-axis test in integers.

use glam::DVec3;

use super::{improper_contact, orient, segment_meets_triangle};

/// An exact rational `num / den`, `den > 0`, in lowest terms.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Q {
    num: i128,
    den: i128,
}

fn gcd(a: i128, b: i128) -> i128 {
    let (mut a, mut b) = (a.abs(), b.abs());
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a.max(1)
}

impl Q {
    fn new(num: i128, den: i128) -> Self {
        let sign = if den < 0 { -1 } else { 1 };
        let g = gcd(num, den);
        Self {
            num: sign * num / g,
            den: sign * den / g,
        }
    }
    fn int(n: i64) -> Self {
        Self::new(i128::from(n), 1)
    }
    fn add(self, o: Self) -> Self {
        Self::new(self.num * o.den + o.num * self.den, self.den * o.den)
    }
    fn sub(self, o: Self) -> Self {
        Self::new(self.num * o.den - o.num * self.den, self.den * o.den)
    }
    fn mul(self, o: Self) -> Self {
        Self::new(self.num * o.num, self.den * o.den)
    }
    fn div(self, o: Self) -> Self {
        Self::new(self.num * o.den, self.den * o.num)
    }
    fn signum(self) -> i128 {
        self.num.signum()
    }
}

type I3 = [i64; 3];
type Q3 = [Q; 3];

fn sub(a: I3, b: I3) -> I3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: I3, b: I3) -> I3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: I3, b: I3) -> i64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn to_q(p: I3) -> Q3 {
    p.map(Q::int)
}
fn to_f(p: I3) -> DVec3 {
    // Small integers convert exactly.
    DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)
}
fn linear(n: I3, x: Q3) -> Q {
    (0..3).fold(Q::int(0), |s, k| s.add(Q::int(n[k]).mul(x[k])))
}

/// The closed half-space `n · x >= k`.
#[derive(Clone, Copy)]
struct HalfSpace {
    n: I3,
    k: i64,
}

/// Sutherland–Hodgman clipping of a convex (possibly flat) polygon by a closed half-space.
fn clip(polygon: &[Q3], h: HalfSpace) -> Vec<Q3> {
    let side = |x: Q3| linear(h.n, x).sub(Q::int(h.k));
    let mut out = Vec::new();
    for i in 0..polygon.len() {
        let (p, q) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        let (sp, sq) = (side(p), side(q));
        if sp.signum() >= 0 {
            out.push(p);
        }
        if sp.signum() * sq.signum() < 0 {
            let t = sp.div(sp.sub(sq));
            out.push([0, 1, 2].map(|k| p[k].add(q[k].sub(p[k]).mul(t))));
        }
    }
    out
}

/// The vertices of the intersection of two closed triangles (a convex polygon, segment,
/// point or nothing), exactly.
fn intersection(t1: [I3; 3], t2: [I3; 3]) -> Vec<Q3> {
    let [a, b, c] = t2;
    let n = cross(sub(b, a), sub(c, a));
    let mut spaces = vec![
        HalfSpace { n, k: dot(n, a) },
        HalfSpace {
            n: n.map(|x| -x),
            k: -dot(n, a),
        },
    ];
    for (p, q) in [(a, b), (b, c), (c, a)] {
        let m = cross(n, sub(q, p));
        spaces.push(HalfSpace { n: m, k: dot(m, p) });
    }
    spaces
        .into_iter()
        .fold(t1.map(to_q).to_vec(), |polygon, h| clip(&polygon, h))
}

/// Whether `x` lies on the closed segment `[u, v]`.
fn on_segment(x: Q3, u: I3, v: I3) -> bool {
    let d = sub(v, u);
    let rel = [0, 1, 2].map(|k| x[k].sub(Q::int(u[k])));
    let collinear = (0..3).all(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        rel[i]
            .mul(Q::int(d[j]))
            .sub(rel[j].mul(Q::int(d[i])))
            .signum()
            == 0
    });
    let along = linear(d, rel);
    collinear && along.signum() >= 0 && Q::int(dot(d, d)).sub(along).signum() >= 0
}

/// The reference: whether the triangles (with vertex indices) meet beyond what they share.
fn reference(t1: [I3; 3], v1: [u32; 3], t2: [I3; 3], v2: [u32; 3]) -> bool {
    let shared: Vec<I3> = (0..3)
        .filter(|&i| v2.contains(&v1[i]))
        .map(|i| t1[i])
        .collect();
    let meet = intersection(t1, t2);
    match shared.as_slice() {
        [] => !meet.is_empty(),
        [v] => meet.iter().any(|&x| x != to_q(*v)),
        [u, v] => meet.iter().any(|&x| !on_segment(x, *u, *v)),
        _ => true,
    }
}

/// Separating-axis test in integers: whether two closed triangles meet.
fn separating_axis_meet(t1: [I3; 3], t2: [I3; 3]) -> bool {
    let edges = |t: [I3; 3]| [sub(t[1], t[0]), sub(t[2], t[1]), sub(t[0], t[2])];
    let (e1, e2) = (edges(t1), edges(t2));
    let (n1, n2) = (cross(e1[0], e1[1]), cross(e2[0], e2[1]));
    let mut axes = vec![n1, n2];
    for a in e1 {
        for b in e2 {
            axes.push(cross(a, b));
        }
    }
    for n in [n1, n2] {
        for e in e1.iter().chain(&e2) {
            axes.push(cross(n, *e));
        }
    }
    let range = |t: [I3; 3], w: I3| {
        let d = t.map(|p| dot(p, w));
        (
            d.iter().copied().min().unwrap_or(0),
            d.iter().copied().max().unwrap_or(0),
        )
    };
    !axes.into_iter().filter(|w| *w != [0, 0, 0]).any(|w| {
        let ((lo1, hi1), (lo2, hi2)) = (range(t1, w), range(t2, w));
        hi1 < lo2 || hi2 < lo1
    })
}

/// The `SplitMix64` generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn coordinate(&mut self, size: u64) -> i64 {
        (self.next() % size) as i64
    }
    fn point(&mut self, size: u64) -> I3 {
        [0; 3].map(|_| self.coordinate(size))
    }
}

fn degenerate(t: [I3; 3]) -> bool {
    cross(sub(t[1], t[0]), sub(t[2], t[0])) == [0, 0, 0]
}

/// A pair of non-degenerate triangles sharing `shared` vertices (by index and position),
/// with their corners in a random rotation and, for a shared edge, either orientation.
fn random_pair(rng: &mut Rng, shared: usize, size: u64) -> ([I3; 3], [u32; 3], [I3; 3], [u32; 3]) {
    loop {
        let t1 = [rng.point(size), rng.point(size), rng.point(size)];
        let mut t2 = [rng.point(size), rng.point(size), rng.point(size)];
        let mut v2 = [3, 4, 5];
        // Triangle 2's first `shared` corners are triangle 1's last ones, reversed (as
        // in an oriented mesh), or in the same order.
        let reversed = rng.next().is_multiple_of(2);
        for k in 0..shared {
            let i = if reversed { 2 - k } else { 3 - shared + k };
            t2[k] = t1[i];
            v2[k] = i as u32;
        }
        let r = (rng.next() % 3) as usize;
        t2.rotate_left(r);
        v2.rotate_left(r);
        if !degenerate(t1) && !degenerate(t2) {
            return (t1, [0, 1, 2], t2, v2);
        }
    }
}

#[test]
fn orient_is_positive_behind_the_triangle() {
    let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
    assert!(orient(a, b, c, -DVec3::Z) > 0.0);
    assert!(orient(a, b, c, DVec3::Z) < 0.0);
    assert!(orient(a, b, c, DVec3::new(5.0, -3.0, 0.0)) == 0.0);
}

#[test]
fn the_clipping_reference_agrees_with_the_separating_axes() {
    let mut rng = Rng(11);
    for _ in 0..20_000 {
        let (t1, _, t2, _) = random_pair(&mut rng, 0, 4);
        assert_eq!(
            !intersection(t1, t2).is_empty(),
            separating_axis_meet(t1, t2),
            "{t1:?} {t2:?}"
        );
    }
}

#[test]
fn contacts_agree_with_the_exact_reference() {
    let mut rng = Rng(7);
    let mut positives = [0_usize; 4];
    for case in 0..120_000 {
        let shared = case % 4;
        let size = if case % 8 < 4 { 3 } else { 5 };
        let (t1, v1, t2, v2) = random_pair(&mut rng, shared, size);
        let expected = reference(t1, v1, t2, v2);
        let got = improper_contact(t1.map(to_f), v1, t2.map(to_f), v2);
        assert_eq!(
            got, expected,
            "shared {shared}: {t1:?} {v1:?} / {t2:?} {v2:?}"
        );
        // Symmetric in the two triangles.
        assert_eq!(
            improper_contact(t2.map(to_f), v2, t1.map(to_f), v1),
            expected
        );
        positives[shared] += usize::from(expected);
    }
    // Both answers are frequent in every case (degenerate contacts included).
    for (shared, &count) in positives.iter().enumerate().take(3) {
        assert!(count > 1_000 && count < 29_000, "shared {shared}: {count}");
    }
}

#[test]
fn segments_against_triangles_agree_with_the_reference() {
    let mut rng = Rng(3);
    for _ in 0..40_000 {
        let t = loop {
            let t = [rng.point(4), rng.point(4), rng.point(4)];
            if !degenerate(t) {
                break t;
            }
        };
        let (a, b) = (rng.point(4), rng.point(4));
        if a == b {
            continue;
        }
        // A segment as a flat triangle with a repeated corner.
        let expected = !intersection([a, b, b], t).is_empty();
        assert_eq!(
            segment_meets_triangle(to_f(a), to_f(b), t.map(to_f)),
            expected,
            "{a:?} {b:?} {t:?}"
        );
    }
}

#[test]
fn a_fold_across_a_shared_edge_is_a_contact_and_a_flat_pair_is_not() {
    let (u, v) = (DVec3::ZERO, DVec3::X);
    let up = DVec3::new(0.3, 1.0, 0.0);
    let down = DVec3::new(0.6, -1.0, 0.0);
    let folded = DVec3::new(0.6, 0.5, 0.0);
    assert!(!improper_contact(
        [u, v, up],
        [0, 1, 2],
        [v, u, down],
        [1, 0, 3]
    ));
    assert!(improper_contact(
        [u, v, up],
        [0, 1, 2],
        [v, u, folded],
        [1, 0, 3]
    ));
    // Out of the plane: only the edge in common.
    let lifted = DVec3::new(0.6, 0.5, 1e-60);
    assert!(!improper_contact(
        [u, v, up],
        [0, 1, 2],
        [v, u, lifted],
        [1, 0, 3]
    ));
}
