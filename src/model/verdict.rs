//! How a reference run ended, from the modes and state it came to rest in. Completed when
//! every magnet but the last arrived or was passed by propagation, and every folding joint
//! closed. A magnet is passed when it came to rest mid-path at a rigid joint while its
//! partner across the joint arrived: a curved path paired with a straight one (thesis 7.3.2,
//! SL-SR-SL) ends at its point of closest approach to the straight partner, not at its path
//! end, and propagation goes on through the partner. Otherwise the first
//! joint left open (or holding a magnet that never arrived) is named: inhibited when its
//! pair's path ends lie farther apart than the pair at rest (the geometry of Table 7.1's LR
//! and RL), stalled otherwise, with what the dynamics left.

use crate::model::{Mode, Model};
use crate::timeline::{joint_of_magnet, Outcome};

/// The end of a run: its modes, state and drives there.
pub(crate) struct RestState<'a> {
    pub(crate) model: &'a Model,
    pub(crate) modes: &'a [Mode],
    pub(crate) y: &'a [f64],
    pub(crate) drive: &'a [f64],
}

/// Where a run that neither completed nor was inhibited stalled (see [`RestState::ending`]).
pub(crate) struct Stall {
    /// The first magnet (but the last) that neither arrived nor was passed.
    pub(crate) unarrived: Option<usize>,
    /// The first folding joint left open.
    pub(crate) open: Option<usize>,
    /// The joint named: the first joint of the two above.
    pub(crate) joint: usize,
}

impl RestState<'_> {
    /// How a run of `model` ended at `time`, read from each magnet's mode `magnet_mode(k)` and
    /// each folding joint's mode `joint_mode(j)` (`None`: no mode known): the one verdict of
    /// the reference and the engine (see the module's opening); a stalled run's reason in
    /// words from `reason`.
    pub(crate) fn ending(
        model: &Model,
        magnet_mode: impl Fn(usize) -> Option<Mode>,
        joint_mode: impl Fn(usize) -> Option<Mode>,
        time: f64,
        reason: impl FnOnce(&Stall) -> String,
    ) -> Outcome {
        let g = &model.geometry;
        let n = g.magnets();
        // passed: at rest mid-path at a rigid joint while its partner across the joint
        // (magnet `k + 1` for odd `k`, `k - 1` for even) arrived
        let passed = |k: usize| {
            let j = joint_of_magnet(k);
            let rigid = j + 1 >= g.tiles() || model.joint_var(j).is_none();
            let partner = if k % 2 == 1 { k + 1 } else { k.wrapping_sub(1) };
            rigid
                && k > 0
                && partner < n
                && magnet_mode(k) == Some(Mode::Free)
                && magnet_mode(partner) == Some(Mode::AtEnd)
        };
        let unarrived =
            (0..n.saturating_sub(1)).find(|&k| magnet_mode(k) != Some(Mode::AtEnd) && !passed(k));
        let open = (0..g.tiles().saturating_sub(1))
            .find(|&j| model.joint_var(j).is_some() && joint_mode(j) != Some(Mode::AtEnd));
        let joint = match (unarrived.map(joint_of_magnet), open) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        let Some(j) = joint else {
            return Outcome::Completed;
        };
        let (diverges, end, rest) = if j + 1 < g.tiles() {
            g.pair_diverges(j)
        } else {
            (false, 0.0, 0.0)
        };
        if diverges {
            return Outcome::Inhibited {
                joint: j,
                time,
                end_distance_mm: end,
                rest_distance_mm: rest,
            };
        }
        let never = (0..n.saturating_sub(1))
            .find(|&k| magnet_mode(k) == Some(Mode::AtStart))
            .unwrap_or(n.saturating_sub(1));
        let stall = Stall {
            unarrived,
            open,
            joint: j,
        };
        Outcome::Stalled {
            joint: j,
            time,
            magnet: never,
            reason: reason(&stall),
        }
    }

    /// The outcome, dated `time` (the last event).
    pub(crate) fn outcome(&self, time: f64) -> Outcome {
        let m = self.model;
        let magnet_mode = |k: usize| Some(self.modes[m.magnet_var(k)]);
        let joint_mode = |j: usize| m.joint_var(j).map(|v| self.modes[v]);
        RestState::ending(m, magnet_mode, joint_mode, time, |stall| {
            self.stall_reason(stall.unarrived, stall.open, stall.joint)
        })
    }

    fn stall_reason(&self, unarrived: Option<usize>, open: Option<usize>, j: usize) -> String {
        let m = self.model;
        if let Some(k) = unarrived.filter(|&k| joint_of_magnet(k) == j) {
            let v = m.magnet_var(k);
            let len = m.path_length(k);
            let drive = self.drive[v];
            return match self.modes[v] {
                Mode::AtStart => format!(
                    "magnet {k} never started: the force along its path stays {drive:.3e} N (towards its rest point) once every magnet before it has stopped (reference dynamics)"
                ),
                _ => format!(
                    "magnet {k} came to rest {:.4} mm along its {len:.4} mm path, the forces along it balanced ({drive:.3e} N): it cannot reach the point that starts the next magnet (reference dynamics)",
                    self.y[v] * len
                ),
            };
        }
        if let Some(jj) = open {
            if let Some(v) = m.joint_var(jj) {
                return format!(
                    "joint {jj} stopped at {:.2} degrees, its torque balanced ({:.3e} N m) before the walls close it (reference dynamics)",
                    self.y[v] * 90.0,
                    self.drive[v]
                );
            }
        }
        format!("propagation stopped at joint {j} (reference dynamics)")
    }
}

/// The balance a run could not decide within its work budget, in words: of the unknowns
/// `free` (state index, fraction of its range, drive along it), the one whose net drive is
/// the smallest fraction of its scale (the bonded rest force or torque), where it is and that
/// margin. Said when a run ends `undecided` ([`crate::timeline::RunResult::Undecided`]): a
/// magnet or fold creeping towards a balance that it neither passes nor settles on within the
/// budget, so the run can say neither `completed` nor `stalled`.
pub(crate) fn undecided_margin(
    model: &Model,
    free: impl IntoIterator<Item = (usize, f64, f64)>,
) -> String {
    let nearest = free
        .into_iter()
        .map(|(i, y, drive)| (i, y, drive, drive / model.drive_scale(i)))
        .min_by(|a, b| a.3.abs().total_cmp(&b.3.abs()));
    let Some((i, y, drive, margin)) = nearest else {
        return "nothing was moving".to_string();
    };
    match model.unknowns[i] {
        crate::model::Unknown::Magnet(k) => {
            let len = model.path_length(k);
            format!(
                "magnet {k} is {:.4} mm along its {len:.4} mm path, the net force along it {drive:.3e} N, a margin of {margin:.2e} of the bonded rest force",
                y.clamp(0.0, 1.0) * len
            )
        }
        crate::model::Unknown::Joint(j) => format!(
            "joint {j} is at {:.3} degrees, its net torque {drive:.3e} N m, a margin of {margin:.2e} of the bonded rest torque",
            y.clamp(0.0, 1.0) * 90.0
        ),
    }
}
