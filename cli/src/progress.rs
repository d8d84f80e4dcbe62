//! Progress of long runs on stderr, the same in every tool.
//!
//! On a terminal a bar (or, for a stage that cannot count its work, a spinner) appears once a
//! run has taken more than a second, and is cleared before the result is printed
//! ([`Progress::finish`]). When stderr is not a terminal (a pipe, a log file, a batch job) a
//! plain line is printed after [`FIRST_LINE`] and then at most every [`PLAIN_INTERVAL`]: the
//! stage, what is done, the rate and the time left at that rate, or for a stage that cannot
//! count, how long it has run; so a long run is never silent. A thread of its own prints
//! them, so a stage that reports nothing (one long library call) is still heard from.
//! `--quiet` silences both.
//!
//! [`Progress`] is a [`foldchain::Progress`]: the libraries' callbacks report into it.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::errln;
use crate::numbers::thousands;

/// The least time between two plain progress lines (the environment variable
/// `FOLDCHAIN_PROGRESS_SECONDS` sets another, and the first line's time too, e.g. for tests;
/// `0` prints every update as it comes).
pub const PLAIN_INTERVAL: Duration = Duration::from_secs(5);

/// When the first plain line is printed: a run shorter than this says nothing.
pub const FIRST_LINE: Duration = Duration::from_secs(2);

fn env_interval() -> Option<Duration> {
    std::env::var("FOLDCHAIN_PROGRESS_SECONDS")
        .ok()
        .and_then(|v| v.parse::<f64>().ok())
        .filter(|v| v.is_finite() && *v >= 0.0 && *v < 1e6)
        .map(Duration::from_secs_f64)
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

/// What the run is doing now.
#[derive(Debug)]
struct State {
    stage: String,
    unit: String,
    done: u64,
    total: u64,
    stage_start: Instant,
    last_line: Option<Instant>,
}

#[derive(Debug)]
struct Shared {
    tool: String,
    unit: String,
    mode: ProgressMode,
    bar: ProgressBar,
    start: Instant,
    first: Duration,
    interval: Duration,
    state: Mutex<State>,
    stop: AtomicBool,
}

/// A progress reporter, safe to call from several threads; see the module documentation.
#[derive(Debug)]
pub struct Progress {
    shared: Arc<Shared>,
    ticker: Mutex<Option<JoinHandle<()>>>,
}

impl Progress {
    /// A reporter for `tool`, counting `unit`s by default (e.g. `parts`, `samples`).
    pub fn new(tool: &str, unit: &str, mode: ProgressMode) -> Progress {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        let (first, interval) = match env_interval() {
            Some(t) => (t, t),
            None => (FIRST_LINE, PLAIN_INTERVAL),
        };
        let now = Instant::now();
        let shared = Arc::new(Shared {
            tool: tool.to_string(),
            unit: unit.to_string(),
            mode,
            bar,
            start: now,
            first,
            interval,
            state: Mutex::new(State {
                stage: String::new(),
                unit: unit.to_string(),
                done: 0,
                total: 0,
                stage_start: now,
                last_line: None,
            }),
            stop: AtomicBool::new(false),
        });
        let ticker = (mode != ProgressMode::Quiet).then(|| {
            let shared = Arc::clone(&shared);
            std::thread::spawn(move || tick(&shared))
        });
        Progress {
            shared,
            ticker: Mutex::new(ticker),
        }
    }

    /// A reporter that says nothing.
    pub fn quiet() -> Progress {
        Progress::new("", "", ProgressMode::Quiet)
    }

    /// Begins a stage that cannot count its work (one long library call): the display says
    /// how long it has run.
    pub fn stage(&self, stage: &str) {
        self.set(stage, None, 0, 0);
    }

    /// `done` of `total` units of the stage `stage`, in the reporter's unit.
    pub fn update(&self, stage: &str, done: u64, total: u64) {
        self.set(stage, None, done, total);
    }

    /// `done` of `total` `unit`s of the stage `stage`.
    pub fn update_in(&self, stage: &str, unit: &str, done: u64, total: u64) {
        self.set(stage, Some(unit), done, total);
    }

    fn set(&self, stage: &str, unit: Option<&str>, done: u64, total: u64) {
        if self.shared.mode == ProgressMode::Quiet {
            return;
        }
        let Ok(mut s) = self.shared.state.lock() else {
            return;
        };
        if s.stage != stage {
            s.stage = stage.to_string();
            s.stage_start = Instant::now();
        }
        s.unit = unit.unwrap_or(&self.shared.unit).to_string();
        s.done = done;
        s.total = total;
        // `FOLDCHAIN_PROGRESS_SECONDS=0`: every update is a line, printed here (the display's
        // thread looks only every tenth of a second and would miss a run shorter than that)
        if self.shared.mode == ProgressMode::Lines && self.shared.interval.is_zero() {
            let now = Instant::now();
            s.last_line = Some(now);
            errln!("{}", line(&self.shared.tool, &s, now));
        }
    }

    /// Stops the display and clears the bar: call it before printing the result.
    pub fn finish(&self) {
        self.shared.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.ticker.lock().ok().and_then(|mut t| t.take()) {
            t.thread().unpark();
            let _ = t.join();
        }
        self.shared.bar.finish_and_clear();
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}

impl foldchain::Progress for Progress {
    fn update(&self, stage: &str, done: u64, total: u64) {
        Progress::update(self, stage, done, total);
    }
}

/// The display's own thread: every tenth of a second, the bar; plain lines when due.
fn tick(shared: &Shared) {
    let mut shown = false;
    while !shared.stop.load(Ordering::Relaxed) {
        std::thread::park_timeout(Duration::from_millis(100));
        if shared.stop.load(Ordering::Relaxed) {
            break;
        }
        let now = Instant::now();
        let Ok(mut s) = shared.state.lock() else {
            break;
        };
        if s.stage.is_empty() {
            continue;
        }
        match shared.mode {
            ProgressMode::Quiet => break,
            ProgressMode::Bar => {
                if !shown {
                    if now.duration_since(shared.start) < Duration::from_secs(1) {
                        continue;
                    }
                    shown = true;
                    shared.bar.set_draw_target(ProgressDrawTarget::stderr());
                }
                let counted = s.total > 1;
                let template = if counted {
                    format!(
                        "{{msg}} [{{bar:40}}] {{pos}}/{{len}} {}, {{elapsed}} (eta {{eta}})",
                        s.unit
                    )
                } else {
                    "{spinner} {msg}, {elapsed}".to_string()
                };
                if let Ok(style) = ProgressStyle::with_template(&template) {
                    shared.bar.set_style(style.progress_chars("=> "));
                }
                shared
                    .bar
                    .set_message(format!("{}: {}", shared.tool, s.stage));
                if counted {
                    shared.bar.set_length(s.total);
                    shared.bar.set_position(s.done);
                } else {
                    shared.bar.tick();
                }
            }
            ProgressMode::Lines => {
                let due = match s.last_line {
                    None => now.duration_since(shared.start) >= shared.first,
                    Some(t) => now.duration_since(t) >= shared.interval,
                };
                if due {
                    s.last_line = Some(now);
                    errln!("{}", line(&shared.tool, &s, now));
                }
            }
        }
    }
}

/// The plain progress line.
fn line(tool: &str, s: &State, now: Instant) -> String {
    let secs = now.duration_since(s.stage_start).as_secs_f64().max(1e-9);
    if s.total <= 1 {
        return format!("{tool}: {}: {} so far", s.stage, duration_words(secs));
    }
    let rate = s.done as f64 / secs;
    let left = if s.done > 0 && s.done < s.total {
        format!(
            ", about {} left",
            duration_words((s.total - s.done) as f64 / rate)
        )
    } else {
        String::new()
    };
    format!(
        "{tool}: {}: {}/{} {} ({:.0}%), {} {}/s, {} so far{left}",
        s.stage,
        thousands(s.done),
        thousands(s.total),
        s.unit,
        100.0 * s.done as f64 / s.total as f64,
        rate_words(rate),
        s.unit,
        duration_words(secs),
    )
}

/// A rate in three significant digits: `0.5`, `12.3`, `4560`.
fn rate_words(rate: f64) -> String {
    if rate >= 100.0 {
        format!("{rate:.0}")
    } else if rate >= 1.0 {
        format!("{rate:.1}")
    } else {
        format!("{rate:.2}")
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

    fn state(stage: &str, done: u64, total: u64, start: Instant) -> State {
        State {
            stage: stage.into(),
            unit: "parts".into(),
            done,
            total,
            stage_start: start,
            last_line: None,
        }
    }

    #[test]
    fn plain_lines_say_done_rate_and_time_left() {
        let start = Instant::now();
        let now = start + Duration::from_secs(20);
        let l = line("fold-enum", &state("counting", 10, 40, start), now);
        assert_eq!(
            l,
            "fold-enum: counting: 10/40 parts (25%), 0.50 parts/s, 20 s so far, about 60 s left"
        );
        let l = line("fold-run", &state("event engine", 0, 0, start), now);
        assert_eq!(l, "fold-run: event engine: 20 s so far");
        assert_eq!(duration_words(7200.0), "2.0 h");
    }
}
