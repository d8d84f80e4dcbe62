//! The inertial reference dynamics (issue 11): the thesis' three-tile experiments fold, the
//! overdamped model is its limit of negligible mass, magnets bounce at their path ends, and
//! inertia alone does not rescue the old curved final point.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::f64::consts::FRAC_PI_2;

use foldchain::model::{Dynamics, ModelOptions};
use foldchain::physics::ForceLaw;
use foldchain::reference::{run_reference, Recording, ReferenceOptions, ReferenceRun};
use foldchain::timeline::RunSource;
use foldchain::timeline::{EventKind, Outcome, TileDesigns};
use foldchain::{Chain, Design, FoldWord};

fn run(word: &str, design: Design, model: ModelOptions) -> ReferenceRun {
    let chain = FoldWord::parse(word).unwrap().to_chain();
    run_reference(
        &chain,
        &TileDesigns::global(design),
        &ReferenceOptions::default().with_model(model),
    )
    .unwrap()
}

fn inertial() -> ModelOptions {
    ModelOptions::default().with_dynamics(Dynamics::Inertial)
}

#[test]
fn three_tile_experiments_fold_with_both_laws() {
    let d = Design::thesis();
    for law in [ForceLaw::PointDipole, ForceLaw::cylinder(&d)] {
        for (word, folds) in [
            ("SS", vec![]),
            ("SL", vec![1]),
            ("LS", vec![0]),
            ("LL", vec![0, 1]),
        ] {
            let r = run(word, d, inertial().with_force_law(law));
            assert_eq!(
                r.outcome,
                Outcome::Completed,
                "{word} {law:?}: {:?}",
                r.stopped
            );
            assert_eq!(r.folded_joints(), folds, "{word}");
            // a fraction of a second: the magnets' inertial time is milliseconds
            assert!(
                r.duration() > 0.01 && r.duration() < 2.0,
                "{word}: {}",
                r.duration()
            );
        }
    }
}

#[test]
fn overdamped_is_the_limit_of_negligible_mass() {
    // the same drag, a magnet of 0.0265 g: m / gamma = 5e-6 s against moves of ~0.1 s
    let d = Design::thesis();
    let od = ModelOptions::default();
    let light = Design {
        magnet_mass: 0.0265,
        magnet_drag: Some(5.0), /* the overdamped default */
        ..d
    };
    let word = "SS";
    let a = run(word, d, od);
    let b = run(word, light, od.with_dynamics(Dynamics::Inertial));
    assert_eq!(a.outcome, b.outcome);
    let rel = (a.duration() - b.duration()).abs() / a.duration();
    assert!(rel < 1e-3, "{word}: {} {}", a.duration(), b.duration());
    let arrivals = |r: &ReferenceRun| {
        r.events
            .iter()
            .filter(|e| e.kind == EventKind::MagnetArrives)
            .count()
    };
    assert_eq!(arrivals(&a), arrivals(&b), "{word}");
}

#[test]
fn magnets_bounce_at_their_path_ends() {
    // with restitution the magnets rebound before they stay: arrivals come later than
    // without, and the outcome is the same
    let d = Design::thesis();
    let dead = Design {
        restitution: 0.0,
        ..d
    };
    let bouncy = Design {
        restitution: 0.6,
        ..d
    };
    let a = run("SS", dead, inertial());
    let b = run("SS", bouncy, inertial());
    assert_eq!(a.outcome, Outcome::Completed);
    assert_eq!(b.outcome, Outcome::Completed);
    assert!(
        b.duration() > a.duration(),
        "{} {}",
        a.duration(),
        b.duration()
    );
    // a heavier magnet (the thesis' 0.625 g) is slower
    let heavy = run(
        "SS",
        Design {
            magnet_mass: 0.625,
            ..d
        },
        inertial(),
    );
    assert!(heavy.duration() > run("SS", d, inertial()).duration());
}

#[test]
fn inertia_does_not_rescue_the_old_final_point() {
    // c = 2.8 mm from the diagonal face (a 1.3 mm wall): the last fold stalls with inertia
    // too, magnet 3 at rest mid-path
    let old = Design {
        c: Some(2.8),
        ..Design::thesis()
    };
    for word in ["SL", "LL"] {
        let r = run(word, old, inertial());
        assert!(
            matches!(r.outcome, Outcome::Stalled { joint: 1, .. }),
            "{word}: {:?}",
            r.outcome
        );
    }
    // and bad inertial parameters are refused by name
    let bad = Design {
        restitution: 1.5,
        ..Design::thesis()
    };
    let e = run_reference(
        &Chain::parse("SS").unwrap(),
        &TileDesigns::global(bad),
        &ReferenceOptions::default().with_model(inertial()),
    )
    .unwrap_err();
    assert!(e.to_string().contains("restitution"), "{e}");
}

#[test]
fn the_old_stall_is_a_balance_that_misses_by_a_fraction_of_a_percent() {
    // README, "The end-of-chain stall": with c = 2.8 mm, SL (overdamped) stops with magnet 3
    // mid-path; magnet 4, at rest, is pulled on by magnet 3 and held back by its partner 5,
    // and the two nearly cancel (net about -0.07 mN against a 9.4 mN pull)
    let old = Design {
        c: Some(2.8),
        ..Design::thesis()
    };
    let r = run("SL", old, ModelOptions::default());
    assert!(matches!(r.outcome, Outcome::Stalled { joint: 1, .. }));
    let m = &r.model;
    let y = &r.final_state;
    let p: Vec<kurbo::Point> = m.positions(y).into_iter().map(kurbo::Point::from).collect();
    let poses = m.poses(y);
    let t = m.geometry.path(4).tangent_at(0.0);
    let t = kurbo::Vec2::from(poses[2].transform_vector(t));
    let moment = old.moment();
    let law = ForceLaw::PointDipole;
    let drive = |from: usize| {
        let attract = (from % 2) != 0;
        law.force(p[from], p[4], moment, moment, attract).dot(t) * 1e3
    };
    let (d3, d5, d2, d1) = (drive(3), drive(5), drive(2), drive(1));
    assert!((d3 - 9.374).abs() < 0.01, "{d3}");
    assert!((d5 + 9.327).abs() < 0.01, "{d5}");
    assert!((d2 + 0.267).abs() < 0.01, "{d2}");
    assert!((d1 - 0.148).abs() < 0.01, "{d1}");
    let net = d3 + d5 + d2 + d1;
    assert!(net < 0.0 && net > -0.1, "{net}");
    assert!((p[3].distance(p[4]) - 14.29).abs() < 0.01);
}

#[test]
fn the_chain_index_cutoff_misses_touching_tiles_far_apart_in_index() {
    // the known limit of the cutoff (pairs at most 3 apart in chain index): in the LLL ring
    // the first and last tiles touch, and the pairs left out change a magnet's drive along its
    // path by 31% of the bonded rest force at the end (measured; under 2% at rest). The
    // distance cutoff (90 mm, three tile widths) keeps them: what it leaves out is small
    let r = run("LLL", Design::thesis(), inertial());
    assert_eq!(r.outcome, Outcome::Completed);
    let e = r.model.cutoff_error(&r.final_state);
    assert!(e > 0.2 && e < 0.5, "{e}");
    let e0 = r.model.cutoff_error(&vec![0.0; r.model.len()]);
    assert!(e0 < 0.02, "{e0}");
    let d = run(
        "LLL",
        Design::thesis(),
        inertial().with_distance_cutoff(Some(90.0)),
    );
    assert_eq!(d.outcome, Outcome::Completed);
    assert_eq!(d.folded_joints(), r.folded_joints());
    let ed = d.model.cutoff_error(&d.final_state);
    assert!(ed < 1e-3, "{ed}");
    // a straight chain: the same events, times within a fraction of a percent
    let (a, b) = (
        run("S*9", Design::thesis(), inertial()),
        run(
            "S*9",
            Design::thesis(),
            inertial().with_distance_cutoff(Some(90.0)),
        ),
    );
    assert_eq!(a.events.len(), b.events.len());
    let rel = (a.duration() - b.duration()).abs() / a.duration();
    assert!(rel < 0.01, "{rel}");
    let bad = run_reference(
        &Chain::parse("SS").unwrap(),
        &TileDesigns::default(),
        &ReferenceOptions::default().with_model(inertial().with_distance_cutoff(Some(-1.0))),
    );
    assert!(bad.is_err());
}

#[test]
fn recorded_fold_tracks_keep_each_bounce_peak() {
    // SLRRRL at s = 0: joint 2 meets its wall at 0.5442 s at about 13 folds per second and
    // rebounds at 0.3 of that; the even grid of recorded states (1.8e-4 s apart) straddles
    // the bounce, and a track drawn through the grid alone passed short of the wall, where
    // tiles 1 and 6 graze by 4 um (the collision check then missed that contact). The wall
    // contacts are kept: each fold's track reaches its wall at every bounce
    let chain = FoldWord::parse("SLRRRL").unwrap().to_chain();
    let r = run_reference(
        &chain,
        &TileDesigns::global(Design::thesis().with_s(0.0)),
        &ReferenceOptions::default()
            .with_model(inertial())
            .with_record(Recording::within_budget(chain.len())),
    )
    .unwrap();
    assert!(r.walls.windows(2).all(|w| w[0].0 <= w[1].0));
    let mut worst_grid: f64 = 0.0;
    let mut bounces = 0;
    for j in 0..r.tiles() - 1 {
        let Some(v) = r.model.joint_var(j) else {
            continue;
        };
        let track = r.joint_angle(j);
        let wall = r.model.joint_sign(j) * FRAC_PI_2;
        for &(t, _, x) in r.walls.iter().filter(|w| w.1 == v && w.2 == 1.0) {
            bounces += 1;
            assert!((track.value_at(t) - wall).abs() < 1e-12, "joint {j} at {t}");
            // the grid of states alone, linear between the two around the contact
            let i = r.states.partition_point(|s| s.0 <= t);
            if i == r.states.len() {
                // the final state (the run ends on this contact)
                continue;
            }
            let ((t0, y0), (t1, y1)) = (&r.states[i - 1], &r.states[i]);
            let grid = y0[v] + (y1[v] - y0[v]) * (t - t0) / (t1 - t0);
            worst_grid = worst_grid.max((x - grid) * FRAC_PI_2);
        }
    }
    assert!(bounces >= 5, "{bounces}");
    // the cut the contacts make good (measured: up to 1.8e-3 rad over the 15 bounces)
    assert!(worst_grid > 5e-4, "{worst_grid}");
}
