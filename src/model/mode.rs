//! Where each unknown of the model is held ([`Mode`]): at its start, free, or at its end, and
//! when it switches (the model's event conditions).

use crate::model::Model;

/// Where an unknown is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mode {
    /// Held at 0 (magnet at rest, joint straight).
    AtStart,
    /// Moving freely inside `(0, 1)`.
    Free,
    /// Held at 1 (magnet arrived, joint closed by its walls).
    AtEnd,
}

/// The mode unknown `i` switches to from `mode` at value `y` under `drive`, if it switches: a
/// clamped unknown driven off its end (harder than its threshold), a free one reaching an
/// end of its range.
pub(crate) fn condition(model: &Model, i: usize, mode: Mode, y: f64, drive: f64) -> Option<Mode> {
    match mode {
        Mode::AtStart if drive > model.threshold(i) => Some(Mode::Free),
        Mode::AtEnd if -drive > model.threshold(i) => Some(Mode::Free),
        Mode::Free if y >= 1.0 => Some(Mode::AtEnd),
        Mode::Free if y <= 0.0 => Some(Mode::AtStart),
        _ => None,
    }
}
