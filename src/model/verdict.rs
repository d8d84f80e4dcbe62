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

impl RestState<'_> {
    /// The outcome, dated `time` (the last event).
    pub(crate) fn outcome(&self, time: f64) -> Outcome {
        let m = self.model;
        let n = m.geometry.magnets();
        let unarrived = (0..n.saturating_sub(1))
            .find(|&k| self.modes[m.magnet_var(k)] != Mode::AtEnd && !self.passed(k));
        let open = (0..m.geometry.tiles().saturating_sub(1))
            .find(|&j| m.joint_var(j).is_some_and(|v| self.modes[v] != Mode::AtEnd));
        let joint = match (unarrived.map(joint_of_magnet), open) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        let Some(j) = joint else {
            return Outcome::Completed;
        };
        let (diverges, end, rest) = if j + 1 < m.geometry.tiles() {
            m.geometry.pair_diverges(j)
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
            .find(|&k| self.modes[m.magnet_var(k)] == Mode::AtStart)
            .unwrap_or(n.saturating_sub(1));
        Outcome::Stalled {
            joint: j,
            time,
            magnet: never,
            reason: self.stall_reason(unarrived, open, j),
        }
    }

    /// Whether magnet `k` rests mid-path at a rigid joint while its partner across the
    /// joint (magnet `k + 1` for odd `k`, `k - 1` for even) arrived.
    fn passed(&self, k: usize) -> bool {
        let m = self.model;
        let n = m.geometry.magnets();
        let j = joint_of_magnet(k);
        let rigid = j + 1 >= m.geometry.tiles() || m.joint_var(j).is_none();
        let partner = if k % 2 == 1 { k + 1 } else { k.wrapping_sub(1) };
        rigid
            && k > 0
            && partner < n
            && self.modes[m.magnet_var(k)] == Mode::Free
            && self.modes[m.magnet_var(partner)] == Mode::AtEnd
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
