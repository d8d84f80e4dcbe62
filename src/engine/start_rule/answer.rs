//! What the force rule answers for one magnet: when it starts, or that it never does.

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

impl ForceStart {
    /// The same answer with its time moved by `dt`.
    pub(super) fn shifted(self, dt: f64) -> ForceStart {
        match self {
            ForceStart::At(t) => ForceStart::At(t + dt),
            ForceStart::Never { time, drive } => ForceStart::Never {
                time: time + dt,
                drive,
            },
        }
    }
}
