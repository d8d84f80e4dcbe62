//! The inertial reference dynamics (issue 11): the thesis' three-tile experiments fold, the
//! overdamped model is its limit of negligible mass, magnets bounce at their path ends, and
//! inertia alone does not rescue the old curved final point.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use foldchain::physics::{ForceLaw, Inertia};
use foldchain::reference::{run_reference, Dynamics, ModelOptions, ReferenceOptions, ReferenceRun};
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
    ModelOptions::default().with_dynamics(Dynamics::Inertial(Inertia::default()))
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
    let light = Inertia {
        magnet_mass_g: Some(0.0265),
        drag: od.drag,
        ..Inertia::default()
    };
    let word = "SS";
    let a = run(word, d, od);
    let b = run(word, d, od.with_dynamics(Dynamics::Inertial(light)));
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
    let dead = Inertia {
        restitution: 0.0,
        ..Inertia::default()
    };
    let bouncy = Inertia {
        restitution: 0.6,
        ..Inertia::default()
    };
    let a = run("SS", d, inertial().with_dynamics(Dynamics::Inertial(dead)));
    let b = run(
        "SS",
        d,
        inertial().with_dynamics(Dynamics::Inertial(bouncy)),
    );
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
        d,
        inertial().with_dynamics(Dynamics::Inertial(
            Inertia::default().with_magnet_mass(0.625),
        )),
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
    let bad = Inertia {
        restitution: 1.5,
        ..Inertia::default()
    };
    let e = run_reference(
        &Chain::parse("SS").unwrap(),
        &TileDesigns::default(),
        &ReferenceOptions::default().with_model(inertial().with_dynamics(Dynamics::Inertial(bad))),
    )
    .unwrap_err();
    assert!(e.to_string().contains("restitution"), "{e}");
}
