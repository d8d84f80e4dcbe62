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
//! The force rule samples the drive at 64 points along the mover's path (and 16 after it
//! arrives, while magnets behind it still move), then bisects the first sign change to
//! 1e-15 of the span. Its cost is about 100 force evaluations of at most `2 cutoff` pairs
//! per magnet, with nothing cached: for chains up to some 1e5 tiles.

use kurbo::{Point, Vec2};

use crate::engine::progress::Progress;
use crate::kinematics::joint_transform;
use crate::physics::{along_path, neighbours, reach, ForceLaw, Pole};
use crate::timeline::Geometry;
use crate::Pose;

/// A drive smaller than this fraction of the bonded rest force counts as zero (the
/// reference's balance tolerance), so an exact balance (`s = 0`) starts nothing on a
/// rounding error: 1e-12.
pub const DRIVE_TOLERANCE: f64 = 1e-12;

/// Samples of the drive along the mover's path.
const PATH_SAMPLES: usize = 64;
/// Samples after the mover arrives, while magnets behind it still move.
const AFTER_SAMPLES: usize = 16;

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

/// Where the force rule starts a magnet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ForceStart {
    /// At this time, s.
    At(f64),
    /// Never: the drive came nearest to starting it at `time`, where it was `drive` N.
    Never {
        /// When the drive was largest, s.
        time: f64,
        /// The largest drive, N (negative: towards the rest point).
        drive: f64,
    },
}

/// The force rule's view of a run: the chain, the run so far, the law and the cutoff.
pub(crate) struct ForceRule<'a> {
    pub(crate) geometry: &'a Geometry,
    pub(crate) progress: Progress<'a>,
    pub(crate) law: ForceLaw,
    pub(crate) cutoff: usize,
}

impl ForceRule<'_> {
    /// The force (N) along magnet `m`'s path at its rest point at time `t`, from every
    /// magnet within the cutoff of it in chain index (and the RI while within reach), each
    /// where the run has it then.
    fn drive(&self, m: usize, t: f64) -> f64 {
        let g = self.geometry;
        let within = reach(m, self.cutoff, g.magnets());
        let (tlo, thi) = (within.start() / 2, within.end() / 2);
        // tile poses in the frame of tile `tlo`
        let mut poses = Vec::with_capacity(thi - tlo + 1);
        let mut pose = Pose::IDENTITY;
        poses.push(pose);
        for j in tlo..thi {
            pose = pose.then(&joint_transform(self.progress.joint_angle(j, t), g.w));
            poses.push(pose);
        }
        let at = |k: usize| {
            let p = g.path(k).point_at(self.progress.travel_at(k, t));
            Point::from(poses[k / 2 - tlo].transform_point(p))
        };
        let on = Pole::Magnet(m);
        let pm = at(m);
        let tangent = Vec2::from(poses[m / 2 - tlo].transform_vector(g.path(m).tangent_at(0.0)));
        let mm = g.design(m / 2).moment();
        let ri = g.ri();
        let mut drive = 0.0;
        for source in neighbours(m, self.cutoff, g.magnets()) {
            let (p, moment) = match source {
                Pole::Magnet(k) => (at(k), g.design(k / 2).moment()),
                // the RI is fixed in tile 0's frame
                Pole::Ri => (
                    Point::from(poses[0].transform_point(ri.position.into())),
                    ri.moment,
                ),
            };
            let force = self.law.force(p, pm, moment, mm, source.attracts(on));
            drive += along_path(force, tangent);
        }
        drive
    }

    /// When magnet `m` starts, magnet `m - 1` having started at `t0`.
    pub(crate) fn start(&self, m: usize, t0: f64) -> ForceStart {
        let threshold = DRIVE_TOLERANCE * self.law.bonded_rest_force(self.geometry.design(0));
        let mover = m - 1;
        let motion = *self.progress.motion(mover);
        let mover_end = t0 + motion.duration();
        // the last moment anything within reach behind `m` still moves
        let lo = m.saturating_sub(self.cutoff);
        let last = (lo..m)
            .filter_map(|k| self.progress.arrival_of(k))
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
        let mut best = (t0, f64::NEG_INFINITY);
        let mut prev = t0;
        for (i, &t) in times.iter().enumerate() {
            let v = self.drive(m, t);
            if v > threshold {
                if i == 0 {
                    return ForceStart::At(t0);
                }
                let (mut a, mut b) = (prev, t);
                for _ in 0..60 {
                    let mid = 0.5 * (a + b);
                    if mid <= a || mid >= b {
                        break;
                    }
                    if self.drive(m, mid) > threshold {
                        b = mid;
                    } else {
                        a = mid;
                    }
                }
                return ForceStart::At(b);
            }
            if v > best.1 {
                best = (t, v);
            }
            prev = t;
        }
        ForceStart::Never {
            time: best.0,
            drive: best.1,
        }
    }
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
