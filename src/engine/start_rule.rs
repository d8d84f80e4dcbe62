//! When a magnet starts: the rule the engine applies each time a magnet moves.
//!
//! **Distance (default).** The thesis' rule (SPEC section 4, inequalities (6.2)-(6.4)):
//! magnet `m` starts when the moving magnet `m - 1` comes as near to it as its other
//! neighbour `m + 1` is. Nearest neighbours only, at their rest points; it is decided on the
//! mover's path alone, so it is cached per path kind and costs nothing per magnet.
//!
//! **Force.** The same question asked of the forces (SPEC (6.12)): magnet `m` starts at
//! the first moment the force along its path, from every magnet within `cutoff` of it in
//! chain index (and the RI while it is within reach), turns it away from its rest point,
//! each magnet where the engine's own timeline has it at that moment and each tile turned
//! by the engine's fold law. With `cutoff = 1` and straight paths it is the distance rule;
//! the longer-range pairs decide where the nearest ones balance: at the sequential edge
//! `s = e/3` and on a curved path that only just reaches its trigger, where the last tile
//! of a chain lacks the same-pole push of a magnet one tile further on. The pair force, the
//! drive along the path and the neighbour set come from [`crate::physics`], as the reference
//! integrator's do ([`crate::reference`]), so the two agree on which magnets start; the
//! engine's times still come from its speed law.
//!
//! **Cost.** The rule asks for the drive along the mover's path at 64 sample times (and 16
//! after it arrives, while magnets behind it still move). The search evaluates every fourth
//! sample first and, in the first interval where the drive turns positive, the samples
//! between, then finds the root by the Illinois method to [`ROOT_TOLERANCE`] of the mover's
//! duration and bisection to the clock's last bit; with no sign change it evaluates every sample, as the rule is stated, for the
//! nearest approach. Each drive reuses what has not changed since the last time asked
//! (window module: poses, sines and cosines, points on the paths). The answer is cached by
//! the neighbourhood's integer description (cache module), so along a straight run or a
//! serpentine's rows most magnets cost one hash look-up. Fast or cached, the start is within
//! [`START_TOLERANCE`] of the mover's duration of the exact rule's (every sample, bisection
//! to the last bit): the tests check it. About 0.35 us per tile in the engine on a straight
//! run or a serpentine, next to the distance rule's 0.22 (BENCHMARKS.md, "Force start rule").

use crate::engine::run_state::RunState;
use crate::physics::ForceLaw;
use crate::timeline::Geometry;

mod answer;
mod cache;
#[cfg(test)]
mod exact;
#[cfg(test)]
mod fast_tests;
mod neighbourhood;

pub(crate) use answer::ForceStart;
pub(crate) use cache::ForceCache;
use neighbourhood::Neighbourhood;

/// A drive smaller than this fraction of the bonded rest force counts as zero (the
/// reference's balance tolerance), so an exact balance (`s = 0`) starts nothing on a
/// rounding error: 1e-12.
pub(crate) const DRIVE_TOLERANCE: f64 = 1e-12;

/// The root search takes false-position (Illinois) steps until the start is bracketed to
/// this fraction of the mover's duration, then bisects to the clock's last bit (as the exact
/// rule does, so that both end on the same number): 1e-12.
pub(crate) const ROOT_TOLERANCE: f64 = 1e-12;

/// The force rule's start, fast and cached, is within this fraction of the mover's duration
/// of the exact rule's: 1e-9 (the search ends on the same last bit of the clock as the exact
/// rule's bisection unless the drive crosses its threshold more than once within a sample
/// step; the cache merges neighbourhoods whose starts differ by some 100 units of the clock's
/// last bit).
#[cfg(test)]
pub(crate) const START_TOLERANCE: f64 = 1e-9;

/// Samples of the drive along the mover's path.
const PATH_SAMPLES: usize = 64;
/// Samples after the mover arrives, while magnets behind it still move.
const AFTER_SAMPLES: usize = 16;
/// The first pass of the search evaluates every this many samples.
const COARSE: usize = 4;
/// At most this many steps of the root search (it needs about twenty).
const ROOT_STEPS: usize = 100;

/// The rule that starts a magnet.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "rule", rename_all = "snake_case")]
pub enum StartRule {
    /// Nearest neighbours' distances (the thesis' inequalities).
    #[default]
    Distance,
    /// The pair forces of every magnet within `cutoff` in chain index.
    Force {
        /// Pairs at most this many apart in chain index count (at least 1).
        cutoff: usize,
    },
}

/// The force rule's view of a run: the chain, the run so far, the law and the cutoff.
pub(crate) struct ForceRule<'a> {
    pub(crate) geometry: &'a Geometry,
    pub(crate) progress: RunState<'a>,
    pub(crate) law: ForceLaw,
    pub(crate) cutoff: usize,
}

/// The rule's sample times for magnet `m`, its mover having started at `t0`: `t0`, 64 along
/// the mover's path (equal steps of arc length), and 16 after its arrival while any magnet
/// within reach behind `m` still moves.
fn sample_times(progress: &RunState<'_>, cutoff: usize, m: usize, t0: f64) -> Vec<f64> {
    let motion = *progress.motion(m - 1);
    let mover_end = t0 + motion.duration();
    // the last moment anything within reach behind `m` still moves
    let lo = m.saturating_sub(cutoff);
    let last = (lo..m)
        .filter_map(|k| progress.arrival_of(k))
        .fold(mover_end, f64::max);
    let mut times = Vec::with_capacity(PATH_SAMPLES + AFTER_SAMPLES + 1);
    times.push(t0);
    for i in 1..=PATH_SAMPLES {
        times.push(t0 + motion.time_to(motion.length * i as f64 / PATH_SAMPLES as f64));
    }
    if last > mover_end {
        for i in 1..=AFTER_SAMPLES {
            times.push(mover_end + (last - mover_end) * i as f64 / AFTER_SAMPLES as f64);
        }
    }
    times
}

impl ForceRule<'_> {
    /// When magnet `m` starts, magnet `m - 1` having started at `t0`: from `cache` when the
    /// same neighbourhood was searched before in this run.
    pub(crate) fn start(&self, cache: &mut ForceCache, m: usize, t0: f64) -> ForceStart {
        cache.start(self.geometry, &self.progress, self.cutoff, m, t0, || {
            self.search(m, t0)
        })
    }

    /// The drive threshold, N.
    fn threshold(&self) -> f64 {
        DRIVE_TOLERANCE * self.law.bonded_rest_force(self.geometry.design(0))
    }

    /// When magnet `m` starts, magnet `m - 1` having started at `t0`, searched (no cache).
    pub(crate) fn search(&self, m: usize, t0: f64) -> ForceStart {
        let threshold = self.threshold();
        let times = sample_times(&self.progress, self.cutoff, m, t0);
        let tol = ROOT_TOLERANCE * self.progress.motion(m - 1).duration();
        let mut win = Neighbourhood::new(self.geometry, self.progress, self.law, self.cutoff, m);
        let v0 = win.drive(t0);
        if v0 > threshold {
            return ForceStart::At(t0);
        }
        // every COARSE-th sample (and the last); in the first interval where the drive
        // turns positive, the samples between, in order
        let last = times.len() - 1;
        let (mut i, mut vi) = (0, v0);
        while i < last {
            let next = (i + COARSE).min(last);
            let v = win.drive(times[next]);
            if v > threshold {
                let mut below = (times[i], vi);
                for &t in &times[i + 1..next] {
                    let vk = win.drive(t);
                    if vk > threshold {
                        return ForceStart::At(root(&mut win, threshold, below, (t, vk), tol));
                    }
                    below = (t, vk);
                }
                let above = (times[next], v);
                return ForceStart::At(root(&mut win, threshold, below, above, tol));
            }
            (i, vi) = (next, v);
        }
        // no sign change on the coarse samples: every sample, as the rule is stated
        let mut best = (t0, v0);
        let mut below = (t0, v0);
        for &t in &times[1..] {
            let v = win.drive(t);
            if v > threshold {
                return ForceStart::At(root(&mut win, threshold, below, (t, v), tol));
            }
            if v > best.1 {
                best = (t, v);
            }
            below = (t, v);
        }
        ForceStart::Never {
            time: best.0,
            drive: best.1,
        }
    }
}

/// The first time in `(below.0, above.0]` where the drive exceeds `threshold`, the drive
/// being at most `threshold` at `below` and above it at `above`: the Illinois method (false
/// position, halving the value kept at an end that stays twice) until the bracket is within
/// `tol`, then bisection until its ends are neighbouring numbers of the clock, as the exact
/// rule's bisection ends; the bracket's upper end, where the drive is above the threshold.
fn root(
    win: &mut Neighbourhood<'_>,
    threshold: f64,
    below: (f64, f64),
    above: (f64, f64),
    tol: f64,
) -> f64 {
    let (mut a, mut fa) = (below.0, below.1 - threshold);
    let (mut b, mut fb) = (above.0, above.1 - threshold);
    let mut kept = 0i8;
    for _ in 0..ROOT_STEPS {
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            break;
        }
        let falsi = b - fb * (b - a) / (fb - fa);
        let c = if b - a > tol && falsi > a && falsi < b {
            falsi
        } else {
            mid
        };
        let fc = win.drive(c) - threshold;
        if fc > 0.0 {
            (b, fb) = (c, fc);
            if kept == -1 {
                fa *= 0.5;
            }
            kept = -1;
        } else {
            (a, fa) = (c, fc);
            if kept == 1 {
                fb *= 0.5;
            }
            kept = 1;
        }
    }
    b
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use crate::engine::{run, EngineError, EngineOptions, StartRule};
    use crate::timeline::{EventKind, Outcome, SpeedLaw, TileDesigns};
    use crate::{Chain, Design};

    fn run_with(word: &str, s: f64, rule: StartRule) -> crate::engine::Timeline {
        run_design(word, Design::thesis().with_s(s), rule)
    }

    fn run_design(word: &str, design: Design, rule: StartRule) -> crate::engine::Timeline {
        run(
            &Chain::parse(word).unwrap(),
            &TileDesigns::global(design),
            &EngineOptions::default()
                .with_speed(SpeedLaw::Unit)
                .with_start_rule(rule),
        )
        .unwrap()
    }

    #[test]
    fn nearest_neighbour_forces_on_a_straight_chain_are_the_distance_rule() {
        // cutoff 1, straight paths: the drive changes sign where the next magnet is
        // equidistant from its neighbours, 4s along (thesis 6.2)
        for s in [0.1, 0.3, 1.0] {
            let d = run_with("S*7", s, StartRule::Distance);
            let f = run_with("S*7", s, StartRule::Force { cutoff: 1 });
            assert_eq!(f.outcome, Outcome::Completed);
            for k in 0..d.geometry.magnets() {
                match (d.start_of(k), f.start_of(k)) {
                    (Some(a), Some(b)) => assert!((a - b).abs() < 1e-9, "s {s} k {k}: {a} {b}"),
                    (a, b) => assert_eq!(a.is_some(), b.is_some(), "s {s} k {k}"),
                }
            }
        }
    }

    #[test]
    fn the_last_tile_lacks_the_push_from_beyond() {
        // the same-pole magnet one tile ahead pushes each magnet off its balance; the last
        // tile has none, so where the nearest neighbours only just balance (a fold at the
        // last joint with the thesis' layout c = 2.8 mm at the curved final point, the
        // sequential edge) its first magnet never starts
        let force = StartRule::Force { cutoff: 3 };
        let old = Design {
            c: Some(2.8),
            ..Design::thesis()
        };
        for word in ["SL", "LL", "SSL"] {
            // with the final point against the default 0.8 mm wall it folds
            assert_eq!(run_with(word, 0.3, force).outcome, Outcome::Completed);
            let t = run_design(word, old, force);
            let last = 2 * (word.len() + 1) - 2;
            match &t.outcome {
                Outcome::Stalled { magnet, joint, .. } => {
                    assert_eq!((*magnet, *joint), (last, word.len() - 1), "{word}")
                }
                o => panic!("{word}: {o:?}"),
            }
            // one more straight tile and it folds
            let longer = run_design(&format!("{word}S"), old, force);
            assert_eq!(longer.outcome, Outcome::Completed, "{word}S");
            // the distance rule folds both
            assert_eq!(
                run_design(word, old, StartRule::Distance).outcome,
                Outcome::Completed
            );
        }
        let e = Design::thesis().e;
        let t = run_with("S*9", e / 3.0, force);
        assert!(
            matches!(t.outcome, Outcome::Stalled { magnet: 18, .. }),
            "{:?}",
            t.outcome
        );
        assert_eq!(t.count(EventKind::MagnetStarts), 18);
    }

    #[test]
    fn simultaneous_limit_starts_all_but_the_end_at_once() {
        let t = run_with("S*9", 0.0, StartRule::Force { cutoff: 3 });
        assert_eq!(t.outcome, Outcome::Completed);
        let starts: Vec<f64> = (0..t.geometry.magnets() - 1)
            .map(|k| t.start_of(k).unwrap())
            .collect();
        // every magnet starts at once (within the drive tolerance's 1e-11 s) except the
        // last two, which lack the pull of the magnets beyond the end: they start once
        // those before them have moved
        let n = starts.len();
        assert!(starts[..n - 2].iter().all(|&s| s < 1e-9), "{starts:?}");
        assert!(starts[n - 2..].iter().all(|&s| s > 1e-3), "{starts:?}");
    }

    #[test]
    fn cutoff_zero_is_refused() {
        let r = run(
            &Chain::parse("SS").unwrap(),
            &TileDesigns::default(),
            &EngineOptions::default().with_start_rule(StartRule::Force { cutoff: 0 }),
        );
        assert!(matches!(r, Err(EngineError::BadCutoff)));
    }
}
