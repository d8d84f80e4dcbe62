//! The force rule's drive, evaluated fast: one magnet's neighbourhood set up once per start
//! search, then the drive at many times without rebuilding what does not change.
//!
//! A search for magnet `m`'s start asks for the drive on `m` at some 20 to 90 times. Between
//! them only the magnets still moving and the joints still folding change. [`Neighbourhood`] keeps,
//! for the magnets within the cutoff and the tiles that carry them: each magnet's path,
//! moment and polarity, its last travel and the point there (a point on an arc costs a sine
//! and a cosine), each joint's last angle and transform, and each tile's pose with the sine
//! and cosine of its angle. A new time recomputes the travels of the magnets that move then,
//! the angles of the joints that fold then, and the poses from the first joint that changed.
//!
//! The arithmetic is the one the rule was written with ([`crate::kinematics::joint_transform`],
//! [`Pose::then`], [`Pose::transform_point`] with its sine and cosine kept, the pair law of
//! [`ForceLaw::force`] and [`along_path`] in the order of [`crate::physics::neighbours`]), so the drive is the
//! same number bit for bit; only a magnet that arrived at least a millionth of its duration
//! ago is put at its path end without calling its speed law (the law's own clamp puts it
//! there too).

use kurbo::Point;

use crate::engine::fold_law::fold_angle_from;
use crate::engine::run_state::RunState;
use crate::engine::speed::Motion;
use crate::kinematics::joint_transform;
use crate::magnet_path::MagnetPath;
use crate::physics::{along_path, reach, ForceLaw, Pole};
use crate::tile_frame::TileFrame;
use crate::timeline::{FoldRecord, Geometry};
use crate::Pose;

/// A magnet counts as arrived (at its path end, its speed law not asked) once this fraction
/// of its duration has passed after its arrival: 1e-6, far above the law's rounding near the
/// end, far below any time the rule resolves.
pub(super) const ARRIVED_MARGIN: f64 = 1e-6;

/// One magnet within reach.
#[derive(Clone, Copy, Debug)]
struct Source {
    path: MagnetPath,
    motion: Motion,
    /// Start, s (`None`: not started, at rest for the whole search).
    start: Option<f64>,
    /// After this time it is at its path end.
    settled: f64,
    moment: f64,
    /// Tile offset from the window's first tile.
    tile: usize,
    /// Last travel (mm) and the point there (tile frame).
    travel: f64,
    local: (f64, f64),
}

/// One joint within the window.
#[derive(Clone, Copy, Debug)]
struct Joint<'a> {
    fold: Option<&'a FoldRecord>,
    angle: f64,
    transform: Pose,
}

/// Magnet `m`'s neighbourhood, ready to give the drive on `m` at any time of its search.
pub(super) struct Neighbourhood<'a> {
    progress: RunState<'a>,
    law: ForceLaw,
    w: f64,
    m: usize,
    /// First magnet within reach.
    lo: usize,
    sources: Vec<Source>,
    joints: Vec<Joint<'a>>,
    /// Each tile's pose in the window's frame, with the sine and cosine of its angle.
    frames: Vec<TileFrame>,
    /// The RI (tile 0's frame) when within reach: position and moment.
    ri: Option<(Point, f64)>,
    /// `m`'s path direction at its rest point, tile frame.
    tangent: (f64, f64),
    /// Whether every time so far has been evaluated once (the caches are primed).
    primed: bool,
}

impl<'a> Neighbourhood<'a> {
    /// The neighbourhood of magnet `m` within `cutoff` in chain index.
    pub(super) fn new(
        geometry: &'a Geometry,
        progress: RunState<'a>,
        law: ForceLaw,
        cutoff: usize,
        m: usize,
    ) -> Neighbourhood<'a> {
        let g = geometry;
        let within = reach(m, cutoff, g.magnets());
        let (lo, hi) = (*within.start(), *within.end());
        let (tlo, thi) = (lo / 2, hi / 2);
        let sources = (lo..=hi)
            .map(|k| {
                let motion = *progress.motion(k);
                let start = progress.start_of(k);
                let settled = start.map_or(f64::INFINITY, |s| {
                    s + motion.duration() * (1.0 + ARRIVED_MARGIN)
                });
                let path = *g.path(k);
                Source {
                    path,
                    motion,
                    start,
                    settled,
                    moment: g.design(k / 2).moment(),
                    tile: k / 2 - tlo,
                    travel: 0.0,
                    local: path.point_at(0.0),
                }
            })
            .collect();
        let joints = (tlo..thi)
            .map(|j| Joint {
                fold: progress.fold_at(j),
                angle: 0.0,
                transform: joint_transform(0.0, g.w),
            })
            .collect();
        let ri = (m < cutoff).then(|| {
            let ri = g.ri();
            (ri.position, ri.moment)
        });
        Neighbourhood {
            progress,
            law,
            w: g.w,
            m,
            lo,
            sources,
            joints,
            frames: vec![TileFrame::IDENTITY; thi - tlo + 1],
            ri,
            tangent: g.path(m).tangent_at(0.0),
            primed: false,
        }
    }

    /// The travel of source `i` at `t`, as [`RunState::travel_at`] gives it.
    fn travel(&self, i: usize, t: f64) -> f64 {
        let s = &self.sources[i];
        if self.progress.solved.is_some() {
            return self.progress.travel_at(self.lo + i, t);
        }
        match s.start {
            None => 0.0,
            Some(_) if t >= s.settled => s.motion.length,
            Some(start) if t > start => s.motion.distance_at(t - start),
            Some(_) => 0.0,
        }
    }

    /// The force (N) along magnet `m`'s path at its rest point at time `t`, from every
    /// magnet within the cutoff (and the RI while within reach), each where the run has it.
    pub(super) fn drive(&mut self, t: f64) -> f64 {
        let first = !self.primed;
        self.primed = true;
        for i in 0..self.sources.len() {
            let u = self.travel(i, t);
            let s = &mut self.sources[i];
            if first || u.to_bits() != s.travel.to_bits() {
                s.travel = u;
                s.local = s.path.point_at(u);
            }
        }
        // joint angles, and the poses from the first joint that turned
        let mut changed = if first { Some(0) } else { None };
        for n in 0..self.joints.len() {
            let angle = self.joint_angle(n, t);
            let joint = &mut self.joints[n];
            if first || angle.to_bits() != joint.angle.to_bits() {
                joint.angle = angle;
                joint.transform = joint_transform(angle, self.w);
                changed.get_or_insert(n);
            }
        }
        if let Some(from) = changed {
            for n in from..self.joints.len() {
                let pose = self.frames[n].to_pose().then(&self.joints[n].transform);
                self.frames[n + 1] = TileFrame::from_pose(&pose);
            }
        }
        let at = |s: &Source| self.frames[s.tile].point(s.local);
        let on = Pole::Magnet(self.m);
        let target = &self.sources[self.m - self.lo];
        let pm = at(target);
        let tangent = self.frames[target.tile].vector(self.tangent);
        let mm = target.moment;
        let mut drive = 0.0;
        // the order of `neighbours`: the magnets in chain order, then the RI
        let magnets = (self.lo..self.lo + self.sources.len())
            .filter(|&k| k != self.m)
            .map(Pole::Magnet);
        for source in magnets.chain(self.ri.is_some().then_some(Pole::Ri)) {
            let (p, moment) = match source {
                Pole::Magnet(k) => {
                    let s = &self.sources[k - self.lo];
                    (at(s), s.moment)
                }
                Pole::Ri => match self.ri {
                    // the RI is fixed in tile 0's frame, the window's first
                    Some((p, moment)) => (self.frames[0].point(p.into()), moment),
                    None => continue,
                },
            };
            let force = self.law.force(p, pm, moment, mm, source.attracts(on));
            drive += along_path(force, tangent);
        }
        drive
    }

    /// The angle of the window's joint `n` at `t`, as [`RunState::joint_angle`] gives it,
    /// from the travels just computed.
    fn joint_angle(&self, n: usize, t: f64) -> f64 {
        let Some(fold) = self.joints[n].fold else {
            return 0.0;
        };
        if self.progress.solved.is_some() {
            return self.progress.joint_angle(fold.joint, t);
        }
        if t <= fold.start || t >= fold.end {
            return fold_angle_from(fold, t, 0.0, 0.0);
        }
        let frac = |k: usize| {
            let s = &self.sources[k - self.lo];
            s.travel / s.motion.length
        };
        fold_angle_from(fold, t, frac(2 * fold.joint + 1), frac(2 * fold.joint + 2))
    }
}
