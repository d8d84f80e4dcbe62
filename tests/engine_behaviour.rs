//! The event engine against the thesis (chapter 6 and 7): overlap set by s, the 4s rule, the
//! sequential edge, inhibition, stalls, and the three-tile experiments.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use foldchain::collision::CheckOptions;
use foldchain::engine::{run, EngineMethod, EngineOptions, Timeline};
use foldchain::timeline::{EventKind, Outcome, SpeedLaw, TileDesigns};
use foldchain::{simulate, Chain, Design, Octagon, Pose};
use parry2d_f64::query::intersection_test;

fn run_with(chain: &str, designs: TileDesigns, speed: SpeedLaw) -> Timeline {
    run(
        &Chain::parse(chain).unwrap(),
        &designs,
        &EngineOptions::default().with_speed(speed),
    )
    .unwrap()
}

fn straight20(s: f64, speed: SpeedLaw) -> Timeline {
    run_with(
        "S*19",
        TileDesigns::global(Design::thesis().with_s(s)),
        speed,
    )
}

#[test]
fn sequential_at_e_over_3_and_cascade_at_0() {
    let e = Design::thesis().e;
    for speed in [SpeedLaw::Unit, SpeedLaw::default()] {
        let tl = straight20(e / 3.0, speed);
        assert_eq!(tl.tiles(), 20);
        assert_eq!(tl.outcome, Outcome::Completed, "{speed:?}");
        assert_eq!(tl.max_moving_magnets(), 1, "{speed:?}");
        // each magnet starts exactly when the previous one arrives
        for k in 1..39 {
            assert_eq!(tl.start_of(k), tl.arrival_of(k - 1), "{speed:?} {k}");
        }
        let tl = straight20(0.0, speed);
        assert_eq!(tl.outcome, Outcome::Completed);
        // every magnet that moves (all but the last, which has no further neighbour)
        assert_eq!(tl.max_moving_magnets(), 39, "{speed:?}");
        assert!((0..39).all(|k| tl.start_of(k) == Some(0.0)));
        assert_eq!(tl.start_of(39), None);
    }
}

#[test]
fn intermediate_s_overlaps_as_the_geometry_predicts() {
    // unit speed: magnet k starts at 4 s k and moves for a = s + e, so ceil(a / 4s) move at
    // once when a / 4s is not whole
    let e = Design::thesis().e;
    for s in [0.1, 0.3, 0.5, 1.0, 1.4] {
        let tl = straight20(s, SpeedLaw::Unit);
        let a = s + e;
        let expect = (a / (4.0 * s)).ceil() as usize;
        assert_eq!(tl.max_moving_magnets(), expect, "s = {s}");
        for k in 0..39 {
            let t = tl.start_of(k).unwrap();
            assert!(
                (t - 4.0 * s * k as f64).abs() < 1e-9,
                "s = {s}, k = {k}: {t}"
            );
        }
    }
    // overdamped: the same trigger points, so more overlap for smaller s
    let counts: Vec<usize> = [0.1, 0.3, 1.0]
        .iter()
        .map(|&s| straight20(s, SpeedLaw::default()).max_moving_magnets())
        .collect();
    assert!(counts[0] > counts[1] && counts[1] > counts[2], "{counts:?}");
}

#[test]
fn sl_sr_sl_propagates_as_ss_ss_ss() {
    let d = TileDesigns::global(Design::thesis());
    let mixed = run_with("SL SR SL", d.clone(), SpeedLaw::default());
    let plain = run_with("SS SS SS", d, SpeedLaw::default());
    for tl in [&mixed, &plain] {
        assert_eq!(tl.outcome, Outcome::Completed);
        assert!(tl.folds.is_empty());
        assert_eq!(tl.count(EventKind::MagnetStarts), 5);
        assert_eq!(tl.count(EventKind::MagnetArrives), 5);
    }
    // the same events (the curved paths change their timing, not what happens)
    let kinds = |tl: &Timeline| {
        let mut v = tl
            .events
            .iter()
            .map(|e| (e.kind, e.index))
            .collect::<Vec<_>>();
        v.sort();
        v
    };
    assert_eq!(kinds(&mixed), kinds(&plain));
    // and the same final shape: every joint straight
    let angles = mixed.joint_angles_at(mixed.duration());
    assert_eq!(angles, vec![0.0, 0.0]);
}

#[test]
fn opposite_curves_stop_propagation_at_that_joint() {
    for (chain, joint) in [("SS SL RS SS", 1), ("SS SS SR LS SS SS", 2), ("SL RS", 0)] {
        let tl = run_with(chain, TileDesigns::default(), SpeedLaw::default());
        match tl.outcome {
            Outcome::Inhibited { joint: j, .. } => assert_eq!(j, joint, "{chain}"),
            ref o => panic!("{chain}: {o:?}"),
        }
        // nothing past the joint moves: the pair's first magnet never starts
        for k in 2 * joint + 1..tl.geometry.magnets() {
            assert_eq!(tl.start_of(k), None, "{chain}: magnet {k}");
        }
        assert_eq!(tl.count(EventKind::Inhibited), 1);
    }
}

#[test]
fn s_above_e_over_3_stalls_where_the_geometry_says() {
    // uniform: magnet 0 cannot travel 4s, so magnet 1 never starts: joint 0
    let tl = straight20(1.7, SpeedLaw::default());
    match &tl.outcome {
        Outcome::Stalled { joint, magnet, .. } => assert_eq!((*joint, *magnet), (0, 1)),
        o => panic!("{o:?}"),
    }
    // one tile with a large s in a chain of good tiles: find the first magnet whose mover
    // cannot travel far enough, from the straight-path distances, and compare.
    let designs = TileDesigns::from_json(
        r#"{"global": {"s": 0.3}, "tiles": [{"from": 7, "to": 7, "s": 2.0}]}"#,
        "test",
    )
    .unwrap();
    let tl = run_with("S*19", designs.clone(), SpeedLaw::default());
    let (list, index) = designs.resolve(20);
    let dz = |t: usize| list[index[t] as usize];
    let b = |t: usize| dz(t).b();
    let (d, a) = (15.0, |t: usize| dz(t).a());
    let mut expect = None;
    for m in 1..39usize {
        let (need, mover_len) = if m % 2 == 1 {
            let t = m / 2; // partner recedes until m is as far from it as from m + 1
            let gap = (d - b(t) / 2.0) + (d - b(t + 1) / 2.0);
            (gap - b(t), a(t))
        } else {
            let t = m / 2; // m - 1 approaches until as near as m's partner
            let gap = (d - b(t - 1) / 2.0) + (d - b(t) / 2.0);
            (gap - b(t), a(t - 1))
        };
        if need > mover_len + 1e-9 {
            expect = Some(m);
            break;
        }
    }
    let m = expect.expect("the override breaks the chain");
    match &tl.outcome {
        Outcome::Stalled {
            joint,
            magnet,
            reason,
            ..
        } => {
            assert_eq!(*magnet, m, "{reason}");
            // magnets 2j+1 and 2j+2 sit either side of joint j
            assert_eq!(*joint, m.saturating_sub(1) / 2);
            assert!(reason.contains("short"), "{reason}");
        }
        o => panic!("{o:?}"),
    }
}

#[test]
fn curved_path_must_start_the_next_magnet_before_its_closest_approach() {
    // with the thesis' layout c = 2.8 mm at the final point (a 1.3 mm wall), s = 0.5 mm is
    // < e/3, so straight paths propagate, but the curve turns away before the next magnet is
    // as near as its partner: propagation stalls at the first fold.
    let old = Design {
        c: Some(2.8),
        ..Design::thesis().with_s(0.5)
    };
    let tl = run_with("SSLSS", TileDesigns::global(old), SpeedLaw::default());
    match &tl.outcome {
        Outcome::Stalled { joint, reason, .. } => {
            assert_eq!(*joint, 2, "{reason}");
            assert!(reason.contains("closest approach"), "{reason}");
        }
        o => panic!("{o:?}"),
    }
    // and the thesis' s = 0.3 mm serves straight and curved paths alike; so does 0.5 mm with
    // the final point against the default 0.8 mm wall (the curve reaches farther)
    let tl = run_with("SSLSS", TileDesigns::default(), SpeedLaw::default());
    assert_eq!(tl.outcome, Outcome::Completed);
    let tl = run_with(
        "SSLSS",
        TileDesigns::global(Design::thesis().with_s(0.5)),
        SpeedLaw::default(),
    );
    assert_eq!(tl.outcome, Outcome::Completed);
}

#[test]
fn thesis_three_tile_experiments_complete() {
    // 7.3: linear propagation then a 90 degree fold; two folds making 180 degrees; and the
    // other two three-tile cases, by the thesis' inequalities (the kinematic baseline's
    // distance rule; the physical engine follows the reference, engine_vs_reference.rs)
    for (word, folds) in [
        ("SL", vec![1]),
        ("LL", vec![0, 1]),
        ("SS", vec![]),
        ("LS", vec![0]),
    ] {
        let (tl, summary) = simulate(
            &Chain::parse(word).unwrap(),
            &TileDesigns::default(),
            &EngineOptions::default().with_method(EngineMethod::Kinematic),
            &CheckOptions::default(),
        )
        .unwrap();
        assert_eq!(summary.tiles, 3);
        assert!(summary.completed, "{word}: {summary:?}");
        assert_eq!(summary.folds, folds, "{word}");
        assert_eq!(summary.first_collision, None);
        let angles = tl.joint_angles_at(tl.duration());
        let expect = foldchain::FoldWord::parse(word).unwrap().final_angles();
        assert_eq!(angles, expect, "{word}");
    }
}

#[test]
fn mixed_s_mixes_sequential_and_simultaneous_stretches() {
    let e = Design::thesis().e;
    let designs = TileDesigns::from_json(
        &format!(
            r#"{{"global": {{"s": {}}}, "tiles": [{{"from": 10, "to": 19, "s": 0.0}}]}}"#,
            e / 3.0
        ),
        "test",
    )
    .unwrap();
    let tl = run_with("S*19", designs, SpeedLaw::Unit);
    assert_eq!(tl.outcome, Outcome::Completed);
    // tiles 0..9: one at a time; tiles 10..: all at once when propagation gets there
    let t20 = tl.start_of(20).unwrap();
    assert!((21..39).all(|k| tl.start_of(k) == Some(t20)));
    assert!(tl.max_moving_magnets() >= 19);
    for k in 1..19 {
        assert_eq!(tl.start_of(k), tl.arrival_of(k - 1));
    }
}

/// The pairs of tiles, not neighbours, whose outlines (inset by the collision check's
/// default tolerance, 1e-7 w) overlap at time `t`: parry's intersection test on the poses
/// of the engine's joint angles, independent of the collision check.
fn overlapping_tiles(tl: &Timeline, t: f64) -> Vec<(usize, usize)> {
    let w = tl.geometry.w;
    let poses = Pose::chain_at_angles(&tl.joint_angles_at(t), w);
    let shape = Octagon::new(w).to_parry(1e-7 * w).unwrap();
    let mut pairs = Vec::new();
    for a in 0..poses.len() {
        for b in a + 2..poses.len() {
            let (pa, pb) = (poses[a].to_parry(), poses[b].to_parry());
            if intersection_test(&pa, &shape, &pb, &shape).unwrap() {
                pairs.push((a, b));
            }
        }
    }
    pairs
}

#[test]
fn collisions_are_reported_with_time_and_tiles() {
    // LLLL closes a ring, and the tile after it runs into the ring
    let (tl, summary) = simulate(
        &Chain::parse("SLLLLS").unwrap(),
        &TileDesigns::default(),
        &EngineOptions::default(),
        &CheckOptions::default(),
    )
    .unwrap();
    assert_eq!(summary.result, "collided", "{summary:?}");
    assert!(!summary.completed);
    let c = summary.first_collision.unwrap();
    let t = c.time.unwrap();
    assert!(t > 0.0 && t <= summary.duration_s, "{c:?}");
    // the fold turning at contact lies between the two tiles, and contact falls inside it
    let (a, b) = c.tiles;
    let j = c.joint.unwrap();
    assert!(a + 2 <= b && (a..b).contains(&j), "{c:?}");
    let f = tl.fold_at(j).unwrap();
    assert!(f.start < t && t <= f.end, "{c:?} {f:?}");
    // the reported tiles overlap just after the reported time, and no two tiles just before
    let dt = 1e-3 * (f.end - f.start);
    assert_eq!(overlapping_tiles(&tl, t - dt), vec![], "{c:?}");
    assert!(
        overlapping_tiles(&tl, (t + dt).min(f.end)).contains(&(a, b)),
        "{c:?}"
    );
    let reason = summary.reason.unwrap();
    assert!(
        reason.starts_with(&format!(
            "tiles {a} and {b} collide at t = {t:.6} s while joint {j} folds"
        )),
        "{reason}"
    );
}

#[test]
fn local_solves_on_one_thread_or_two_give_the_same_events() {
    // the sweeps two at once, the later trailing the earlier: every event the same to the
    // last bit (engine::local's cache rule and shape ids, not the threads' timing)
    use foldchain::model::{Dynamics, ModelOptions};
    let chain = Chain::parse("S*30 LL S*30 RR S*30 LL S*30").unwrap();
    let designs = TileDesigns::global(Design::thesis().with_s(0.1));
    let model = ModelOptions::default().with_dynamics(Dynamics::Inertial);
    let on = |threads| {
        let opts = EngineOptions::default()
            .with_model(model)
            .with_threads(threads);
        run(&chain, &designs, &opts).unwrap()
    };
    let one = on(1);
    assert_eq!(one.outcome, Outcome::Completed);
    for threads in [2, 2, 0] {
        let other = on(threads);
        assert_eq!(one.events.len(), other.events.len());
        for (a, b) in one.events.iter().zip(&other.events) {
            assert_eq!(
                (a.time.to_bits(), a.kind, a.index),
                (b.time.to_bits(), b.kind, b.index),
                "{threads} threads"
            );
        }
    }
}
