//! The fast search and its cache against the exact rule (every sample, every pose rebuilt,
//! bisection to the last bit), replayed magnet by magnet on the neighbourhoods real runs meet:
//! straight runs, tight U-turns both ways, quarter turns (curved paths), `s` from the
//! simultaneous limit to the sequential edge, and the cylinder law.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use crate::engine::run_state::RunState;
use crate::engine::start_rule::neighbourhood::Neighbourhood;
use crate::engine::start_rule::{ForceCache, ForceRule, ForceStart, START_TOLERANCE};
use crate::engine::{run, EngineOptions, StartRule};
use crate::physics::ForceLaw;
use crate::timeline::{SpeedLaw, TileDesigns};
use crate::{Chain, Design};

/// What a replay saw: searches compared, cache hits, stalls met.
#[derive(Debug, Default)]
struct Replay {
    compared: usize,
    hits: u64,
    never: usize,
}

/// Runs `word` with the force rule, then asks the rule again for every magnet it was asked
/// about, in the run's state at that moment: exact, searched and cached answers agree within
/// the tolerance, and the fast drive is the exact drive.
fn replay(word: &str, design: Design, law: ForceLaw, cutoff: usize, speed: SpeedLaw) -> Replay {
    let opts = EngineOptions::default()
        .with_speed(speed)
        .with_force_law(law)
        .with_start_rule(StartRule::Force { cutoff });
    let tl = run(
        &Chain::parse(word).unwrap(),
        &TileDesigns::global(design),
        &opts,
    )
    .unwrap();
    let g = &tl.geometry;
    let n = g.magnets();
    let mut start = vec![f64::NAN; n];
    let mut fold_of_joint = vec![u32::MAX; tl.fold_of_joint.len()];
    let mut cache = ForceCache::default();
    let mut seen = Replay::default();
    for m in 1..n - 1 {
        let Some(t0) = tl.start_of(m - 1) else {
            break;
        };
        // the run as it stood when magnet m - 1 started
        start[m - 1] = t0;
        if (m - 1) % 2 == 0 && m >= 3 {
            let j = (m - 1) / 2 - 1;
            fold_of_joint[j] = tl.fold_of_joint[j];
        }
        let progress = RunState {
            start: &start,
            motions: &tl.motions,
            folds: &tl.folds,
            fold_of_joint: &fold_of_joint,
            solved: None,
        };
        let rule = ForceRule {
            geometry: g,
            progress,
            law,
            cutoff,
        };
        let exact = rule.exact_start(m, t0);
        let searched = rule.search(m, t0);
        let cached = rule.start(&mut cache, m, t0);
        let tol = START_TOLERANCE * progress.motion(m - 1).duration();
        let bond = law.bonded_rest_force(g.design(0));
        for (what, got) in [("searched", searched), ("cached", cached)] {
            match (exact, got) {
                (ForceStart::At(a), ForceStart::At(b)) => assert!(
                    (a - b).abs() <= tol,
                    "{word} m {m} {what}: exact {a} got {b} (tolerance {tol:e})"
                ),
                (
                    ForceStart::Never { time, drive },
                    ForceStart::Never {
                        time: t2,
                        drive: d2,
                    },
                ) => assert!(
                    (time - t2).abs() <= tol && (drive - d2).abs() <= 1e-9 * bond,
                    "{word} m {m} {what}: exact never ({time}, {drive}) got ({t2}, {d2})"
                ),
                (a, b) => panic!("{word} m {m} {what}: exact {a:?} got {b:?}"),
            }
        }
        // the fast drive is the exact one, bit for bit, at the start and around it
        let at = match exact {
            ForceStart::At(t) => t,
            ForceStart::Never { time, .. } => {
                seen.never += 1;
                time
            }
        };
        let mut win = Neighbourhood::new(g, progress, law, cutoff, m);
        for t in [t0, at, 0.5 * (t0 + at), at + 0.01 * tol.max(1e-12), t0] {
            assert_eq!(
                win.drive(t).to_bits(),
                rule.exact_drive(m, t).to_bits(),
                "{word} m {m} t {t}"
            );
        }
        seen.compared += 1;
    }
    seen.hits = cache.hits;
    seen
}

fn thesis(s: f64) -> Design {
    Design::thesis().with_s(s)
}

#[test]
fn fast_and_cached_starts_are_the_exact_rule_on_straight_runs_and_u_turns() {
    let e = Design::thesis().e;
    let overdamped = SpeedLaw::default();
    for s in [0.0, 0.05, 0.3, e / 3.0] {
        for word in ["S*24", "S*8 L L S*8", "S*8 R R S*8", "S*6 L L S*6 R R S*6"] {
            let r = replay(word, thesis(s), ForceLaw::PointDipole, 3, overdamped);
            assert!(r.compared >= 10, "{word} s {s}: {r:?}");
            if s == e / 3.0 && word == "S*24" {
                // the sequential edge: the last tile stalls (start_rule's tests)
                assert_eq!(r.never, 1, "{r:?}");
            }
        }
        // a straight run settles into one neighbourhood: the cache answers most magnets
        let r = replay("S*40", thesis(s), ForceLaw::PointDipole, 3, overdamped);
        assert!(r.hits as usize * 2 > r.compared, "s {s}: {r:?}");
    }
}

#[test]
fn fast_and_cached_starts_are_the_exact_rule_on_curved_paths_and_the_cylinder_law() {
    let overdamped = SpeedLaw::default();
    for s in [0.05, 0.3] {
        for word in ["S*6 L S*6 R S*6", "SLSRSLLSRRS", "S*5 L S L S*5"] {
            replay(word, thesis(s), ForceLaw::PointDipole, 3, overdamped);
            replay(word, thesis(s), ForceLaw::PointDipole, 3, SpeedLaw::Unit);
        }
    }
    let law = ForceLaw::cylinder(&Design::thesis());
    for word in ["S*20", "S*8 L L S*8 R R S*8", "S*6 L S*6 R S*6"] {
        let r = replay(word, thesis(0.3), law, 3, overdamped);
        assert!(r.compared >= 10, "{word}: {r:?}");
    }
    // other cutoffs: the nearest neighbours only, and a longer reach
    for cutoff in [1, 5] {
        replay(
            "S*8 L L S*8 R R S*8",
            thesis(0.3),
            ForceLaw::PointDipole,
            cutoff,
            overdamped,
        );
    }
    // the thesis' older layout, where a curved path only just reaches its trigger and the
    // last tile stalls
    let old = Design {
        c: Some(2.8),
        ..Design::thesis()
    };
    for word in ["SL", "LL", "SSL", "SLS"] {
        replay(word, old, ForceLaw::PointDipole, 3, SpeedLaw::Unit);
    }
}
