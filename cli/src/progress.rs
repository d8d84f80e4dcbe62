//! Progress of long runs on stderr.
//!
//! On a terminal a bar appears once a run has taken more than a second. When stderr is not a
//! terminal (a pipe, a log file, a batch job) a plain line is printed at most every
//! [`PLAIN_INTERVAL`]: what is done, the rate and the time left at that rate, so a long run is
//! never silent. `--quiet` silences both.

use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::errln;

/// The least time between two plain progress lines (the environment variable
/// `FOLDCHAIN_PROGRESS_SECONDS` sets another, e.g. for tests).
pub const PLAIN_INTERVAL: Duration = Duration::from_secs(5);

fn plain_interval() -> Duration {
    std::env::var("FOLDCHAIN_PROGRESS_SECONDS")
        .ok()
        .and_then(|v| v.parse::<f64>().ok())
        .filter(|v| v.is_finite() && *v >= 0.0)
        .map_or(PLAIN_INTERVAL, Duration::from_secs_f64)
}

/// Where progress goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProgressMode {
    /// A bar on the terminal, after a second.
    Bar,
    /// Plain lines at most every [`PLAIN_INTERVAL`].
    Lines,
    /// Nothing.
    Quiet,
}

impl ProgressMode {
    /// The bar on a terminal, plain lines otherwise, nothing when `quiet`.
    pub fn detect(quiet: bool) -> ProgressMode {
        if quiet {
            ProgressMode::Quiet
        } else if std::io::stderr().is_terminal() {
            ProgressMode::Bar
        } else {
            ProgressMode::Lines
        }
    }
}

#[derive(Debug)]
struct Plain {
    last: Option<Instant>,
}

/// A progress reporter, safe to call from several threads.
#[derive(Debug)]
pub struct Progress {
    tool: String,
    unit: String,
    mode: ProgressMode,
    bar: ProgressBar,
    start: Instant,
    shown: Mutex<bool>,
    plain: Mutex<Plain>,
    interval: Duration,
}

impl Progress {
    /// A reporter for `tool`, counting `unit`s (e.g. `parts`, `frames`).
    pub fn new(tool: &str, unit: &str, mode: ProgressMode) -> Progress {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        let template =
            format!("{{msg}} [{{bar:40}}] {{pos}}/{{len}} {unit}, {{elapsed}} (eta {{eta}})");
        if let Ok(style) = ProgressStyle::with_template(&template) {
            bar.set_style(style.progress_chars("=> "));
        }
        Progress {
            tool: tool.to_string(),
            unit: unit.to_string(),
            mode,
            bar,
            start: Instant::now(),
            shown: Mutex::new(false),
            plain: Mutex::new(Plain { last: None }),
            interval: plain_interval(),
        }
    }

    /// `done` of `total` units of the stage `stage`.
    pub fn update(&self, stage: &str, done: u64, total: u64) {
        match self.mode {
            ProgressMode::Quiet => {}
            ProgressMode::Bar => {
                if let Ok(mut shown) = self.shown.lock() {
                    if !*shown && self.start.elapsed() > Duration::from_secs(1) {
                        *shown = true;
                        self.bar.set_draw_target(ProgressDrawTarget::stderr());
                    }
                }
                self.bar.set_message(stage.to_string());
                self.bar.set_length(total);
                self.bar.set_position(done);
            }
            ProgressMode::Lines => {
                let Ok(mut plain) = self.plain.lock() else {
                    return;
                };
                let now = Instant::now();
                let due = match plain.last {
                    None => now.duration_since(self.start) >= self.interval,
                    Some(t) => now.duration_since(t) >= self.interval,
                };
                if due && done < total {
                    plain.last = Some(now);
                    errln!(
                        "{}",
                        self.line(stage, done, total, now.duration_since(self.start))
                    );
                }
            }
        }
    }

    /// The plain progress line.
    fn line(&self, stage: &str, done: u64, total: u64, elapsed: Duration) -> String {
        let secs = elapsed.as_secs_f64().max(1e-9);
        let rate = done as f64 / secs;
        let left = if done > 0 {
            format!(
                ", about {} left",
                duration_words((total - done) as f64 / rate)
            )
        } else {
            String::new()
        };
        format!(
            "{}: {stage}: {done}/{total} {} ({:.0}%), {:.1} {}/s, {} so far{left}",
            self.tool,
            self.unit,
            100.0 * done as f64 / total.max(1) as f64,
            rate,
            self.unit,
            duration_words(secs),
        )
    }

    /// Clears the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

/// A duration in words: `42 s`, `3.5 min`, `2.1 h`, `4.0 days`.
pub fn duration_words(secs: f64) -> String {
    if secs < 90.0 {
        format!("{secs:.0} s")
    } else if secs < 5400.0 {
        format!("{:.1} min", secs / 60.0)
    } else if secs < 172_800.0 {
        format!("{:.1} h", secs / 3600.0)
    } else {
        format!("{:.1} days", secs / 86_400.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_lines_say_done_rate_and_time_left() {
        let p = Progress::new("fold-enum", "parts", ProgressMode::Lines);
        let line = p.line("counting", 10, 40, Duration::from_secs(20));
        assert_eq!(
            line,
            "fold-enum: counting: 10/40 parts (25%), 0.5 parts/s, 20 s so far, about 60 s left"
        );
        assert_eq!(duration_words(7200.0), "2.0 h");
    }
}
