//! The stiff study's defining case: where the model is stiff, the L-stable ROS2 finishes in a
//! fraction of Dormand-Prince's steps (issue 6), with the same events.

// Tests may unwrap (CONTRIBUTING.md); the workspace lint is for library code.
#![allow(clippy::unwrap_used)]

use foldchain::reference::Method;
use foldchain::timeline::{Event, EventKind, Outcome};
use foldchain_validation::stiff::select_cases;

/// The magnets' start events, by index.
fn starts(events: &[Event]) -> Vec<u32> {
    events
        .iter()
        .filter(|e| e.kind == EventKind::MagnetStarts)
        .map(|e| e.index)
        .collect()
}

#[test]
fn stiff_case_ros2_finishes_in_a_twentieth_of_the_steps() {
    // heavy, slowly folding tiles (water 1e9 times as viscous): the folds take
    // about 1e6 magnet time scales, the magnets of each folding pair follow their balances,
    // and Dormand-Prince is held to its stability bound while ROS2 (L-stable) is not.
    // Counts, not wall times: the step counts are deterministic.
    let case = select_cases(&["SLLS visc x1e9".to_string()])
        .unwrap()
        .remove(0);
    assert!(case.stiff);
    assert!(case.time_scales().unwrap().ratio() > 1e5);
    let (a, _) = case.run(Method::Dopri5).unwrap();
    let (b, _) = case.run(Method::Ros2).unwrap();
    for r in [&a, &b] {
        assert_eq!(r.outcome, Outcome::Completed, "{:?}", r.options.method);
        assert_eq!(r.stopped, None, "{:?}", r.options.method);
        assert_eq!(r.folded_joints(), vec![1, 2]);
        assert!(r.final_state.iter().all(|v| v.is_finite()));
    }
    // both at tolerance 1e-3: end times (the folds' closing, about 121 s) agree to 1%
    // (0.35% measured); the same for the last event
    let rel = (a.end_time - b.end_time).abs() / b.end_time;
    assert!(
        rel < 1e-2,
        "end times {} vs {}: {rel}",
        a.end_time,
        b.end_time
    );
    let rel = (a.duration() - b.duration()).abs() / b.duration();
    assert!(
        rel < 1e-2,
        "durations {} vs {}: {rel}",
        a.duration(),
        b.duration()
    );
    assert_eq!(starts(&a.events), starts(&b.events));
    // the requirement: the explicit method needs far more steps (56x measured)
    assert!(
        a.stats.accepted >= 20 * b.stats.accepted,
        "dopri5 {} accepted steps, ros2 {}",
        a.stats.accepted,
        b.stats.accepted
    );
}
