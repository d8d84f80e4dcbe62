//! The free-body reference (issue 27): momentum conserved without drag, both sides of a fold
//! turning, the options it refuses.
#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::f64::consts::FRAC_PI_2;

use foldchain::model::{Dynamics, ModelOptions};
use foldchain::reference::ReferenceError;
use foldchain::reference::{run_free_body, FreeBodyOptions, ReferenceOptions};
use foldchain::timeline::{Outcome, TileDesigns};
use foldchain::{Chain, Design};

fn run(word: &str, opts: &FreeBodyOptions) -> foldchain::reference::FreeBodyRun {
    run_in(word, &TileDesigns::default(), opts)
}

fn run_in(
    word: &str,
    designs: &TileDesigns,
    opts: &FreeBodyOptions,
) -> foldchain::reference::FreeBodyRun {
    run_free_body(&Chain::parse(word).unwrap(), designs, opts).unwrap()
}

#[test]
fn momentum_is_conserved_without_drag() {
    // no water: the pair forces are internal and central, a fold's bounce and arrival an
    // impulse inside the chain; from rest the momentum stays zero, within 1e-9 of the
    // momenta of the parts that move (measured: 1.4e-10 at most over these chains at
    // tolerance 1e-10; about 1e-8 at the default 1e-8, the integrator's own error)
    let still = TileDesigns::global(Design {
        water_viscosity: 0.0,
        ..Design::thesis()
    });
    let base = FreeBodyOptions::default().with_momentum_track();
    let opts = base.with_reference(base.reference.with_tolerance(1e-10));
    for word in ["SLS", "SLLS", "SLSRS", "SSLSSRRS"] {
        let r = run_in(word, &still, &opts);
        assert_eq!(r.run.outcome, Outcome::Completed, "{word}");
        let (mut p, mut l, mut ps, mut ls): (f64, f64, f64, f64) = (0.0, 0.0, 0.0, 0.0);
        for m in &r.momentum {
            p = p.max(m.linear[0].hypot(m.linear[1]));
            l = l.max(m.angular.abs());
            ps = ps.max(m.linear_scale);
            ls = ls.max(m.angular_scale);
        }
        // the parts moved (tip speeds of tenths of a metre per second), and the chain
        // turned and moved as a whole
        assert!(ps > 1e-4 && ls > 1e-7, "{word}: {ps} {ls}");
        println!(
            "{word}: linear {:.2e}, angular {:.2e} of the parts'",
            p / ps,
            l / ls
        );
        assert!(p <= 1e-9 * ps, "{word}: linear {p:.3e} against {ps:.3e}");
        assert!(l <= 1e-9 * ls, "{word}: angular {l:.3e} against {ls:.3e}");
        let last = r.base.last().unwrap().1;
        assert!(last[2].abs() > 0.1, "{word}: tile 0 turned {}", last[2]);
    }
}

#[test]
fn a_short_head_turns_about_a_long_tail() {
    // S*2 L S*20: three tiles against twenty-one; nothing anchored, the head swings round
    // (tile 0 turns by most of the fold) and the tail's heading changes far less
    let r = run("S*2LS*20", &FreeBodyOptions::default());
    assert_eq!(r.run.folded_joints(), vec![2]);
    let head = r.base.last().unwrap().1[2];
    let tail = head + FRAC_PI_2;
    assert!(head < -0.5 * FRAC_PI_2, "head turned {head}");
    assert!(tail.abs() < 0.25 * head.abs(), "tail {tail} head {head}");
    // the mirror image: a right fold turns the head the other way
    let m = run("S*2RS*20", &FreeBodyOptions::default());
    let mirror = m.base.last().unwrap().1[2];
    assert!((mirror + head).abs() < 1e-6 * head.abs(), "{mirror} {head}");
}

#[test]
fn what_it_does_not_take_is_refused() {
    let chain = Chain::parse("SLS").unwrap();
    let d = TileDesigns::default();
    let overdamped = FreeBodyOptions::default().with_reference(
        ReferenceOptions::default()
            .with_model(ModelOptions::default().with_dynamics(Dynamics::Overdamped)),
    );
    assert!(matches!(
        run_free_body(&chain, &d, &overdamped),
        Err(ReferenceError::FreeBodyUnsupported { .. })
    ));
    let light = TileDesigns::global(Design {
        tile_mass: 0.0,
        ..Design::thesis()
    });
    let e = run_free_body(&chain, &light, &FreeBodyOptions::default()).unwrap_err();
    assert!(e.to_string().contains("tile_mass"), "{e}");
    let cutoff = FreeBodyOptions::default();
    let cutoff = cutoff.with_reference(
        cutoff
            .reference
            .with_model(cutoff.reference.model.with_distance_cutoff(Some(90.0))),
    );
    assert!(run_free_body(&chain, &d, &cutoff).is_err());
}

/// The coupled joint-angle reference (`ReferenceOptions::coupled`) of `word` in `designs`.
fn coupled(
    word: &str,
    designs: &TileDesigns,
    tolerance: f64,
) -> foldchain::reference::ReferenceRun {
    let opts = FreeBodyOptions::default()
        .reference
        .with_coupled(true)
        .with_tolerance(tolerance);
    foldchain::reference::run_reference(&Chain::parse(word).unwrap(), designs, &opts).unwrap()
}

#[test]
fn the_coupled_joint_angle_reference_follows_the_free_body() {
    // two folds turning at once (a face held shut or pulled open by the other fold's swing,
    // BENCHMARKS.md) and one fold alone: the joints integrated together, with the chain's
    // momentum held at zero, end within 1% of the free body's duration (the joint-angle
    // reference, each joint alone: 22-83% apart on the two-fold chains)
    let d = TileDesigns::default();
    for word in [
        "SLS",
        "S*2LS*20",
        "SLLS",
        "SLLLS",
        "SLRS",
        "SLSRS",
        "S*2LS*2RS*2",
        "S*4LLS*4RRS*4",
    ] {
        let fb = run(word, &FreeBodyOptions::default());
        let c = coupled(word, &d, 1e-8);
        assert_eq!(c.made_by, "coupled joint-angle reference");
        assert_eq!(c.outcome, fb.run.outcome, "{word}");
        assert_eq!(c.folded_joints(), fb.run.folded_joints(), "{word}");
        let (a, b) = (c.duration(), fb.duration());
        println!(
            "{word}: coupled {a:.4} s, free body {b:.4} s, {:+.3}%",
            100.0 * (a / b - 1.0)
        );
        assert!((a / b - 1.0).abs() < 0.01, "{word}: {a} {b}");
    }
    // no water: the free body's momentum stays zero from rest, so holding it at zero
    // changes nothing: the two agree to the integrators' tolerance
    let still = TileDesigns::global(Design {
        water_viscosity: 0.0,
        ..Design::thesis()
    });
    let base = FreeBodyOptions::default();
    let tight = base.with_reference(base.reference.with_tolerance(1e-10));
    for word in ["SLLS", "SLSRS"] {
        let fb = run_in(word, &still, &tight);
        let c = coupled(word, &still, 1e-10);
        let (a, b) = (c.duration(), fb.duration());
        println!("{word} without water: coupled {a:.9} s, free body {b:.9} s");
        assert!((a / b - 1.0).abs() < 1e-6, "{word}: {a} {b}");
    }
    // what it does not take: the overdamped dynamics, ROS2
    let chain = Chain::parse("SLS").unwrap();
    let od = ReferenceOptions::default().with_coupled(true);
    assert!(matches!(
        foldchain::reference::run_reference(&chain, &d, &od),
        Err(ReferenceError::FreeBodyUnsupported { .. })
    ));
    let ros = base
        .reference
        .with_coupled(true)
        .with_method(foldchain::reference::Method::Ros2);
    assert!(foldchain::reference::run_reference(&chain, &d, &ros).is_err());
}

#[test]
fn the_coupled_reference_reaches_the_free_body_s_verdicts_on_every_short_word() {
    // every fold word of 1 to 4 joints at s = 0.3 mm: the same outcome and folds as the free
    // body, and the duration within 1% (measured: 0.097% at most, RRLS; up to 6
    // letters the same verdicts on all 1,092 words, and 4 words 5-7% apart where a slow fold
    // lets the water's drag give the chain a drift the coupled model drops: BENCHMARKS.md)
    let d = TileDesigns::default();
    let mut worst: (f64, String) = (0.0, String::new());
    let mut words = vec![String::new()];
    for _ in 0..4 {
        words = words
            .iter()
            .flat_map(|w| ["S", "L", "R"].map(|c| format!("{w}{c}")))
            .collect();
        for word in &words {
            let fb = run(word, &FreeBodyOptions::default()).run;
            let c = coupled(word, &d, 1e-8);
            assert_eq!(
                std::mem::discriminant(&c.outcome),
                std::mem::discriminant(&fb.outcome),
                "{word}: {:?} {:?}",
                c.outcome,
                fb.outcome
            );
            assert_eq!(c.folded_joints(), fb.folded_joints(), "{word}");
            let e = (c.duration() / fb.duration() - 1.0).abs();
            if e > worst.0 {
                worst = (e, word.clone());
            }
        }
    }
    println!("worst duration: {:.4}% ({})", 100.0 * worst.0, worst.1);
    assert!(worst.0 < 0.01, "{worst:?}");
}
