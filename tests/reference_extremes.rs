//! The reference force integrator on stiff and extreme cases (issue 6): no NaN, no panic, no
//! hang, and an explicit diagnosis where the physics fails; agreement with the event engine
//! on the order in which magnets start.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use foldchain::engine::{run, EngineMethod, EngineOptions, StartRule};
use foldchain::model::ModelOptions;
use foldchain::reference::{run_reference, Method, ReferenceOptions, ReferenceRun};
use foldchain::timeline::{Event, EventKind, Outcome, RunResult, TileDesigns};
use foldchain::{Chain, Design, FoldWord, Pose};

fn reference(word: &str, d: Design, model: ModelOptions, method: Method) -> ReferenceRun {
    let r = run_reference(
        &Chain::parse(word).unwrap(),
        &TileDesigns::global(d),
        &ReferenceOptions::default()
            .with_method(method)
            .with_tolerance(1e-5)
            .with_model(model),
    )
    .unwrap();
    assert!(r.final_state.iter().all(|v| v.is_finite()), "{word}");
    assert!(r.events.iter().all(|e| e.time.is_finite()), "{word}");
    r
}

fn starts(events: &[Event]) -> Vec<u32> {
    events
        .iter()
        .filter(|e| e.kind == EventKind::MagnetStarts)
        .map(|e| e.index)
        .collect()
}

#[test]
fn cascade_at_s_1e_minus_12_d_completes() {
    let t = Design::thesis();
    let r = reference(
        "S*5",
        t.with_s(1e-12 * t.d),
        ModelOptions::default(),
        Method::Dopri5,
    );
    assert_eq!(r.outcome, Outcome::Completed);
    assert_eq!(r.stopped, None);
    // every magnet but the last moves
    assert_eq!(starts(&r.events).len(), 11);
}

#[test]
fn sequential_edge_then_stall() {
    let t = Design::thesis();
    // exactly s = e/3: the nearest-neighbour forces balance where the previous magnet
    // arrives, so the longer-range forces decide. Inside the chain the same-pole magnet one
    // tile ahead pushes the next magnet off; the last tile has none, and its first magnet
    // never starts: the reference stalls at the last joint where the engine completes.
    let r = reference(
        "S*5",
        t.with_s(t.e / 3.0),
        ModelOptions::default(),
        Method::Dopri5,
    );
    match &r.outcome {
        Outcome::Stalled {
            joint,
            magnet,
            reason,
            ..
        } => {
            assert_eq!((*joint, *magnet), (4, 10), "{reason}");
            assert!(reason.contains("never started"), "{reason}");
        }
        o => panic!("{o:?}"),
    }
    // just above: all stall at joint 0. The kinematic baseline's magnet 1 never starts; in
    // the reference the push of magnet 3 (same pole, one tile ahead) still starts magnet 1,
    // and magnet 2 never starts; the engine's local solves weigh the same forces
    let s = t.e / 3.0 + 0.05;
    let r = reference("S*5", t.with_s(s), ModelOptions::default(), Method::Dopri5);
    let engine = |opts: EngineOptions| {
        run(
            &Chain::parse("S*5").unwrap(),
            &TileDesigns::global(t.with_s(s)),
            &opts,
        )
        .unwrap()
    };
    let tl = engine(EngineOptions::default());
    let kin = engine(EngineOptions::default().with_method(EngineMethod::Kinematic));
    for (o, m) in [(&r.outcome, 2), (&tl.outcome, 2), (&kin.outcome, 1)] {
        assert!(
            matches!(o, Outcome::Stalled { joint: 0, magnet, .. } if *magnet == m),
            "{o:?}"
        );
    }
    // the engine's force rule weighs the same pairs as the reference and stalls where it
    // does, at both values of s
    let force = EngineOptions::default().with_start_rule(StartRule::Force {
        cutoff: ModelOptions::DEFAULT_CUTOFF,
    });
    for (s, joint, magnet) in [(t.e / 3.0, 4, 10), (t.e / 3.0 + 0.05, 0, 2)] {
        let tl = run(
            &Chain::parse("S*5").unwrap(),
            &TileDesigns::global(t.with_s(s)),
            &force,
        )
        .unwrap();
        assert!(
            matches!(tl.outcome, Outcome::Stalled { joint: j, magnet: m, .. } if (j, m) == (joint, magnet)),
            "s {s}: {:?}",
            tl.outcome
        );
    }
}

#[test]
fn moments_from_1e_minus_6_to_1e6_scale_time_only() {
    let t = Design::thesis();
    let base = reference("S*3", t, ModelOptions::default(), Method::Dopri5);
    for f in [1e-6, 1e-3, 1e3, 1e6] {
        let d = Design {
            remanence: t.remanence * f,
            ..t
        };
        let r = reference("S*3", d, ModelOptions::default(), Method::Dopri5);
        assert_eq!(r.outcome, Outcome::Completed, "x{f}");
        // overdamped under forces ~ m^2: every time scales by 1/f^2
        let ratio = r.duration() * f * f / base.duration();
        assert!((ratio - 1.0).abs() < 1e-6, "x{f}: {ratio}");
        assert_eq!(starts(&r.events), starts(&base.events));
    }
}

#[test]
fn micrometre_tiles() {
    // thesis 8.2.1: the design scaled by 1e-3 (30 um tiles, 3 um x 5 um magnets). With
    // Stokes drag (~ size, rotational ~ size^3) the timeline is the same as at 30 mm: forces
    // go as size^2 (moments ~ size^3, 1/r^4), torques as size^3. The magnet's drag scales by
    // the size, and the tiles' water drag with a film scaled alike (`mu A / h` ~ size,
    // `mu J / h` ~ size^3).
    let t = Design::thesis();
    let k = 1e-3;
    let micro = Design {
        tile_width: 30.0 * k,
        d: 15.0 * k,
        s: 0.3 * k,
        e: 4.7 * k,
        magnet_diameter: 3.0 * k,
        magnet_height: 5.0 * k,
        wall: t.wall * k,
        magnet_drag: Some(5.0 * k), // the overdamped default, 5 N s/m
        water_film: t.water_film * k,
        ..t
    };
    let mo = ModelOptions::default();
    let macro_run = reference("SLLS", t, mo, Method::Dopri5);
    let r = reference("SLLS", micro, mo, Method::Dopri5);
    assert_eq!(r.outcome, macro_run.outcome);
    assert_eq!(r.folded_joints(), vec![1, 2]);
    let rel = (r.duration() - macro_run.duration()).abs() / macro_run.duration();
    assert!(rel < 1e-4, "{rel}");
    // a static friction of 1 uN, far below anything at 30 mm, stops the micrometre chain
    // before it starts: a diagnosis, not a hang
    let r = reference(
        "SLLS",
        Design {
            friction: 1e-6,
            ..micro
        },
        mo,
        Method::Dopri5,
    );
    match &r.outcome {
        Outcome::Stalled {
            joint: 0, reason, ..
        } => {
            assert!(reason.contains("never started"), "{reason}")
        }
        o => panic!("{o:?}"),
    }
}

#[test]
fn bonded_magnets_nearly_touching() {
    // final gap 2c = 1.001 magnet diameters (c = 1.5015 mm, e = 6.7 mm keep (6.1)-(6.10)):
    // the 1/r^4 pull grows 12-fold over the thesis' 2c = 5.6 mm at the end of each move
    let d = Design {
        c: Some(1.5 * 1.001),
        e: 6.7,
        ..Design::thesis()
    };
    assert!(d.check().is_ok());
    for m in [Method::Dopri5, Method::Ros2] {
        let r = reference("S*3", d, ModelOptions::default(), m);
        assert_eq!(r.outcome, Outcome::Completed, "{m:?}");
        assert_eq!(r.stopped, None);
    }
}

#[test]
fn integrators_agree_and_engine_starts_magnets_in_the_same_order() {
    let t = Design::thesis();
    let a = reference("S*7", t, ModelOptions::default(), Method::Dopri5);
    let b = reference("S*7", t, ModelOptions::default(), Method::Ros2);
    assert_eq!(a.outcome, Outcome::Completed);
    assert_eq!(b.outcome, Outcome::Completed);
    let rel = (a.duration() - b.duration()).abs() / a.duration();
    assert!(rel < 1e-3, "{rel}");
    let tl = run(
        &Chain::parse("S*7").unwrap(),
        &TileDesigns::global(t),
        &EngineOptions::default(),
    )
    .unwrap();
    assert_eq!(starts(&a.events), starts(&tl.events));
    assert_eq!(starts(&b.events), starts(&tl.events));
}

/// Whether JSON `a` equals `b`, numbers within 1e-15 relative (JSON text need not round-trip
/// the last bit of an f64).
fn same_json(a: &serde_json::Value, b: &serde_json::Value) -> bool {
    use serde_json::Value;
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            (x - y).abs() <= 1e-15 * x.abs().max(y.abs())
        }
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(p, q)| same_json(p, q))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len()
                && x.iter()
                    .all(|(k, v)| y.get(k).is_some_and(|w| same_json(v, w)))
        }
        _ => a == b,
    }
}

#[test]
fn summary_and_timeline_say_what_the_run_did() {
    let r = reference(
        "SLLS",
        Design::thesis(),
        ModelOptions::default(),
        Method::Dopri5,
    );
    // the summary, in the engine's fields, holds the run's own values
    let mut json: serde_json::Value = serde_json::to_value(r.to_summary()).unwrap();
    // the parameters the run used, defaults filled in; no free motion without recorded states
    let parameters = json.as_object_mut().unwrap().remove("parameters").unwrap();
    assert_eq!(parameters["model"], "joint-angle reference");
    assert_eq!(parameters["magnet_drag_n_s_per_m"], 5.0);
    assert_eq!(parameters["water_viscosity_pa_s"], 1e-3);
    assert_eq!(
        json.as_object_mut().unwrap().remove("free_motion"),
        Some(serde_json::Value::Null)
    );
    let duration = r.duration();
    assert!(duration > 0.0 && duration <= r.end_time);
    let want = serde_json::json!({
        "tiles": 5,
        "completed": true,
        "result": "completed",
        "duration_s": duration,
        "events": r.events.len(),
        "folds": [1, 2],
        "max_moving_magnets": r.max_moving.0,
        "inhibited_at": null,
        "stalled_at": null,
        "reason": null,
        "first_collision": null,
        // measured by the collision check (check_reference), not by the run
        "clearance": null,
        "speed_law": {"overdamped": {"drag": 5.0}},
    });
    assert!(same_json(&json, &want), "{json}");
    // every magnet but the last started and arrived, both folds started and ended
    for (kind, n) in [
        (EventKind::MagnetStarts, 9),
        (EventKind::MagnetArrives, 9),
        (EventKind::FoldStarts, 2),
        (EventKind::FoldEnds, 2),
        (EventKind::RiContact, 1),
    ] {
        assert_eq!(
            r.events.iter().filter(|e| e.kind == kind).count(),
            n,
            "{kind}"
        );
    }
    assert!(
        r.max_moving.0 >= 2 && r.max_moving.0 <= 9,
        "{:?}",
        r.max_moving
    );
    // the timeline holds every event as [time, kind, index], in time order
    let tl: serde_json::Value = serde_json::from_str(&r.timeline_json()).unwrap();
    let events: Vec<serde_json::Value> = r
        .events
        .iter()
        .map(|e| serde_json::json!([e.time, e.kind.name(), e.index]))
        .collect();
    let want = serde_json::json!({
        "tiles": 5,
        "speed_law": {"reference": {
            "method": "dopri5",
            "tolerance": 1e-5,
            "drag": 5.0,
        }},
        "index": "magnet k is magnet k mod 2 of tile k/2; joint events index the joint",
        "events": events,
    });
    assert!(same_json(&tl, &want), "{tl}");
    assert_eq!(tl["events"][0], serde_json::json!([0.0, "ri_contact", 0]));
    assert!(r.events.windows(2).all(|w| w[0].time <= w[1].time));
    // a stall reads the same way: with the thesis' layout c = 2.8 mm at the curved final
    // point (a 1.3 mm wall), in the three-tile U-turn the first fold closes, then magnet 3
    // comes to rest mid-path, balanced, and magnet 4 never starts: joint 1 stays open
    let r = reference(
        "LL",
        Design {
            c: Some(2.8),
            ..Design::thesis()
        },
        ModelOptions::default(),
        Method::Dopri5,
    );
    let s = r.to_summary();
    match &r.outcome {
        Outcome::Stalled { joint, magnet, .. } => assert_eq!((*joint, *magnet), (1, 4)),
        o => panic!("{o:?}"),
    }
    assert_eq!((s.result, s.completed), (RunResult::Stalled, false));
    assert_eq!((s.stalled_at, s.inhibited_at), (Some(1), None));
    assert_eq!(s.folds, vec![0]);
    let reason = s.reason.unwrap();
    assert!(reason.starts_with("magnet 3 came to rest"), "{reason}");
    let along = r.final_state[r.model.magnet_var(3)];
    assert!(along > 0.1 && along < 0.9, "{along}");
    assert_eq!(
        r.events.last().map(|e| (e.kind, e.index)),
        Some((EventKind::Stalled, 1))
    );
}

fn engine_pose_drift(tiles: usize) -> f64 {
    // a serpentine of tight U-turns, run by the engine; its f64 final poses (composed
    // transforms at the folds' final angles) against the exact poses
    let mut word = String::new();
    let mut left = true;
    while word.len() < tiles - 1 {
        word.push_str(&"S".repeat(98));
        word.push_str(if left { "LL" } else { "RR" });
        left = !left;
    }
    word.truncate(tiles - 1);
    let chain = Chain::parse(&word).unwrap();
    // the poses come from the final angles alone: the kinematic baseline's will do
    let tl = run(
        &chain,
        &TileDesigns::default(),
        &EngineOptions::default().with_method(EngineMethod::Kinematic),
    )
    .unwrap();
    assert_eq!(tl.outcome, Outcome::Completed);
    let angles = tl.joint_angles_at(tl.duration());
    let w = 30.0;
    let approx = Pose::chain_at_angles(&angles, w);
    let exact = FoldWord::parse(&word).unwrap().final_poses();
    approx
        .iter()
        .zip(&exact)
        .map(|(a, e)| {
            let (x, y) = e.centre.to_f64(w);
            ((a.x - x).powi(2) + (a.y - y).powi(2)).sqrt() / w
        })
        .fold(0.0, f64::max)
}

#[test]
fn engine_pose_drift_100k_tiles() {
    let drift = engine_pose_drift(100_000);
    assert!(drift < 1e-9, "{drift}");
}

#[test]
#[ignore = "1,000,000 tiles: a few seconds in release (cargo test --release -- --ignored)"]
fn engine_pose_drift_1m_tiles() {
    let drift = engine_pose_drift(1_000_000);
    println!("1e6 tiles: largest centre drift {drift:.3e} w");
    assert!(drift < 1e-8, "{drift}");
}
