//! `Scene::collide` against brute-force triangle–triangle tests, budgets honoured, answers
//! improving monotonically with the budget, the same answer on any number of threads.

use std::collections::BTreeSet;
use std::time::Duration;

use proptest::prelude::*;
use sphaera_mesh::geometry::Similarity;
use sphaera_mesh::{DVec3, TriMesh};
use sphaera_scene::{Budget, Scene, SceneCollision};
use sphaera_spheretree::SphereTree;

mod common;

/// The mesh of an instance, posed in the scene.
fn posed(scene: &Scene, i: usize) -> TriMesh {
    let instance = &scene.instances()[i];
    sphaera_tests::awkward::mapped(instance.model.mesh(), |p| instance.pose.point(p), false)
}

/// A cluster of instances in a small box, so that many pairs are close.
fn cluster() -> impl Strategy<Value = Vec<(usize, Similarity)>> {
    prop::collection::vec(
        (
            0usize..4,
            prop::array::uniform3(-1.2..1.2f64),
            prop::array::uniform3(-1.0..1.0f64),
            0.0..6.3f64,
            0.6..1.4f64,
        ),
        2..6,
    )
    .prop_map(|v| {
        v.into_iter()
            .map(|(m, t, axis, angle, scale)| {
                (
                    m,
                    common::pose(DVec3::from_array(t), DVec3::from_array(axis), angle, scale),
                )
            })
            .collect()
    })
}

/// The ancestor of `node` at `level`.
fn ancestor(tree: &SphereTree, mut node: usize, level: usize) -> usize {
    while tree.nodes()[node].level as usize > level {
        node = tree.nodes()[node].parent.expect("a parent above level 0") as usize;
    }
    node
}

/// Every contact of `fine` lies under a contact of `coarse`, and every pair is at least as
/// deep.
fn refines(scene: &Scene, coarse: &SceneCollision, fine: &SceneCollision) -> Result<(), String> {
    for pair in &fine.pairs {
        let Some(before) = coarse.pairs.iter().find(|p| (p.a, p.b) == (pair.a, pair.b)) else {
            return Err(format!(
                "pair {:?} appears with a larger budget",
                (pair.a, pair.b)
            ));
        };
        if pair.level < before.level {
            return Err(format!("pair {:?} went up a level", (pair.a, pair.b)));
        }
        let ta = scene.instances()[pair.a].model.collision_tree();
        let tb = scene.instances()[pair.b].model.collision_tree();
        let (ta, tb) = (ta.tree(), tb.tree());
        let known: BTreeSet<(usize, usize)> = before.contacts.iter().map(|c| (c.a, c.b)).collect();
        for c in &pair.contacts {
            let up = (
                ancestor(ta, c.a, before.level),
                ancestor(tb, c.b, before.level),
            );
            if !known.contains(&up) {
                return Err(format!(
                    "contact {:?} has no coarser contact {up:?}",
                    (c.a, c.b)
                ));
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(24)))]

    /// Surfaces that cross are always reported; a reported pair is at most its contacts'
    /// error bound apart; every pair agrees with the single-pair traversal.
    #[test]
    fn contacts_agree_with_brute_force_triangle_tests(placements in cluster()) {
        let scene = common::scene(&placements);
        let found = scene.collide(&Budget::Unlimited).expect("collide");
        prop_assert!(found.completed);
        let broad = scene.broad_phase();
        prop_assert_eq!(found.broad_phase_pairs, broad.len());
        for a in 0..scene.len() {
            for b in a + 1..scene.len() {
                let distance = sphaera_tests::brute::solid_distance(&posed(&scene, a), &posed(&scene, b));
                let reported = found.pairs.iter().find(|p| (p.a, p.b) == (a, b));
                if distance == 0.0 {
                    prop_assert!(reported.is_some(), "instances {a} and {b} touch and were missed");
                }
                if let Some(pair) = reported {
                    let bound = pair.separation_bound().expect("contacts");
                    prop_assert!(
                        distance <= bound * (1.0 + 1e-9) + 1e-12,
                        "instances {a}, {b}: {distance} apart, contacts claim at most {bound}"
                    );
                    let (ia, ib) = (&scene.instances()[a], &scene.instances()[b]);
                    let (ta, tb) = (ia.model.collision_tree(), ib.model.collision_tree());
                    let single = sphaera_spheretree::collide(
                        ta.tree(), &ia.pose, tb.tree(), &ib.pose, &Budget::Unlimited,
                    ).expect("collide");
                    prop_assert_eq!(&single.contacts, &pair.contacts);
                    prop_assert!(broad.contains(&(a, b)));
                }
            }
        }
    }

    /// A cost budget is never exceeded beyond the always-done root tests, and a larger one
    /// gives a refinement of a smaller one's answer.
    #[test]
    fn budgets_are_honoured_and_answers_improve_monotonically(placements in cluster()) {
        let scene = common::scene(&placements);
        let roots = scene.collide(&Budget::cost(0.0)).expect("collide");
        prop_assert_eq!(roots.pairs.iter().map(|p| p.level).max().unwrap_or(0), 0);
        let mut previous = roots.clone();
        for limit in [10.0, 40.0, 100.0, 300.0, 1_000.0, 5_000.0, 1e9] {
            let found = scene.collide(&Budget::cost(limit)).expect("collide");
            let spent = found.stats.tests as f64 + 2.0 * found.stats.updates as f64;
            prop_assert!(
                spent <= limit.max(roots.stats.tests as f64 + 2.0 * roots.stats.updates as f64),
                "spent {spent} of {limit}"
            );
            if let Err(why) = refines(&scene, &previous, &found) {
                prop_assert!(false, "budget {}: {}", limit, why);
            }
            previous = found;
        }
        prop_assert_eq!(&previous, &scene.collide(&Budget::Unlimited).expect("collide"));
    }
}

#[test]
fn time_budgets_stop_at_the_roots_or_run_to_the_leaves() {
    let placements: Vec<_> = (0..10)
        .map(|k| {
            let t = DVec3::new(0.5 * k as f64, 0.1 * (k % 3) as f64, 0.0);
            (k, common::pose(t, DVec3::Y, 0.3 * k as f64, 1.0))
        })
        .collect();
    let scene = common::scene(&placements);
    let none = scene
        .collide(&Budget::Time(Duration::ZERO))
        .expect("collide");
    assert!(!none.pairs.is_empty());
    assert!(none.pairs.iter().all(|p| p.level == 0));
    let all = scene
        .collide(&Budget::Time(Duration::from_secs(600)))
        .expect("collide");
    assert!(all.completed);
    assert_eq!(
        all.pairs,
        scene.collide(&Budget::Unlimited).expect("collide").pairs
    );
    // A NaN cost budget is refused.
    assert!(scene.collide(&Budget::cost(f64::NAN)).is_err());
    // An empty scene has no contact.
    let empty = Scene::new().collide(&Budget::Unlimited).expect("collide");
    assert!(empty.pairs.is_empty() && empty.completed);
}

/// The same scene gives the same contacts on one thread and on two (and, through
/// `cargo xtask test`, without the `parallel` feature: the digest is recorded).
#[test]
fn the_same_answer_on_any_number_of_threads() {
    let placements: Vec<_> = (0..16)
        .map(|k| {
            let t = DVec3::new(0.45 * (k % 5) as f64, 0.5 * (k / 5) as f64, 0.1 * k as f64);
            (
                k,
                common::pose(t, DVec3::new(1.0, k as f64, 2.0), 0.7 * k as f64, 1.0),
            )
        })
        .collect();
    let scene = common::scene(&placements);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool")
            .install(|| scene.collide(&Budget::cost(3_000.0)).expect("collide"))
    };
    let one = run(1);
    assert_eq!(one, run(2));
    assert_eq!(one, run(3));
    let mut digest: u64 = 0xcbf2_9ce4_8422_2325;
    let mut mix = |x: u64| {
        digest ^= x;
        digest = digest.wrapping_mul(0x0100_0000_01b3);
    };
    for pair in &one.pairs {
        mix(pair.a as u64);
        mix(pair.b as u64);
        mix(pair.level as u64);
        for c in &pair.contacts {
            mix(c.a as u64);
            mix(c.b as u64);
            mix(c.depth.to_bits());
            mix(c.error_bound.to_bits());
        }
    }
    assert!(!one.pairs.is_empty() && !one.completed);
    assert_eq!(
        digest,
        0xefa8_d9ef_b1d7_8868,
        "digest {digest:#018x}, {} pairs",
        one.pairs.len()
    );
}
